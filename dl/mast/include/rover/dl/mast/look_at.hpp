#pragma once
/// @file
/// Look-at geometry: the mast pan/tilt that puts the NAVCAM boresight on a site-frame point.
///
/// Frames (core/hwconfig rover_description.hpp):
///   site S    the dl/pose reference frame; site_from_rover is the rover pose estimate;
///   rover R   x forward, y left, z up;
///   head H    origin on the tilt axis, x boresight at pan = tilt = 0;
///               rover_from_head = T(pan_joint + (0, 0, head_height)) Rz(pan) Ry(-tilt);
///   pair P    the NAVCAM pair frame in H (x = boresight, origin midway between the cameras);
///             rover_from_pair = RoverDescription::NavcamPose(pan, tilt);
///               head_from_pair = T(navcam.position) Rz(navcam.yaw) Ry(navcam.depression).
/// The boresight is the line {o + s d : s > 0} with o the origin of P and d its x axis. The
/// camera driver moves the NAVCAM models by the same rover_from_head (ddl/camera), so a pair
/// pointed here sees the target on the boresight.
///
/// Maths. Let q = rover_from_site * target and h = pan_joint + (0, 0, head_height) (the head
/// origin, on the pan axis). When the pair origin lies on the head's x axis and yaw and
/// depression are 0 (the default rover), the answer is closed form:
///   pan  = atan2(q_y - h_y, q_x - h_x)
///   tilt = atan2(q_z - h_z, hypot(q_x - h_x, q_y - h_y)).
/// In general (an offset pair, a mount yaw or depression) these angles, corrected by -yaw and
/// +depression, start a Newton iteration on the two bearing errors of the target seen from P,
///   e = (atan2(p_y, p_x), atan2(p_z, hypot(p_x, p_y))),  p = pair_from_rover(pan, tilt) * q,
/// with a forward-difference Jacobian, until |e| < 1e-10 rad (at most 30 steps). The result
/// has the target in front of the pair (p_x > 0).
///
/// Refusals (InvalidArgument, naming the field and value): a non-finite target or pose; a
/// target nearer the head origin than min_look_distance; a target straight above or below the
/// pan axis (no pan defined); no convergence; and a pan or tilt outside the options' limits,
/// e.g. "look_at [-3, 0, 0] needs pan = 180 deg, outside [-175, 175] deg" (behind the mast).

#include <Eigen/Geometry>
#include <string>

#include "rover/base/status.hpp"
#include "rover/dl/mast/mast_options.hpp"
#include "rover/hwconfig/rover_description.hpp"

namespace rover::dl::mast {

/// Mast joint angles [rad].
struct PanTilt {
  double pan = 0.0;
  double tilt = 0.0;
};

/// The pan/tilt that puts the NAVCAM boresight on `target_site` (see the file comment).
/// Precondition: rover.Validate() and limits.Validate() hold.
Result<PanTilt> LookAtAngles(const hwconfig::RoverDescription& rover,
                             const Eigen::Isometry3d& site_from_rover,
                             const Eigen::Vector3d& target_site, const MastOptions& limits);

/// Ok when `angles` lie inside the options' pan and tilt limits; the message names `what`
/// ("pan", or "look_at (...) needs pan") and the value in degrees.
Status CheckMastLimits(const PanTilt& angles, const MastOptions& limits,
                       const std::string& what_pan, const std::string& what_tilt);

}  // namespace rover::dl::mast
