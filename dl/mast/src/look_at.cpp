#include "rover/dl/mast/look_at.hpp"

#include <cmath>
#include <span>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"
#include "rover/base/units.hpp"

namespace rover::dl::mast {
namespace {

// Bearing errors (azimuth, elevation) [rad] of rover-frame point q seen from the NAVCAM pair.
Eigen::Vector2d BearingError(const hwconfig::RoverDescription& rover, const PanTilt& a,
                             const Eigen::Vector3d& q, double* forward) {
  const Eigen::Vector3d p = rover.NavcamPose(a.pan, a.tilt).inverse() * q;
  if (forward != nullptr) *forward = p.x();
  return {std::atan2(p.y(), p.x()), std::atan2(p.z(), std::hypot(p.x(), p.y()))};
}

double WrapPi(double a) { return std::remainder(a, 2.0 * kPi); }

std::string DegText(double rad) { return FormatNumber(rad / kDegree, 4); }

std::string FormatPoint(const Eigen::Vector3d& p) {
  return FormatList(std::span<const double>(p.data(), 3), 4);
}

}  // namespace

Status CheckMastLimits(const PanTilt& angles, const MastOptions& limits,
                       const std::string& what_pan, const std::string& what_tilt) {
  if (!(angles.pan >= limits.pan_min && angles.pan <= limits.pan_max)) {
    return InvalidArgument(what_pan + " = " + DegText(angles.pan) + " deg, outside [" +
                           DegText(limits.pan_min) + ", " + DegText(limits.pan_max) + "] deg");
  }
  if (!(angles.tilt >= limits.tilt_min && angles.tilt <= limits.tilt_max)) {
    return InvalidArgument(what_tilt + " = " + DegText(angles.tilt) + " deg, outside [" +
                           DegText(limits.tilt_min) + ", " + DegText(limits.tilt_max) + "] deg");
  }
  return Status::Ok();
}

Result<PanTilt> LookAtAngles(const hwconfig::RoverDescription& rover,
                             const Eigen::Isometry3d& site_from_rover,
                             const Eigen::Vector3d& target_site, const MastOptions& limits) {
  const std::string name = "look_at " + FormatPoint(target_site);
  if (!target_site.allFinite()) return InvalidArgument(name + " is not finite");
  if (!site_from_rover.matrix().allFinite()) {
    return InvalidArgument("dl/pose is not finite: cannot look at " + FormatPoint(target_site));
  }
  const Eigen::Vector3d q = site_from_rover.inverse() * target_site;
  const Eigen::Vector3d h = rover.mast.pan_joint + Eigen::Vector3d(0.0, 0.0, rover.mast.head_height);
  const Eigen::Vector3d v = q - h;
  if (v.norm() < limits.min_look_distance) {
    return InvalidArgument(name + " is " + FormatNumber(v.norm(), 3) +
                           " m from the mast head, nearer than min_look_distance = " +
                           FormatNumber(limits.min_look_distance) + " m");
  }
  const double horizontal = std::hypot(v.x(), v.y());
  if (horizontal < 1e-6 * v.norm()) {
    return InvalidArgument(name + " lies on the pan axis (straight " +
                           std::string(v.z() > 0 ? "above" : "below") +
                           " the mast head): no pan points at it");
  }
  PanTilt a{WrapPi(std::atan2(v.y(), v.x()) - rover.navcam.yaw),
            std::atan2(v.z(), horizontal) + rover.navcam.depression};
  constexpr double kStep = 1e-7;
  bool converged = false;
  double forward = 0.0;
  for (int it = 0; it < 30; ++it) {
    const Eigen::Vector2d e = BearingError(rover, a, q, &forward);
    if (e.norm() < 1e-10) {
      converged = true;
      break;
    }
    Eigen::Matrix2d j;
    j.col(0) = (BearingError(rover, {a.pan + kStep, a.tilt}, q, nullptr) - e) / kStep;
    j.col(1) = (BearingError(rover, {a.pan, a.tilt + kStep}, q, nullptr) - e) / kStep;
    if (std::abs(j.determinant()) < 1e-12) break;
    const Eigen::Vector2d d = j.lu().solve(e);
    a.pan = WrapPi(a.pan - d.x());
    a.tilt -= d.y();
  }
  if (!converged || forward <= 0.0) {
    return InvalidArgument(name + ": no mast pose puts the NAVCAM boresight on it");
  }
  ROVER_RETURN_IF_ERROR(CheckMastLimits(a, limits, name + " needs pan", name + " needs tilt"));
  return a;
}

}  // namespace rover::dl::mast
