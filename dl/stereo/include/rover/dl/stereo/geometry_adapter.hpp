#pragma once
/// @file
/// Plugs core/geometry's stereo rectification (CAHV/CAHVOR/CAHVORE/pinhole camera models,
/// RectifyStereoPair) into the stereo pipeline: remap tables -> RectificationMaps and the
/// rectified left CAHV model -> StereoCamera.
///
/// The rectified pair shares A, H, V; with the intrinsics hc = A.H, vc = A.V, hs = |A x H| the
/// rectified left camera frame (x right, y down, z forward) has axes H' = (H - hc A) / hs,
/// V' = (V - vc A) / hs and A, origin C_left. Its pose in the models' reference frame is
///     rover_from_camera = [H' V' A | C_left]
/// (the rover frame if the models are in the rover frame, e.g. MSL's ROVER_NAV_FRAME), and the
/// stereo model is f = hs, (cx, cy) = (hc, vc), B = pair.baseline_m,
/// doffs = hc_right - hc_left (0 for RectifyStereoPair's output).

#include <opencv2/core.hpp>

#include "rover/base/status.hpp"
#include "rover/dl/stereo/rectification.hpp"
#include "rover/dl/stereo/reprojection.hpp"
#include "rover/geometry/camera_model.hpp"

namespace rover::dl::stereo {

/// Everything the pipeline needs to process raw images of a calibrated pair.
struct StereoSetup {
  RectificationMaps maps;  ///< raw -> rectified remap tables (CV_32FC1)
  StereoCamera camera;     ///< full-resolution rectified model and pose
};

/// Converts a rectified pair (with remap tables) for raw images of `raw_size`. Errors: a pair
/// without maps, maps of the wrong length, models that are not CAHV, left and right models
/// with different axes, non-finite values.
Result<StereoSetup> StereoSetupFromGeometry(const geometry::RectifiedPair& pair,
                                            cv::Size raw_size);

/// Rectifies two calibrated cameras (any kinds, same image size) with
/// geometry::RectifyStereoPair and converts the result. Errors: different raw image sizes and
/// those of RectifyStereoPair and StereoSetupFromGeometry.
Result<StereoSetup> MakeStereoSetup(const geometry::CameraModel& left,
                                    const geometry::CameraModel& right,
                                    const geometry::RectifyOptions& options = {});

}  // namespace rover::dl::stereo
