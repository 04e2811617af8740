#include "rover/ddl/camera/downsample.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rover/base/format.hpp"

namespace rover::ddl::camera {
namespace {

struct Tap {
  int index;
  double weight;
};

// For each output sample, the input samples it overlaps and their weights (sum 1).
std::vector<std::vector<Tap>> AreaTaps(int in, int out) {
  std::vector<std::vector<Tap>> taps(static_cast<std::size_t>(out));
  const double step = static_cast<double>(in) / out;
  for (int u = 0; u < out; ++u) {
    const double lo = u * step, hi = (u + 1) * step;
    auto& t = taps[static_cast<std::size_t>(u)];
    for (int i = static_cast<int>(std::floor(lo));
         i < std::min(in, static_cast<int>(std::ceil(hi))); ++i) {
      const double w = std::min(hi, i + 1.0) - std::max(lo, static_cast<double>(i));
      if (w > 1e-12) t.push_back({i, w / step});
    }
  }
  return taps;
}

Status CheckImage(const GrayImage& im, const char* name) {
  if (im.width < 1 || im.height < 1) {
    return InvalidArgument(std::string(name) + ": image size " + FormatSize(im.width, im.height) +
                           " is empty");
  }
  if (im.pixels.size() !=
      static_cast<std::size_t>(im.width) * static_cast<std::size_t>(im.height)) {
    return InvalidArgument(std::string(name) + ": " + std::to_string(im.pixels.size()) +
                           " bytes for a " + FormatSize(im.width, im.height) + " image");
  }
  return Status::Ok();
}

}  // namespace

Result<GrayImage> AreaDownsample(const GrayImage& in, int out_w, int out_h) {
  ROVER_RETURN_IF_ERROR(CheckImage(in, "input"));
  if (out_w < 1 || out_h < 1 || out_w > in.width || out_h > in.height) {
    return InvalidArgument("output size " + FormatSize(out_w, out_h) + " must be within 1x1.." +
                           FormatSize(in.width, in.height) + " (no upsampling)");
  }
  GrayImage out;
  out.width = out_w;
  out.height = out_h;
  out.pixels.resize(static_cast<std::size_t>(out_w) * static_cast<std::size_t>(out_h));
  if (out_w == in.width && out_h == in.height) {
    out.pixels = in.pixels;
    return out;
  }
  const auto cols = AreaTaps(in.width, out_w);
  const auto rows = AreaTaps(in.height, out_h);
  // Horizontal pass into doubles (in.height x out_w), then vertical.
  std::vector<double> tmp(static_cast<std::size_t>(in.height) * static_cast<std::size_t>(out_w));
  for (int y = 0; y < in.height; ++y) {
    const std::uint8_t* src = in.pixels.data() + static_cast<std::size_t>(y) * in.width;
    double* dst = tmp.data() + static_cast<std::size_t>(y) * out_w;
    for (int u = 0; u < out_w; ++u) {
      double s = 0.0;
      for (const Tap& t : cols[static_cast<std::size_t>(u)]) s += t.weight * src[t.index];
      dst[u] = s;
    }
  }
  for (int v = 0; v < out_h; ++v) {
    std::uint8_t* dst = out.pixels.data() + static_cast<std::size_t>(v) * out_w;
    for (int u = 0; u < out_w; ++u) {
      double s = 0.0;
      for (const Tap& t : rows[static_cast<std::size_t>(v)]) {
        s +=
            t.weight * tmp[static_cast<std::size_t>(t.index) * out_w + static_cast<std::size_t>(u)];
      }
      dst[u] = static_cast<std::uint8_t>(std::clamp(std::lround(s), 0L, 255L));
    }
  }
  return out;
}

Result<DownsampledStereo> DownsampleStereo(const GrayImage& left, const GrayImage& right,
                                           const geometry::CameraModel& left_model,
                                           const geometry::CameraModel& right_model,
                                           int out_width) {
  ROVER_RETURN_IF_ERROR(CheckImage(left, "left"));
  ROVER_RETURN_IF_ERROR(CheckImage(right, "right"));
  if (left.width != right.width || left.height != right.height) {
    return InvalidArgument("left image is " + FormatSize(left.width, left.height) +
                           " but right is " + FormatSize(right.width, right.height));
  }
  if (left_model.width() != left.width || left_model.height() != left.height) {
    return InvalidArgument("left model is for " +
                           FormatSize(left_model.width(), left_model.height()) +
                           " but the image is " + FormatSize(left.width, left.height));
  }
  if (right_model.width() != right.width || right_model.height() != right.height) {
    return InvalidArgument("right model is for " +
                           FormatSize(right_model.width(), right_model.height()) +
                           " but the image is " + FormatSize(right.width, right.height));
  }
  if (out_width < 0 || out_width > left.width) {
    return InvalidArgument("width " + std::to_string(out_width) + " must be within 0.." +
                           std::to_string(left.width) + " (0 = full size; no upsampling)");
  }
  const int out_w = out_width == 0 ? left.width : out_width;
  const int out_h = std::max(
      1, static_cast<int>(std::lround(static_cast<double>(left.height) * out_w / left.width)));
  auto l = AreaDownsample(left, out_w, out_h);
  if (!l.ok()) return l.status();
  auto r = AreaDownsample(right, out_w, out_h);
  if (!r.ok()) return r.status();
  const double sx = static_cast<double>(out_w) / left.width;
  const double sy = static_cast<double>(out_h) / left.height;
  return DownsampledStereo{std::move(*l),
                           std::move(*r),
                           geometry::Scale(left_model, sx, sy),
                           geometry::Scale(right_model, sx, sy),
                           sx,
                           sy};
}

}  // namespace rover::ddl::camera
