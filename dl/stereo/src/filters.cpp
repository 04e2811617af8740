#include "rover/dl/stereo/filters.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "describe.hpp"
#include "filters_internal.hpp"

namespace rover::dl::stereo {

using internal::Describe;
namespace {

constexpr auto kValid = static_cast<std::uint8_t>(PixelStatus::kValid);

Status CheckImage(const DisparityImage* d) {
  if (d == nullptr || d->empty()) return InvalidArgument("disparity image is empty");
  if (d->disparity.type() != CV_32FC1 || d->status.type() != CV_8UC1 ||
      d->status.size() != d->disparity.size()) {
    return InvalidArgument("disparity image must be CV_32FC1 with a CV_8UC1 status of equal size");
  }
  return Status::Ok();
}

int Find(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    const auto ui = static_cast<std::size_t>(i);
    parent[ui] = parent[static_cast<std::size_t>(parent[ui])];
    i = parent[ui];
  }
  return i;
}

void Union(std::vector<int>& parent, int a, int b) {
  a = Find(parent, a);
  b = Find(parent, b);
  if (a == b) return;
  if (a < b) {
    parent[static_cast<std::size_t>(b)] = a;
  } else {
    parent[static_cast<std::size_t>(a)] = b;
  }
}

}  // namespace

Status FilterOptions::Validate() const {
  const auto bad = [](const std::string& what) { return InvalidArgument("filters." + what); };
  if (border_px < 0 || border_px > 4096) {
    return bad("border_px " + std::to_string(border_px) + " is outside [0, 4096]");
  }
  if (blob_min_area < 0) return bad("blob_min_area " + std::to_string(blob_min_area) + " is < 0");
  if (!(blob_max_step > 0.0 && std::isfinite(blob_max_step))) {
    return bad("blob_max_step " + std::to_string(blob_max_step) + " must be > 0");
  }
  if (!(overhang_tolerance_px >= 0.0 && std::isfinite(overhang_tolerance_px))) {
    return bad("overhang_tolerance_px " + std::to_string(overhang_tolerance_px) + " must be >= 0");
  }
  if (!(overhang_ratio >= 0.0 && overhang_ratio <= 1.0)) {
    return bad("overhang_ratio " + std::to_string(overhang_ratio) + " is outside [0, 1]");
  }
  if (overhang_search_rows < 1 || overhang_search_rows > 256) {
    return bad("overhang_search_rows " + std::to_string(overhang_search_rows) +
               " is outside [1, 256]");
  }
  return Status::Ok();
}

Status ApplyBorderFilter(int margin, DisparityImage* disparity) {
  ROVER_RETURN_IF_ERROR(CheckImage(disparity));
  if (margin < 0) return InvalidArgument("border margin " + std::to_string(margin) + " is < 0");
  const int w = disparity->disparity.cols;
  const int h = disparity->disparity.rows;
  for (int v = 0; v < h; ++v) {
    const bool row_in_border = v < margin || v >= h - margin;
    for (int u = 0; u < w; ++u) {
      if (row_in_border || u < margin || u >= w - margin) {
        disparity->Reject(v, u, PixelStatus::kBorder);
      }
    }
  }
  return Status::Ok();
}

Status ApplyBlobFilter(int min_area, double max_step, DisparityImage* disparity) {
  ROVER_RETURN_IF_ERROR(CheckImage(disparity));
  if (min_area < 0) return InvalidArgument("blob min_area " + std::to_string(min_area) + " is < 0");
  if (!(max_step > 0.0)) {
    return InvalidArgument("blob max_step " + std::to_string(max_step) + " must be > 0");
  }
  if (min_area <= 1) return Status::Ok();
  const int w = disparity->disparity.cols;
  const int h = disparity->disparity.rows;
  const float step = static_cast<float>(max_step);
  // Runs: maximal horizontal stretches of valid pixels whose neighbours differ by <= step.
  // Each run is a union-find node; runs join the runs of the row above they touch.
  struct Run {
    int v, u0, u1;  // pixels [u0, u1) of row v
  };
  std::vector<Run> runs;
  std::vector<int> parent;
  runs.reserve(static_cast<std::size_t>(h) * 8);
  parent.reserve(static_cast<std::size_t>(h) * 8);
  std::vector<int> above(static_cast<std::size_t>(w), -1), here(static_cast<std::size_t>(w), -1);
  for (int v = 0; v < h; ++v) {
    const float* d = disparity->disparity.ptr<float>(v);
    const float* d_up = v > 0 ? disparity->disparity.ptr<float>(v - 1) : nullptr;
    const std::uint8_t* s = disparity->status.ptr<std::uint8_t>(v);
    int u = 0;
    while (u < w) {
      if (s[u] != kValid) {
        here[static_cast<std::size_t>(u++)] = -1;
        continue;
      }
      const int id = static_cast<int>(runs.size());
      const int u0 = u;
      parent.push_back(id);
      int last_joined = -1;
      do {
        here[static_cast<std::size_t>(u)] = id;
        const int a = above[static_cast<std::size_t>(u)];
        if (a >= 0 && a != last_joined && std::abs(d[u] - d_up[u]) <= step) {
          Union(parent, id, a);
          last_joined = a;
        }
        ++u;
      } while (u < w && s[u] == kValid && std::abs(d[u] - d[u - 1]) <= step);
      runs.push_back({v, u0, u});
    }
    std::swap(above, here);
  }
  // Areas per root, then reject the runs of small regions.
  std::vector<int> area(runs.size(), 0);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const int root = Find(parent, static_cast<int>(i));
    parent[i] = root;
    area[static_cast<std::size_t>(root)] += runs[i].u1 - runs[i].u0;
  }
  constexpr auto kBlobCode = static_cast<std::uint8_t>(PixelStatus::kBlob);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (area[static_cast<std::size_t>(parent[i])] >= min_area) continue;
    const Run& r = runs[i];
    float* d = disparity->disparity.ptr<float>(r.v);
    std::uint8_t* s = disparity->status.ptr<std::uint8_t>(r.v);
    for (int u = r.u0; u < r.u1; ++u) {
      d[u] = kInvalidDisparity;
      s[u] = kBlobCode;
    }
  }
  return Status::Ok();
}

namespace internal {

void OverhangColumns(double tolerance_px, double ratio, int search_rows, int u_begin, int u_end,
                     DisparityImage* disparity) {
  // GCC/Clang vector extensions, 4 lanes (SSE2 on x86-64).
  using F4 = float __attribute__((vector_size(16)));
  using I4 = std::int32_t __attribute__((vector_size(16)));
  using B4 = std::uint8_t __attribute__((vector_size(4)));
  const int w = u_end - u_begin;
  const int h = disparity->disparity.rows;
  const float tol = static_cast<float>(tolerance_px);
  const float rat = static_cast<float>(ratio);
  constexpr float kNone = -std::numeric_limits<float>::infinity();
  const int wp = (w + 3) / 4 * 4;
  const int n = search_rows;
  // Sliding maximum of the accepted disparities of the last n rows (van Herk / Gil-Werman):
  // rows form blocks of n; the window of row i (rows i - n .. i - 1) is the tail of the previous
  // block (its suffix maxima, computed once per block) and the head of the current block (a
  // running maximum), so each row costs O(1) per pixel whatever n is. kNone = no accepted pixel.
  const std::size_t row_len = static_cast<std::size_t>(wp);
  std::vector<float> block(static_cast<std::size_t>(n) * row_len, kNone);
  std::vector<float> suffix(static_cast<std::size_t>(n) * row_len, kNone);
  std::vector<float> head(row_len, kNone);
  const F4 none4 = {kNone, kNone, kNone, kNone};
  const F4 tol4 = {tol, tol, tol, tol};
  const F4 rat4 = {rat, rat, rat, rat};
  const F4 nan4 = {kInvalidDisparity, kInvalidDisparity, kInvalidDisparity, kInvalidDisparity};
  const I4 zero4 = {0, 0, 0, 0};
  const int code = static_cast<int>(PixelStatus::kOverhang);
  const I4 code4 = {code, code, code, code};
  const auto load = [](const float* p) {
    F4 v;
    std::memcpy(&v, p, sizeof(v));
    return v;
  };
  const auto store = [](float* p, F4 v) { std::memcpy(p, &v, sizeof(v)); };
  for (int i = 0, v = h - 1; v >= 0; --v, ++i) {
    const int j = i % n;
    if (j == 0) std::fill(head.begin(), head.end(), kNone);
    const float* tail = suffix.data() + static_cast<std::ptrdiff_t>(j) * wp;
    float* hd = head.data();
    float* slot = block.data() + static_cast<std::ptrdiff_t>(j) * wp;
    float* d = disparity->disparity.ptr<float>(v) + u_begin;
    std::uint8_t* s = disparity->status.ptr<std::uint8_t>(v) + u_begin;
    int u = 0;
    for (; u + 4 <= w; u += 4) {
      B4 sb;
      std::memcpy(&sb, s + u, sizeof(sb));
      const I4 st = __builtin_convertvector(sb, I4);
      const F4 dd = load(d + u);
      const F4 t4 = load(tail + u), h4 = load(hd + u);
      const F4 rr = t4 > h4 ? t4 : h4;
      const F4 absr = rr < 0 ? -rr : rr;
      const F4 margin = tol4 > rat4 * absr ? tol4 : rat4 * absr;
      const I4 reject = (st == zero4) & (rr != none4) & (dd > rr + margin);
      const F4 keep = ((st == zero4) & ~reject) ? dd : none4;
      store(slot + u, keep);
      store(hd + u, h4 > keep ? h4 : keep);
      const F4 dn = reject ? nan4 : dd;
      std::memcpy(d + u, &dn, sizeof(dn));
      const I4 so = reject ? code4 : st;
#if defined(__SSE2__)
      const __m128i x = std::bit_cast<__m128i>(so);
      const int word = _mm_cvtsi128_si32(_mm_packus_epi16(_mm_packs_epi32(x, x), x));
      std::memcpy(s + u, &word, sizeof(word));
#else
      const B4 sob = __builtin_convertvector(so, B4);
      std::memcpy(s + u, &sob, sizeof(sob));
#endif
    }
    for (; u < w; ++u) {
      slot[u] = kNone;
      if (s[u] != kValid) continue;
      const float dref = std::max(tail[u], hd[u]);
      if (dref != kNone && d[u] > dref + std::max(tol, rat * std::abs(dref))) {
        s[u] = static_cast<std::uint8_t>(PixelStatus::kOverhang);
        d[u] = kInvalidDisparity;
      } else {
        slot[u] = d[u];
        hd[u] = std::max(hd[u], d[u]);
      }
    }
    if (j == n - 1) {  // block complete: its suffix maxima serve the next block
      float* sfx = suffix.data();
      std::memcpy(sfx + (n - 1) * row_len, slot, row_len * sizeof(float));
      for (int t = n - 2; t >= 0; --t) {
        const float* b = block.data() + static_cast<std::ptrdiff_t>(t) * wp;
        const float* next = sfx + static_cast<std::ptrdiff_t>(t + 1) * wp;
        float* out = sfx + static_cast<std::ptrdiff_t>(t) * wp;
        for (int x = 0; x < wp; x += 4) {
          const F4 a = load(b + x), c = load(next + x);
          store(out + x, a > c ? a : c);
        }
      }
    }
  }
}

}  // namespace internal

Status ApplyOverhangFilter(double tolerance_px, double ratio, int search_rows,
                           DisparityImage* disparity) {
  ROVER_RETURN_IF_ERROR(CheckImage(disparity));
  if (!(tolerance_px >= 0.0) || !(ratio >= 0.0) || search_rows < 1) {
    return InvalidArgument("overhang filter needs tolerance_px >= 0, ratio >= 0, search_rows >= 1");
  }
  internal::OverhangColumns(tolerance_px, ratio, search_rows, 0, disparity->disparity.cols,
                            disparity);
  return Status::Ok();
}

Status ApplyMask(const cv::Mat& mask, PixelStatus reason, DisparityImage* disparity) {
  ROVER_RETURN_IF_ERROR(CheckImage(disparity));
  if (mask.empty()) return Status::Ok();
  if (mask.type() != CV_8UC1) {
    return InvalidArgument("mask is " + Describe(mask) + "; expected CV_8UC1");
  }
  if (mask.size() != disparity->size()) {
    return InvalidArgument("mask is " + Describe(mask) + " but the disparity image is " +
                           Describe(disparity->disparity));
  }
  const auto code = static_cast<std::uint8_t>(reason);
  for (int v = 0; v < mask.rows; ++v) {
    const std::uint8_t* m = mask.ptr<std::uint8_t>(v);
    float* d = disparity->disparity.ptr<float>(v);
    std::uint8_t* s = disparity->status.ptr<std::uint8_t>(v);
    for (int u = 0; u < mask.cols; ++u) {
      if (m[u] != 0) {
        s[u] = code;
        d[u] = kInvalidDisparity;
      }
    }
  }
  return Status::Ok();
}

Result<cv::Mat> RasterizePolygons(const std::vector<std::vector<cv::Point2f>>& polygons,
                                  cv::Size size, int levels) {
  if (size.width <= 0 || size.height <= 0) return InvalidArgument("polygon mask size is empty");
  if (levels < 0) return InvalidArgument("polygon mask levels " + std::to_string(levels) + " < 0");
  constexpr int kShift = 4;  // fractional bits for cv::fillPoly
  const double scale = std::ldexp(1.0, -levels);
  std::vector<std::vector<cv::Point>> pts;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    const auto& poly = polygons[i];
    if (poly.size() < 3) {
      return InvalidArgument("wheel polygon " + std::to_string(i) + " has " +
                             std::to_string(poly.size()) + " vertices; needs at least 3");
    }
    std::vector<cv::Point> p;
    for (const auto& q : poly) {
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || std::abs(q.x) > 1e6 ||
          std::abs(q.y) > 1e6) {
        return InvalidArgument("wheel polygon " + std::to_string(i) +
                               " has a non-finite or huge vertex");
      }
      const double u = (q.x + 0.5) * scale - 0.5;
      const double v = (q.y + 0.5) * scale - 0.5;
      p.emplace_back(static_cast<int>(std::lround(u * (1 << kShift))),
                     static_cast<int>(std::lround(v * (1 << kShift))));
    }
    pts.push_back(std::move(p));
  }
  cv::Mat mask = cv::Mat::zeros(size, CV_8UC1);
  if (!pts.empty()) cv::fillPoly(mask, pts, cv::Scalar(255), cv::LINE_8, kShift);
  return mask;
}

Result<cv::Mat> DownsampleMask(const cv::Mat& mask, int levels) {
  if (mask.empty()) return InvalidArgument("mask is empty");
  if (mask.type() != CV_8UC1) {
    return InvalidArgument("mask is " + Describe(mask) + "; expected CV_8UC1");
  }
  if (levels < 0) return InvalidArgument("mask levels " + std::to_string(levels) + " < 0");
  cv::Mat m = mask;
  for (int l = 0; l < levels; ++l) {
    if (m.cols < 2 || m.rows < 2)
      return InvalidArgument("mask too small for " + std::to_string(levels) + " levels");
    cv::Mat n(m.rows / 2, m.cols / 2, CV_8UC1);
    for (int v = 0; v < n.rows; ++v) {
      const std::uint8_t* a = m.ptr<std::uint8_t>(2 * v);
      const std::uint8_t* b = m.ptr<std::uint8_t>(2 * v + 1);
      std::uint8_t* o = n.ptr<std::uint8_t>(v);
      for (int u = 0; u < n.cols; ++u) {
        o[u] = (a[2 * u] | a[2 * u + 1] | b[2 * u] | b[2 * u + 1]) != 0 ? 255 : 0;
      }
    }
    m = n;
  }
  return m.clone();
}

}  // namespace rover::dl::stereo
