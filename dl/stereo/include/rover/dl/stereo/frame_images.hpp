#pragma once
/// @file
/// The two images of a raw stereo frame (msg::StereoFrame, ddl/stereo_frame) as OpenCV
/// matrices for the stereo pipeline and rectification, without copying.

#include <opencv2/core.hpp>

#include "rover/msg/camera.hpp"

namespace rover::dl::stereo {

/// CV_8UC1 height x width views of a frame's images.
struct FrameImages {
  cv::Mat left, right;
};

/// Views of `frame`'s pixels: valid while the frame's buffers are (e.g. during a DDS callback);
/// clone() to keep them. The views are only to be read. Precondition: msg::CheckStereoFrame(frame)
/// is Ok (msg::StereoFrameFromIdl checks it).
FrameImages ViewFrameImages(const msg::StereoFrame& frame);

}  // namespace rover::dl::stereo
