#pragma once
/// @file
/// Camera messages <-> their idlc C structs (rover_common.idl CameraId, rover_ddl.idl
/// CameraModel, StereoRequest, StereoFrame), and the C camera model <-> core/geometry's
/// CameraModel. Conventions of every rover/msg/*_idl.hpp:
///   * ...ToIdl fills every field of `out` but header.frame_id and header.seq (the writer's:
///     call it after ServiceContext::Stamp); header.stamp_ns is the struct's stamp.
///   * ...FromIdl takes the stamp from header.stamp_ns. It returns a Result when the sample can
///     be bad in a way the struct cannot hold or no consumer could use (an unknown enum value of
///     a state message, sizes that disagree, a quaternion that is not a rotation); the message
///     names the field and the value. Commands keep unknown enum values as they are and plain
///     numbers are copied as they are: the consumer rejects them with its typed reason.
///   * Sequences are viewed (never copied) on the way in, borrowed on the way out: the source
///     must outlive the view or the write.

#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/camera.hpp"

namespace rover::msg {

rover_CameraId CameraIdToIdl(CameraId c);
/// InvalidArgument "<field> = 7 is not a CameraId (0..2)".
Result<CameraId> CameraIdFromIdl(const rover_CameraId& c, std::string_view field = "camera");

/// Field by field (pose quaternion w first; sizes clamped to 0..65535).
void CameraModelToIdl(const CameraModelFields& in, rover_ddl_CameraModel* out);
/// Field by field; the content is checked where it is used (CameraModelFromFields).
CameraModelFields CameraModelFieldsFromIdl(const rover_ddl_CameraModel& in);
/// Both parts of a geometry model (CameraModelFieldsFromModel). Errors: its errors.
Status CameraModelToIdl(const geometry::CameraModel& model, rover_ddl_CameraModel* out);
/// The geometry model of a C model (CameraModelFromFields). Errors: its errors.
Result<geometry::CameraModel> CameraModelFromIdl(const rover_ddl_CameraModel& in);

/// ddl/camera_request. The camera value is kept as it is (a command).
StereoRequest StereoRequestFromIdl(const rover_ddl_StereoRequest& in);
/// Width clamped to 0..65535.
void StereoRequestToIdl(const StereoRequest& in, rover_ddl_StereoRequest* out);

/// ddl/stereo_frame, its images viewing `in`'s buffers (valid while `in` is). Errors: an unknown
/// camera or health value, a null image buffer, and those of CheckStereoFrame (sizes, stamp).
Result<StereoFrame> StereoFrameFromIdl(const rover_ddl_StereoFrame& in);
/// `left`/`right` borrow the frame's views (they must outlive the write).
void StereoFrameToIdl(const StereoFrame& in, rover_ddl_StereoFrame* out);

MiRequest MiRequestFromIdl(const rover_ddl_MiRequest& in);
void MiRequestToIdl(const MiRequest& in, rover_ddl_MiRequest* out);
/// Errors: a health value out of range, a null image buffer, those of CheckMiFrame. The image
/// views `in`'s buffer.
Result<MiFrame> MiFrameFromIdl(const rover_ddl_MiFrame& in);
/// Borrows in.image's bytes (keep them alive until the sample is written).
void MiFrameToIdl(const MiFrame& in, rover_ddl_MiFrame* out);

}  // namespace rover::msg
