#pragma once
// Private to dl_stereo: how an image appears in an error message ("640x480 CV_8UC1").

#include <opencv2/core.hpp>
#include <string>

#include "rover/base/format.hpp"

namespace rover::dl::stereo::internal {

inline std::string Describe(const cv::Mat& m) {
  return FormatSize(m.cols, m.rows) + " " + cv::typeToString(m.type());
}

inline std::string SizeText(cv::Size s) { return FormatSize(s.width, s.height); }

}  // namespace rover::dl::stereo::internal
