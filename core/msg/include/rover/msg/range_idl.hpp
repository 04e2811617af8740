#pragma once
/// @file
/// dl/range_request and dl/range_image <-> their idlc C structs (conventions: see
/// rover/msg/camera_idl.hpp).

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/range.hpp"

namespace rover::msg {

/// A command: the camera value is kept as it is (stereo rejects an unknown one).
RangeRequest RangeRequestFromIdl(const rover_dl_RangeRequest& in);
/// Width clamped to 0..65535.
void RangeRequestToIdl(const RangeRequest& in, rover_dl_RangeRequest* out);

/// The arrays borrow `in`'s vectors (they must outlive the write). Errors: the sizes of
/// RangeImage::CheckSizes (nothing is written to `out` then).
Status RangeImageToIdl(const RangeImage& in, rover_dl_RangeImage* out);
/// Copies the arrays. Errors: an unknown camera, a rover_pose quaternion whose norm is not
/// within 1e-3 of 1, array sizes that disagree with width x height.
Result<RangeImage> RangeImageFromIdl(const rover_dl_RangeImage& in);

}  // namespace rover::msg
