#pragma once
/// @file
/// dl/pose (dl/pose_odometry), dl/relative_pose and dl/estimator_event <-> their idlc C structs
/// (conventions: see rover/msg/camera_idl.hpp). Covariances are row-major on the wire.

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/pose.hpp"

namespace rover::msg {

/// A catalog pose (rover::Pose3: position [m], orientation w, x, y, z) as a rigid transform, the
/// quaternion normalised. Precondition: a finite, non-zero quaternion (the FromIdl functions below
/// check the norm first where the wire may carry a bad one).
Eigen::Isometry3d IsometryFromIdl(const rover_Pose3& in);
/// The rigid transform as position and unit quaternion (w >= 0 not enforced).
void IsometryToIdl(const Eigen::Isometry3d& in, rover_Pose3* out);

/// InvalidArgument "<field> = 9 is not a MotionSource (0..4)".
Result<MotionSource> MotionSourceFromIdl(const rover_dl_MotionSource& s,
                                         std::string_view field = "source");

void PoseEstimateToIdl(const PoseEstimate& in, rover_dl_PoseEstimate* out);
/// rpy from the orientation. Errors: an orientation whose norm is not within 1e-3 of 1 (or NaN).
Result<PoseEstimate> PoseEstimateFromIdl(const rover_dl_PoseEstimate& in);
/// What a pose history keeps (quaternion renormalised). Errors: as PoseEstimateFromIdl, and a
/// non-finite pose.position, velocity or odometer ("pose.position.x is nan (must be finite)").
Result<PoseSample> PoseSampleFromIdl(const rover_dl_PoseEstimate& in);
/// ZYX roll, pitch, yaw of the (normalised) orientation, healthy. Errors: a non-finite or
/// degenerate quaternion (norm outside [0.5, 2]).
Result<AttitudeSample> AttitudeSampleFromIdl(const rover_dl_PoseEstimate& in);

void RelativePoseToIdl(const RelativePose& in, rover_dl_RelativePose* out);
/// Errors: an unknown source or status value, a delta quaternion whose norm is not 1 within
/// 1e-6 (or NaN). Other non-finite values and a covariance that is not symmetric positive
/// definite are for the consumer (PoseEkf::AddRelativePose) to reject.
Result<RelativePose> RelativePoseFromIdl(const rover_dl_RelativePose& in);

/// Precondition: in.client has 1..63 characters.
void VoCommandToIdl(const VoCommand& in, rover_dl_VoCommand* out);
/// Errors: an empty client name ("dl/vo_command: client is empty").
Result<VoCommand> VoCommandFromIdl(const rover_dl_VoCommand& in);

/// The message is truncated to 127 characters.
void EstimatorEventToIdl(const EstimatorEvent& in, rover_dl_EstimatorEvent* out);
/// Errors: an unknown source value.
Result<EstimatorEvent> EstimatorEventFromIdl(const rover_dl_EstimatorEvent& in);

}  // namespace rover::msg
