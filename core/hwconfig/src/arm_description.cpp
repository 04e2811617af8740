#include "rover/hwconfig/arm_description.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"
#include "rover/base/units.hpp"

namespace rover::hwconfig {
namespace {

Eigen::Vector3d InPlane(double azimuth, double angle) {
  return {std::cos(angle) * std::cos(azimuth), std::cos(angle) * std::sin(azimuth), std::sin(angle)};
}

std::string Point(const Eigen::Vector3d& p) {
  return "(" + FormatNumber(p.x()) + ", " + FormatNumber(p.y()) + ", " + FormatNumber(p.z()) + ")";
}

}  // namespace

const char* ArmJointName(int joint) {
  static constexpr const char* kNames[kArmJoints] = {"azimuth", "shoulder", "elbow", "wrist"};
  return joint >= 0 && joint < kArmJoints ? kNames[joint] : "?";
}

Eigen::Isometry3d ArmDescription::ImagerPose(const ArmAngles& q) const {
  const ArmPoints p = Forward(q);
  const Eigen::Vector3d h(-std::sin(q[0]), std::cos(q[0]), 0.0);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear().col(0) = h;
  pose.linear().col(1) = p.look.cross(h).normalized();
  pose.linear().col(2) = p.look;
  pose.translation() = p.face;
  return pose;
}

double MicroscopeOptics::BlurDiameterPx(double distance) const {
  const double s = working_distance;
  return focal_px * aperture * std::abs(distance - s) / (distance * s);
}

double MicroscopeOptics::DepthOfFieldHalf() const {
  // c(d) = k (s - d) / (d s) on the near side, k = focal_px * aperture: solve c = c_max.
  const double s = working_distance, k = focal_px * aperture;
  const double d = k * s / (k + max_sharp_blur_px * s);
  return s - d;
}

Status ArmDescription::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckAllInRange("arm.shoulder", std::span<const double>(shoulder.data(), 3),
                                        Bounds::Closed(-10, 10), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("arm.upper_arm", upper_arm, Bounds::OpenLow(0.0, 2.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("arm.forearm", forearm, Bounds::OpenLow(0.0, 2.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("arm.tool_length", tool_length, Bounds::OpenLow(0.0, 2.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("arm.link_radius", link_radius, 0.0, 0.2, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("arm.clearance", clearance, 0.0, 0.2, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("arm.face_radius", face_radius, 0.0, 0.2, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("arm.contact_standoff", contact_standoff, 0.0, 0.02, "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("arm.imager.image_size", imager.image_size, 16, 2048));
  ROVER_RETURN_IF_ERROR(
      CheckRange("arm.imager.focal_px", imager.focal_px, Bounds::OpenLow(0.0, 1e5), "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("arm.imager.working_distance", imager.working_distance,
                                   Bounds::OpenLow(0.0, 0.5), "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("arm.imager.aperture", imager.aperture, Bounds::OpenLow(0.0, 0.05), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("arm.imager.max_sharp_blur_px", imager.max_sharp_blur_px,
                                   Bounds::OpenLow(0.0, 20.0), "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("arm.check_step", check_step, Bounds::OpenLow(0.0, 0.2), "rad"));
  for (int j = 0; j < kArmJoints; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const std::string n = std::string("arm.") + ArmJointName(j);
    ROVER_RETURN_IF_ERROR(CheckRange(n + ".min_angle", min_angle[k], -kPi - 0.1, kPi + 0.1, "rad"));
    ROVER_RETURN_IF_ERROR(CheckRange(n + ".max_angle", max_angle[k], -kPi - 0.1, kPi + 0.1, "rad"));
    if (!(min_angle[k] < max_angle[k])) {
      return InvalidArgument(Describe(n + ".min_angle", min_angle[k], "rad") +
                             " must be below max_angle " + FormatNumber(max_angle[k]));
    }
  }
  const Status st = CheckLimits(stow);
  if (!st.ok()) return InvalidArgument("arm.stow: " + st.message());
  return Status::Ok();
}

Status ArmDescription::CheckLimits(const ArmAngles& q) const {
  for (int j = 0; j < kArmJoints; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const std::string n = std::string(ArmJointName(j)) + " angle";
    if (!std::isfinite(q[k])) return InvalidArgument(Describe(n, q[k], "rad") + " (must be finite)");
    ROVER_RETURN_IF_ERROR(CheckRange(n, q[k], min_angle[k], max_angle[k], "rad"));
  }
  return Status::Ok();
}

ArmPoints ArmDescription::Forward(const ArmAngles& q) const {
  ArmPoints p;
  p.shoulder = shoulder;
  p.elbow = p.shoulder + upper_arm * InPlane(q[0], q[1]);
  p.wrist = p.elbow + forearm * InPlane(q[0], q[1] + q[2]);
  p.look = InPlane(q[0], q[1] + q[2] + q[3]);
  p.face = p.wrist + tool_length * p.look;
  return p;
}

Result<ArmAngles> ArmDescription::FaceDown(const Eigen::Vector3d& face) const {
  if (!face.allFinite()) return InvalidArgument("arm target " + Point(face) + " is not finite");
  const Eigen::Vector3d w = face + Eigen::Vector3d(0.0, 0.0, tool_length);
  const Eigen::Vector2d horizontal = (w - shoulder).head<2>();
  const double r = horizontal.norm();
  const double z = w.z() - shoulder.z();
  if (r < 1e-3) {
    return OutOfRange("arm target " + Point(face) + " [m] lies on the arm's azimuth axis");
  }
  const double reach = std::hypot(r, z);
  if (reach > upper_arm + forearm - 1e-6) {
    return OutOfRange("arm target " + Point(face) + " [m] is out of reach: the wrist would be " +
                      FormatNumber(reach) + " m from the shoulder, at most " +
                      FormatNumber(upper_arm + forearm));
  }
  if (reach < std::abs(upper_arm - forearm) + 1e-6) {
    return OutOfRange("arm target " + Point(face) + " [m] is too near the shoulder (" +
                      FormatNumber(reach) + " m)");
  }
  const double c2 =
      std::clamp((reach * reach - upper_arm * upper_arm - forearm * forearm) / (2.0 * upper_arm * forearm),
                 -1.0, 1.0);
  ArmAngles q;
  q[0] = std::atan2(horizontal.y(), horizontal.x());
  q[2] = -std::acos(c2);
  q[1] = std::atan2(z, r) + std::atan2(forearm * std::sin(-q[2]), upper_arm + forearm * std::cos(q[2]));
  q[3] = -0.5 * kPi - q[1] - q[2];
  const Status st = CheckLimits(q);
  if (!st.ok()) return OutOfRange("arm target " + Point(face) + " [m] needs " + st.message());
  return q;
}

}  // namespace rover::hwconfig
