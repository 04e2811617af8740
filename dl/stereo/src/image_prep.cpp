#include "rover/dl/stereo/image_prep.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <opencv2/imgproc.hpp>
#include <string>

#include "describe.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace rover::dl::stereo {

using internal::Describe;

const char* PrefilterKindName(PrefilterKind k) {
  switch (k) {
    case PrefilterKind::kNone:
      return "none";
    case PrefilterKind::kLaplacianOfGaussian:
      return "log";
    case PrefilterKind::kDifferenceOfGaussians:
      return "dog";
  }
  return "unknown";
}

Result<PrefilterKind> ParsePrefilterKind(const std::string& name) {
  if (name == "none") return PrefilterKind::kNone;
  if (name == "log") return PrefilterKind::kLaplacianOfGaussian;
  if (name == "dog") return PrefilterKind::kDifferenceOfGaussians;
  return InvalidArgument("prefilter '" + name + "' is not one of: none, log, dog");
}

Status PrefilterOptions::Validate() const {
  if (!(sigma > 0.0 && sigma <= 10.0)) {
    return InvalidArgument("prefilter.sigma " + std::to_string(sigma) + " is outside (0, 10] px");
  }
  if (kind == PrefilterKind::kDifferenceOfGaussians &&
      !(sigma_outer > sigma && sigma_outer <= 20.0)) {
    return InvalidArgument("prefilter.sigma_outer " + std::to_string(sigma_outer) +
                           " must exceed prefilter.sigma " + std::to_string(sigma) +
                           " and be at most 20 px");
  }
  if (!(gain > 0.0 && gain <= 100.0)) {
    return InvalidArgument("prefilter.gain " + std::to_string(gain) + " is outside (0, 100]");
  }
  if (cap < 1 || cap > 63) {
    return InvalidArgument("prefilter.cap " + std::to_string(cap) + " is outside [1, 63]");
  }
  return Status::Ok();
}

namespace {

// Kernel size covering +-3 sigma, odd.
int KernelSize(double sigma) { return 2 * static_cast<int>(std::ceil(3.0 * sigma)) + 1; }

}  // namespace

Status ConvertTo8Bit(const cv::Mat& in, double white_level, double gamma, cv::Mat* out) {
  if (in.empty()) return InvalidArgument("image is empty");
  if (in.type() != CV_8UC1 && in.type() != CV_16UC1) {
    return InvalidArgument("image is " + Describe(in) + "; expected CV_8UC1 or CV_16UC1");
  }
  if (!(white_level > 0.0 && white_level <= 65535.0)) {
    return InvalidArgument("white_level " + std::to_string(white_level) + " is outside (0, 65535]");
  }
  if (!(gamma >= 0.1 && gamma <= 10.0)) {
    return InvalidArgument("gamma " + std::to_string(gamma) + " is outside [0.1, 10]");
  }
  const bool identity = in.type() == CV_8UC1 && white_level == 255.0 && gamma == 1.0;
  if (identity) {
    in.copyTo(*out);
    return Status::Ok();
  }
  const int levels = in.type() == CV_8UC1 ? 256 : 65536;
  std::vector<std::uint8_t> lut(static_cast<std::size_t>(levels));
  for (int i = 0; i < levels; ++i) {
    const double x = std::min(1.0, static_cast<double>(i) / white_level);
    const double y = gamma == 1.0 ? x : std::pow(x, 1.0 / gamma);
    lut[static_cast<std::size_t>(i)] = cv::saturate_cast<std::uint8_t>(255.0 * y);
  }
  out->create(in.size(), CV_8UC1);
  for (int v = 0; v < in.rows; ++v) {
    std::uint8_t* dst = out->ptr<std::uint8_t>(v);
    if (in.type() == CV_8UC1) {
      const std::uint8_t* src = in.ptr<std::uint8_t>(v);
      for (int u = 0; u < in.cols; ++u) dst[u] = lut[src[u]];
    } else {
      const std::uint16_t* src = in.ptr<std::uint16_t>(v);
      for (int u = 0; u < in.cols; ++u) dst[u] = lut[src[u]];
    }
  }
  return Status::Ok();
}

Status Downsample2x(const cv::Mat& in, cv::Mat* out) {
  if (in.empty()) return InvalidArgument("image to downsample is empty");
  if (in.type() != CV_8UC1) {
    return InvalidArgument("image to downsample is " + Describe(in) + "; expected CV_8UC1");
  }
  if (in.cols < 2 || in.rows < 2) {
    return InvalidArgument("image to downsample is " + Describe(in) + "; needs at least 2x2");
  }
  const int w = in.cols / 2;
  const int h = in.rows / 2;
  cv::Mat result(h, w, CV_8UC1);
  for (int v = 0; v < h; ++v) {
    const std::uint8_t* a = in.ptr<std::uint8_t>(2 * v);
    const std::uint8_t* b = in.ptr<std::uint8_t>(2 * v + 1);
    std::uint8_t* dst = result.ptr<std::uint8_t>(v);
    for (int u = 0; u < w; ++u) {
      const int s = a[2 * u] + a[2 * u + 1] + b[2 * u] + b[2 * u + 1];
      dst[u] = static_cast<std::uint8_t>((s + 2) >> 2);
    }
  }
  *out = result;
  return Status::Ok();
}

namespace {

// q = clamp((r * m + 2^11) >> 12, -cap, cap) + cap for one pixel.
inline std::uint8_t Quantise(int r, int m, int cap) {
  const int q = (r * m + 2048) >> 12;
  return static_cast<std::uint8_t>(std::clamp(q, -cap, cap) + cap);
}

#if defined(__SSE2__)
// The same for 8 responses at once (|r| <= 16320 and |m| <= 32767, so r * m + 2048 fits
// in 32 bits): madd of (r, 1) pairs with (m, 2048) does the multiply and the rounding add.
inline __m128i Quantise8(__m128i r, __m128i m_round, __m128i lo, __m128i hi, __m128i cap) {
  const __m128i one = _mm_set1_epi16(1);
  const __m128i a = _mm_srai_epi32(_mm_madd_epi16(_mm_unpacklo_epi16(r, one), m_round), 12);
  const __m128i b = _mm_srai_epi32(_mm_madd_epi16(_mm_unpackhi_epi16(r, one), m_round), 12);
  const __m128i q = _mm_packs_epi32(a, b);
  return _mm_add_epi16(_mm_min_epi16(_mm_max_epi16(q, lo), hi), cap);
}
inline __m128i Load8(const std::int16_t* p) {
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
}
#endif

// Fused 3x3 Laplacian (or difference, if `outer` is set) + scale + clip of 16-bit blurred
// images, border reflect-101; SSE2 in the interior, scalar at the ends of each row.
void QuantiseResponse(const cv::Mat& inner, const cv::Mat* outer, int m, int cap, cv::Mat* out) {
  const int w = inner.cols;
  const int h = inner.rows;
#if defined(__SSE2__)
  const __m128i m_round = _mm_set1_epi32(
      static_cast<int>((static_cast<std::uint32_t>(2048) << 16) | static_cast<std::uint16_t>(m)));
  const __m128i lo = _mm_set1_epi16(static_cast<short>(-cap));
  const __m128i hi = _mm_set1_epi16(static_cast<short>(cap));
  const __m128i vcap = hi;
#endif
  for (int v = 0; v < h; ++v) {
    std::uint8_t* o = out->ptr<std::uint8_t>(v);
    const std::int16_t* c = inner.ptr<std::int16_t>(v);
    if (outer != nullptr) {
      const std::int16_t* b = outer->ptr<std::int16_t>(v);
      int u = 0;
#if defined(__SSE2__)
      for (; u + 16 <= w; u += 16) {
        const __m128i q0 =
            Quantise8(_mm_sub_epi16(Load8(c + u), Load8(b + u)), m_round, lo, hi, vcap);
        const __m128i q1 =
            Quantise8(_mm_sub_epi16(Load8(c + u + 8), Load8(b + u + 8)), m_round, lo, hi, vcap);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(o + u), _mm_packus_epi16(q0, q1));
      }
#endif
      for (; u < w; ++u) o[u] = Quantise(c[u] - b[u], m, cap);
      continue;
    }
    const int vu = v == 0 ? std::min(1, h - 1) : v - 1;
    const int vd = v == h - 1 ? std::max(h - 2, 0) : v + 1;
    const std::int16_t* up = inner.ptr<std::int16_t>(vu);
    const std::int16_t* dn = inner.ptr<std::int16_t>(vd);
    const auto lap = [&](int u) {
      const int ul = u == 0 ? std::min(1, w - 1) : u - 1;
      const int ur = u == w - 1 ? std::max(w - 2, 0) : u + 1;
      return up[u] + dn[u] + c[ul] + c[ur] - 4 * c[u];
    };
    o[0] = Quantise(lap(0), m, cap);
    int u = 1;
#if defined(__SSE2__)
    const auto lap8 = [&](int x) {
      const __m128i sum = _mm_add_epi16(_mm_add_epi16(Load8(up + x), Load8(dn + x)),
                                        _mm_add_epi16(Load8(c + x - 1), Load8(c + x + 1)));
      return _mm_sub_epi16(sum, _mm_slli_epi16(Load8(c + x), 2));
    };
    for (; u + 16 <= w - 1; u += 16) {
      const __m128i q0 = Quantise8(lap8(u), m_round, lo, hi, vcap);
      const __m128i q1 = Quantise8(lap8(u + 8), m_round, lo, hi, vcap);
      _mm_storeu_si128(reinterpret_cast<__m128i*>(o + u), _mm_packus_epi16(q0, q1));
    }
#endif
    for (; u < w; ++u) o[u] = Quantise(lap(u), m, cap);
  }
}

// 16 * (G_sigma * I) as CV_16S (separable, border reflect-101).
void Blur16(const cv::Mat& in, double sigma, cv::Mat* out) {
  const int k = KernelSize(sigma);
  const cv::Mat g = cv::getGaussianKernel(k, sigma, CV_32F);
  cv::sepFilter2D(in, *out, CV_16S, g * 16.0, g, cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT_101);
}

}  // namespace

Status Prefilter(const cv::Mat& in, const PrefilterOptions& options, cv::Mat* out) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  if (in.empty()) return InvalidArgument("image to prefilter is empty");
  if (in.type() != CV_8UC1) {
    return InvalidArgument("image to prefilter is " + Describe(in) + "; expected CV_8UC1");
  }
  if (out->size() != in.size() || out->type() != CV_8UC1) out->create(in.size(), CV_8UC1);
  if (options.kind == PrefilterKind::kNone) {
    in.copyTo(*out);
    return Status::Ok();
  }
  // Blurred images carry 4 fractional bits (x16); m scales the response by gain / 16 in Q12.
  const double sign = options.kind == PrefilterKind::kLaplacianOfGaussian ? -1.0 : 1.0;
  const int m = static_cast<int>(std::lround(sign * options.gain / 16.0 * 4096.0));
  cv::Mat inner;
  Blur16(in, options.sigma, &inner);
  if (options.kind == PrefilterKind::kLaplacianOfGaussian) {
    QuantiseResponse(inner, nullptr, m, options.cap, out);
  } else {
    cv::Mat outer;
    Blur16(in, options.sigma_outer, &outer);
    QuantiseResponse(inner, &outer, m, options.cap, out);
  }
  return Status::Ok();
}

}  // namespace rover::dl::stereo
