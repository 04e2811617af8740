#include "rover/dl/stereo/frame_images.hpp"

#include "rover/base/check.hpp"

namespace rover::dl::stereo {
namespace {

cv::Mat View(std::span<const std::uint8_t> pixels, int width, int height) {
  // cv::Mat has no const view; the pipeline only reads it.
  return cv::Mat(height, width, CV_8UC1, const_cast<std::uint8_t*>(pixels.data()));
}

}  // namespace

FrameImages ViewFrameImages(const msg::StereoFrame& frame) {
  ROVER_DEMAND(msg::CheckStereoFrame(frame).ok());
  return {View(frame.left, frame.width, frame.height),
          View(frame.right, frame.width, frame.height)};
}

}  // namespace rover::dl::stereo
