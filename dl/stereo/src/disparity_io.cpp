#include "rover/dl/stereo/disparity_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "describe.hpp"

namespace rover::dl::stereo {

using internal::Describe;
namespace {

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool LittleEndianHost() {
  const std::uint16_t x = 1;
  std::uint8_t b = 0;
  std::memcpy(&b, &x, 1);
  return b == 1;
}

}  // namespace

Result<cv::Mat> LoadGrayImage(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return NotFound("image '" + path + "' does not exist");
  if (std::filesystem::is_directory(path, ec)) {
    return InvalidArgument("image '" + path + "' is a directory");
  }
  cv::Mat img;
  try {
    img = cv::imread(path, cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR);
  } catch (const cv::Exception& e) {
    return InvalidArgument("image '" + path + "' cannot be decoded: " + e.what());
  }
  if (img.empty()) return InvalidArgument("image '" + path + "' cannot be decoded");
  if (img.depth() != CV_8U && img.depth() != CV_16U) {
    return InvalidArgument("image '" + path + "' is " + Describe(img) +
                           "; expected 8- or 16-bit unsigned");
  }
  if (img.channels() == 3) {
    cv::cvtColor(img, img, cv::COLOR_BGR2GRAY);
  } else if (img.channels() == 4) {
    cv::cvtColor(img, img, cv::COLOR_BGRA2GRAY);
  } else if (img.channels() != 1) {
    return InvalidArgument("image '" + path + "' has " + std::to_string(img.channels()) +
                           " channels; expected 1, 3 or 4");
  }
  return img;
}

Status WritePfm(const std::string& path, const cv::Mat& image) {
  if (image.empty()) return InvalidArgument("image to write to '" + path + "' is empty");
  if (image.type() != CV_32FC1) {
    return InvalidArgument("image to write to '" + path + "' is " + Describe(image) +
                           "; PFM needs CV_32FC1");
  }
  std::ofstream f(path, std::ios::binary);
  if (!f) return Unavailable("cannot open '" + path + "' for writing");
  // Negative scale = little-endian data.
  f << "Pf\n"
    << image.cols << " " << image.rows << "\n"
    << (LittleEndianHost() ? "-1" : "1") << "\n";
  std::vector<float> row(static_cast<std::size_t>(image.cols));
  for (int v = image.rows - 1; v >= 0; --v) {
    const float* src = image.ptr<float>(v);
    for (int u = 0; u < image.cols; ++u) {
      row[static_cast<std::size_t>(u)] =
          std::isfinite(src[u]) ? src[u] : std::numeric_limits<float>::infinity();
    }
    f.write(reinterpret_cast<const char*>(row.data()),
            static_cast<std::streamsize>(row.size() * sizeof(float)));
  }
  f.flush();
  if (!f) return Unavailable("cannot write '" + path + "'");
  return Status::Ok();
}

Result<cv::Mat> ReadPfm(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return NotFound("PFM '" + path + "' does not exist");
    return Unavailable("cannot open PFM '" + path + "'");
  }
  std::string magic;
  long long w = 0, h = 0;
  double scale = 0.0;
  f >> magic >> w >> h >> scale;
  if (!f || magic != "Pf") {
    return InvalidArgument("'" + path + "' is not a single-channel PFM (header '" + magic + "')");
  }
  if (w <= 0 || h <= 0 || w > 65536 || h > 65536 || scale == 0.0) {
    return InvalidArgument("PFM '" + path + "' has a bad header (" + std::to_string(w) + "x" +
                           std::to_string(h) + ", scale " + std::to_string(scale) + ")");
  }
  f.get();  // the single whitespace after the scale
  const bool file_le = scale < 0.0;
  cv::Mat img(static_cast<int>(h), static_cast<int>(w), CV_32FC1);
  std::vector<char> buf(static_cast<std::size_t>(w) * sizeof(float));
  for (int v = img.rows - 1; v >= 0; --v) {
    f.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    if (!f) return InvalidArgument("PFM '" + path + "' is truncated");
    if (file_le != LittleEndianHost()) {
      for (std::size_t i = 0; i < buf.size(); i += 4) {
        std::swap(buf[i], buf[i + 3]);
        std::swap(buf[i + 1], buf[i + 2]);
      }
    }
    float* dst = img.ptr<float>(v);
    std::memcpy(dst, buf.data(), buf.size());
    for (int u = 0; u < img.cols; ++u) {
      if (!std::isfinite(dst[u])) dst[u] = std::numeric_limits<float>::quiet_NaN();
    }
  }
  return img;
}

Status WriteFloatImage(const std::string& path, const cv::Mat& image) {
  const std::string ext = Lower(std::filesystem::path(path).extension().string());
  if (ext == ".pfm") return WritePfm(path, image);
  if (ext != ".tif" && ext != ".tiff") {
    return InvalidArgument("float image '" + path + "' must end in .pfm, .tif or .tiff");
  }
  if (image.empty() || image.type() != CV_32FC1) {
    return InvalidArgument("image to write to '" + path + "' is " + Describe(image) +
                           "; expected CV_32FC1");
  }
  try {
    if (!cv::imwrite(path, image)) return Unavailable("cannot write '" + path + "'");
  } catch (const cv::Exception& e) {
    return Unavailable("cannot write '" + path + "': " + e.what());
  }
  return Status::Ok();
}

Result<cv::Mat> ColorizeDisparity(const cv::Mat& disparity, double d_lo, double d_hi) {
  if (disparity.empty()) return InvalidArgument("disparity to colourise is empty");
  if (disparity.type() != CV_32FC1) {
    return InvalidArgument("disparity to colourise is " + Describe(disparity) +
                           "; expected CV_32FC1");
  }
  if (!(d_hi > d_lo)) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (int v = 0; v < disparity.rows; ++v) {
      const float* d = disparity.ptr<float>(v);
      for (int u = 0; u < disparity.cols; ++u) {
        if (std::isfinite(d[u])) {
          lo = std::min(lo, static_cast<double>(d[u]));
          hi = std::max(hi, static_cast<double>(d[u]));
        }
      }
    }
    d_lo = std::isfinite(lo) ? lo : 0.0;
    d_hi = (std::isfinite(hi) && hi > d_lo) ? hi : d_lo + 1.0;
  }
  cv::Mat grey(disparity.size(), CV_8UC1);
  cv::Mat invalid(disparity.size(), CV_8UC1);
  const double s = 255.0 / (d_hi - d_lo);
  for (int v = 0; v < disparity.rows; ++v) {
    const float* d = disparity.ptr<float>(v);
    std::uint8_t* g = grey.ptr<std::uint8_t>(v);
    std::uint8_t* m = invalid.ptr<std::uint8_t>(v);
    for (int u = 0; u < disparity.cols; ++u) {
      const bool ok = std::isfinite(d[u]);
      g[u] = ok ? cv::saturate_cast<std::uint8_t>((d[u] - d_lo) * s) : 0;
      m[u] = ok ? 0 : 255;
    }
  }
  cv::Mat colour;
  cv::applyColorMap(grey, colour, cv::COLORMAP_TURBO);
  colour.setTo(cv::Scalar(0, 0, 0), invalid);
  return colour;
}

}  // namespace rover::dl::stereo
