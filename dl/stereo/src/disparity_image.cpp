#include "rover/dl/stereo/disparity_image.hpp"

namespace rover::dl::stereo {

const char* PixelStatusName(PixelStatus s) {
  switch (s) {
    case PixelStatus::kValid:
      return "valid";
    case PixelStatus::kBorder:
      return "border";
    case PixelStatus::kNoMatch:
      return "no_match";
    case PixelStatus::kRangeEdge:
      return "range_edge";
    case PixelStatus::kFlat:
      return "flat";
    case PixelStatus::kNotUnique:
      return "not_unique";
    case PixelStatus::kLeftRight:
      return "left_right";
    case PixelStatus::kBlob:
      return "blob";
    case PixelStatus::kOverhang:
      return "overhang";
    case PixelStatus::kVehicle:
      return "vehicle";
    case PixelStatus::kWheel:
      return "wheel";
    case PixelStatus::kRangeLimit:
      return "range_limit";
  }
  return "unknown";
}

void DisparityImage::Reset(cv::Size size, PixelStatus fill) {
  disparity.create(size, CV_32FC1);
  disparity.setTo(cv::Scalar(kInvalidDisparity));
  status.create(size, CV_8UC1);
  status.setTo(cv::Scalar(static_cast<int>(fill)));
}

cv::Mat DisparityImage::ValidMask() const {
  cv::Mat mask;
  cv::compare(status, cv::Scalar(0), mask, cv::CMP_EQ);
  return mask;
}

StatusCounts DisparityImage::CountStatus() const {
  // Four interleaved histograms (no store-to-load dependency between neighbouring pixels).
  std::array<int, 4 * 256> h{};
  for (int v = 0; v < status.rows; ++v) {
    const std::uint8_t* row = status.ptr<std::uint8_t>(v);
    int u = 0;
    for (; u + 4 <= status.cols; u += 4) {
      ++h[row[u]];
      ++h[256 + row[u + 1]];
      ++h[512 + row[u + 2]];
      ++h[768 + row[u + 3]];
    }
    for (; u < status.cols; ++u) ++h[row[u]];
  }
  StatusCounts counts{};
  for (int i = 0; i < kNumPixelStatus; ++i) {
    counts[static_cast<std::size_t>(i)] =
        h[static_cast<std::size_t>(i)] + h[static_cast<std::size_t>(256 + i)] +
        h[static_cast<std::size_t>(512 + i)] + h[static_cast<std::size_t>(768 + i)];
  }
  return counts;
}

}  // namespace rover::dl::stereo
