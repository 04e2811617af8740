#include "rover/dl/stereo/correlator.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "rover/base/check.hpp"
#include "describe.hpp"
#include "worker_pool.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define ROVER_STEREO_X86 1
#endif

namespace rover::dl::stereo {

using internal::Describe;
namespace {

constexpr int kInfCost = 0x7FFF;  // larger than any window cost (checked before correlating)

// Everything one cost row needs; the buffers belong to one thread.
struct RowArgs {
  const std::uint8_t* left;  // padded prefiltered images, row step `step`
  const std::uint8_t* right;
  std::ptrdiff_t step;
  int width;
  int dmin;
  int ndisp;
  std::uint16_t* col;  // ndisp rows of col_step: column sums
  std::uint16_t* sad;  // ndisp rows of col_step: window costs of the current image row
  std::ptrdiff_t col_step;
  std::uint16_t* best;  // per left pixel: best cost and its disparity index
  std::uint16_t* best_k;
  std::uint16_t* rbest;  // per right pixel: best cost and its disparity index
  std::uint16_t* rbest_k;
  std::uint16_t* second;  // per left pixel: best cost away from best_k +-1
  bool need_second;
};
using CostRowFn = void (*)(const RowArgs&, int y, bool first);

namespace scalar {
struct Ops {
  static constexpr int kLanes = 1;
  using V = int;
  static V AbsDiffU8(const std::uint8_t* a, const std::uint8_t* b) {
    return std::abs(static_cast<int>(*a) - static_cast<int>(*b));
  }
  static V Load(const std::uint16_t* p) { return *p; }
  static void Store(std::uint16_t* p, V v) { *p = static_cast<std::uint16_t>(v); }
  static V Add(V a, V b) { return a + b; }
  static V Sub(V a, V b) { return a - b; }
  static V Min(V a, V b) { return a < b ? a : b; }
  static V Lt(V a, V b) { return a < b ? -1 : 0; }
  static V Gt(V a, V b) { return a > b ? -1 : 0; }
  static V Abs(V a) { return a < 0 ? -a : a; }
  static V Select(V m, V a, V b) { return m != 0 ? a : b; }
  static V Set1(int x) { return x; }
  static V AndNot(V a, V b) { return (a == 0 && b != 0) ? -1 : 0; }
  static V Iota() { return 0; }
};
#include "correlator_kernel.inc"
}  // namespace scalar

#if ROVER_STEREO_X86
namespace sse2 {
struct Ops {
  static constexpr int kLanes = 8;
  using V = __m128i;
  static V AbsDiffU8(const std::uint8_t* a, const std::uint8_t* b) {
    const __m128i x = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(a));
    const __m128i y = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(b));
    const __m128i d = _mm_or_si128(_mm_subs_epu8(x, y), _mm_subs_epu8(y, x));
    return _mm_unpacklo_epi8(d, _mm_setzero_si128());
  }
  static V Load(const std::uint16_t* p) {
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  }
  static void Store(std::uint16_t* p, V v) { _mm_storeu_si128(reinterpret_cast<__m128i*>(p), v); }
  static V Add(V a, V b) { return _mm_add_epi16(a, b); }
  static V Sub(V a, V b) { return _mm_sub_epi16(a, b); }
  static V Min(V a, V b) { return _mm_min_epi16(a, b); }
  static V Lt(V a, V b) { return _mm_cmplt_epi16(a, b); }
  static V Gt(V a, V b) { return _mm_cmpgt_epi16(a, b); }
  static V Abs(V a) { return _mm_max_epi16(a, _mm_sub_epi16(_mm_setzero_si128(), a)); }
  static V Select(V m, V a, V b) {
    return _mm_or_si128(_mm_and_si128(m, a), _mm_andnot_si128(m, b));
  }
  static V Set1(int x) { return _mm_set1_epi16(static_cast<short>(x)); }
  static V AndNot(V a, V b) { return _mm_andnot_si128(a, b); }
  static V Iota() { return _mm_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7); }
};
#include "correlator_kernel.inc"
}  // namespace sse2

#pragma GCC push_options
#pragma GCC target("avx2")
namespace avx2 {
struct Ops {
  static constexpr int kLanes = 16;
  using V = __m256i;
  static V AbsDiffU8(const std::uint8_t* a, const std::uint8_t* b) {
    const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a));
    const __m128i y = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b));
    return _mm256_cvtepu8_epi16(_mm_or_si128(_mm_subs_epu8(x, y), _mm_subs_epu8(y, x)));
  }
  static V Load(const std::uint16_t* p) {
    return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
  }
  static void Store(std::uint16_t* p, V v) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), v);
  }
  static V Add(V a, V b) { return _mm256_add_epi16(a, b); }
  static V Sub(V a, V b) { return _mm256_sub_epi16(a, b); }
  static V Min(V a, V b) { return _mm256_min_epi16(a, b); }
  static V Lt(V a, V b) { return _mm256_cmpgt_epi16(b, a); }
  static V Gt(V a, V b) { return _mm256_cmpgt_epi16(a, b); }
  static V Abs(V a) { return _mm256_abs_epi16(a); }
  static V Select(V m, V a, V b) { return _mm256_blendv_epi8(b, a, m); }
  static V Set1(int x) { return _mm256_set1_epi16(static_cast<short>(x)); }
  static V AndNot(V a, V b) { return _mm256_andnot_si256(a, b); }
  static V Iota() {
    return _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  }
};
#include "correlator_kernel.inc"
}  // namespace avx2
#pragma GCC pop_options
#endif  // ROVER_STEREO_X86

CostRowFn SelectKernel(SimdLevel level, int window) {
  switch (level) {
#if ROVER_STEREO_X86
    case SimdLevel::kAvx2:
      return avx2::SelectCostRow(window);
    case SimdLevel::kSse2:
      return sse2::SelectCostRow(window);
#endif
    default:
      return scalar::SelectCostRow(window);
  }
}

bool Supported(SimdLevel level) {
  switch (level) {
    case SimdLevel::kAuto:
    case SimdLevel::kScalar:
      return true;
    case SimdLevel::kSse2:
      return DetectSimdLevel() != SimdLevel::kScalar;
    case SimdLevel::kAvx2:
      return DetectSimdLevel() == SimdLevel::kAvx2;
  }
  return false;
}

std::size_t RoundUp(std::size_t x, std::size_t m) { return (x + m - 1) / m * m; }

// Per-pixel tests and sub-pixel peak for one image row (see correlator.hpp). Branch-free per
// pixel: the status is picked by priority from all test results. `r.sad` has INF sentinel rows
// at disparity indices -1 and ndisp, so C(k*-1) and C(k*+1) can always be read.
struct PostArgs {
  int width;
  int half;
  int dmin;
  int ndisp;
  std::ptrdiff_t col_step;
  bool reject_edge;
  int full_lo, full_hi;  // columns whose search range is complete (if full_only)
  bool full_only;
  int lr_max_diff;     // < 0: off
  int uniqueness_q10;  // (1 + ratio) * 1024; 0: off
  int min_curvature;   // absolute, in cost units
  SubpixelMethod subpixel;
};

// GCC/Clang vector extensions: 4 x int32 / 4 x float, SSE2 on x86-64, portable elsewhere.
using I4 = std::int32_t __attribute__((vector_size(16)));
using F4 = float __attribute__((vector_size(16)));

// Stores the four lanes (each in [0, 255]) as bytes.
inline void StoreBytes4(std::uint8_t* p, I4 v) {
#if defined(__SSE2__)
  const __m128i x = std::bit_cast<__m128i>(v);
  const int word = _mm_cvtsi128_si32(_mm_packus_epi16(_mm_packs_epi32(x, x), x));
  std::memcpy(p, &word, sizeof(word));
#else
  using B4 = std::uint8_t __attribute__((vector_size(4)));
  const B4 b = __builtin_convertvector(v, B4);
  std::memcpy(p, &b, sizeof(b));
#endif
}

inline I4 Load4(const std::uint16_t* p) {
  using U4 = std::uint16_t __attribute__((vector_size(8)));
  U4 v;
  std::memcpy(&v, p, sizeof(v));
  return __builtin_convertvector(v, I4);
}

// Two passes per row: gather C(k*-1), C(k*+1) and the right pixel's best disparity (scalar),
// then the tests and the sub-pixel fit four pixels at a time (no branches, vector division).
void PostRow(const PostArgs& p, const RowArgs& r, std::uint16_t* cm_row, std::uint16_t* cp_row,
             std::uint16_t* rk_row, float* disp, std::uint8_t* status) {
  const int w = p.width;
  constexpr auto kBorderCode = static_cast<std::uint8_t>(PixelStatus::kBorder);
  for (int x = 0; x < p.half; ++x) {
    disp[x] = disp[w - 1 - x] = kInvalidDisparity;
    status[x] = status[w - 1 - x] = kBorderCode;
  }
  const std::ptrdiff_t cs = p.col_step;
  const int x0 = p.half, x1 = w - p.half;
  for (int x = x0; x < x1; ++x) {
    const int k = r.best_k[x];
    cm_row[x] = r.sad[(k - 1) * cs + x];
    cp_row[x] = r.sad[(k + 1) * cs + x];
    rk_row[x] = r.rbest_k[std::clamp(x - p.dmin - k, 0, w - 1)];
  }
  const auto splat = [](int v) { return I4{v, v, v, v}; };
  const I4 inf = splat(kInfCost), zero = splat(0);
  const I4 min_curv = splat(p.min_curvature), q10 = splat(p.uniqueness_q10);
  const I4 lr_max = splat(p.lr_max_diff), dmin = splat(p.dmin);
  const I4 full_lo = splat(p.full_lo), full_hi = splat(p.full_hi);
  const bool use_lr = p.lr_max_diff >= 0, use_uniq = p.uniqueness_q10 > 0;
  const bool parabola = p.subpixel == SubpixelMethod::kParabola;
  const bool fit = p.subpixel != SubpixelMethod::kNone;
  const F4 nan = {kInvalidDisparity, kInvalidDisparity, kInvalidDisparity, kInvalidDisparity};
  const F4 half_f = {0.5f, 0.5f, 0.5f, 0.5f};
  // Process [x0, x1) in blocks of 4; the last block is shifted back to end at x1 (recomputing
  // a few pixels is harmless), rows narrower than 4 pixels fall back to single lanes below.
  for (int xb = x0; x1 - x0 >= 4;) {
    const int x = std::min(xb, x1 - 4);
    const I4 c0 = Load4(r.best + x), k = Load4(r.best_k + x);
    const I4 cm = Load4(cm_row + x), cp = Load4(cp_row + x);
    const I4 s2 = Load4(r.second + x), rk = Load4(rk_row + x);
    const I4 xs = splat(x) + I4{0, 1, 2, 3};
    const I4 no_match = c0 >= inf;
    const I4 edge = (cm >= inf) | (cp >= inf);
    const I4 curv = cm + cp - 2 * c0;
    const I4 flat = ~edge & (curv < min_curv);
    const I4 not_unique = use_uniq ? ((s2 < inf) & (s2 * 1024 <= c0 * q10)) : zero;
    const I4 dk = rk - k;
    const I4 lr = use_lr ? ((dk > lr_max) | (dk < -lr_max)) : zero;
    const I4 partial = p.full_only ? ((xs < full_lo) | (xs >= full_hi)) : zero;
    I4 st = zero;
    st = lr ? splat(static_cast<int>(PixelStatus::kLeftRight)) : st;
    st = not_unique ? splat(static_cast<int>(PixelStatus::kNotUnique)) : st;
    st = flat ? splat(static_cast<int>(PixelStatus::kFlat)) : st;
    st = (p.reject_edge ? edge : zero) ? splat(static_cast<int>(PixelStatus::kRangeEdge)) : st;
    st = no_match ? splat(static_cast<int>(PixelStatus::kNoMatch)) : st;
    st = partial ? splat(static_cast<int>(PixelStatus::kBorder)) : st;
    const I4 den = parabola ? curv : ((cm > cp ? cm : cp) - c0);
    const I4 use_fit = (fit ? ~edge : zero) & (den > zero);
    const F4 num_f = __builtin_convertvector(cm - cp, F4);
    const F4 den_f = __builtin_convertvector(use_fit ? den : splat(1), F4);
    const F4 offset = use_fit ? half_f * num_f / den_f : F4{0, 0, 0, 0};
    const F4 d = __builtin_convertvector(dmin + k, F4) + offset;
    const F4 out = st == zero ? d : nan;
    std::memcpy(disp + x, &out, sizeof(out));
    StoreBytes4(status + x, st);
    if (x == x1 - 4) break;
    xb += 4;
  }
  if (x1 - x0 < 4) {
    for (int x = x0; x < x1; ++x) {  // tiny images: same tests, one pixel at a time
      const int c0 = r.best[x], k = r.best_k[x], cm = cm_row[x], cp = cp_row[x];
      const bool edge = cm >= kInfCost || cp >= kInfCost;
      const int curv = cm + cp - 2 * c0;
      const int dk = rk_row[x] - k;
      auto st = PixelStatus::kValid;
      if (use_lr && (dk > p.lr_max_diff || dk < -p.lr_max_diff)) st = PixelStatus::kLeftRight;
      if (use_uniq && r.second[x] < kInfCost && r.second[x] * 1024 <= c0 * p.uniqueness_q10) {
        st = PixelStatus::kNotUnique;
      }
      if (!edge && curv < p.min_curvature) st = PixelStatus::kFlat;
      if (edge && p.reject_edge) st = PixelStatus::kRangeEdge;
      if (c0 >= kInfCost) st = PixelStatus::kNoMatch;
      if (p.full_only && (x < p.full_lo || x >= p.full_hi)) st = PixelStatus::kBorder;
      const int den = parabola ? curv : std::max(cm, cp) - c0;
      const float offset = (fit && !edge && den > 0)
                               ? 0.5f * static_cast<float>(cm - cp) / static_cast<float>(den)
                               : 0.0f;
      disp[x] =
          st == PixelStatus::kValid ? static_cast<float>(p.dmin + k) + offset : kInvalidDisparity;
      status[x] = static_cast<std::uint8_t>(st);
    }
  }
}

}  // namespace

const char* SimdLevelName(SimdLevel s) {
  switch (s) {
    case SimdLevel::kAuto:
      return "auto";
    case SimdLevel::kScalar:
      return "scalar";
    case SimdLevel::kSse2:
      return "sse2";
    case SimdLevel::kAvx2:
      return "avx2";
  }
  return "unknown";
}

SimdLevel DetectSimdLevel() {
#if ROVER_STEREO_X86
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2")) return SimdLevel::kAvx2;
  if (__builtin_cpu_supports("sse2")) return SimdLevel::kSse2;
#endif
  return SimdLevel::kScalar;
}

Status CorrelatorOptions::Validate() const {
  const auto bad = [](const std::string& what) { return InvalidArgument("correlator." + what); };
  if (window < 3 || window > 15 || window % 2 == 0) {
    return bad("window " + std::to_string(window) + " must be odd and in [3, 15]");
  }
  if (min_disparity < -1024 || min_disparity > 1024) {
    return bad("min_disparity " + std::to_string(min_disparity) + " is outside [-1024, 1024]");
  }
  if (num_disparities < 2 || num_disparities > 512) {
    return bad("num_disparities " + std::to_string(num_disparities) + " is outside [2, 512]");
  }
  if (!(uniqueness_ratio >= 0.0 && uniqueness_ratio <= 2.0)) {
    return bad("uniqueness_ratio " + std::to_string(uniqueness_ratio) + " is outside [0, 2]");
  }
  if (!(min_curvature >= 0.0 && min_curvature <= 255.0)) {
    return bad("min_curvature " + std::to_string(min_curvature) + " is outside [0, 255]");
  }
  if (lr_max_diff < -1 || lr_max_diff > 64) {
    return bad("lr_max_diff " + std::to_string(lr_max_diff) +
               " is outside [0, 64] (or -1 to disable)");
  }
  if (num_threads < 1 || num_threads > 64) {
    return bad("num_threads " + std::to_string(num_threads) + " is outside [1, 64]");
  }
  return Status::Ok();
}

struct Correlator::Scratch {
  std::array<int, 4> layout = {-1, 0, 0, 0};  // width, d_min, D, window the buffers are for
  std::vector<std::uint16_t> col, sad, best, best_k, rbest, rbest_k, second, cm, cp, rk;
};

Correlator::Correlator(const CorrelatorOptions& options, SimdLevel simd)
    : options_(options),
      simd_(simd),
      pool_(std::make_unique<internal::WorkerPool>(options.num_threads - 1)) {}
Correlator::Correlator(Correlator&&) noexcept = default;
Correlator& Correlator::operator=(Correlator&&) noexcept = default;
Correlator::~Correlator() = default;

Result<Correlator> Correlator::Create(const CorrelatorOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  if (!Supported(options.simd)) {
    return InvalidArgument(
        std::string("correlator.simd ") + SimdLevelName(options.simd) +
        " is not supported by this CPU (best: " + SimdLevelName(DetectSimdLevel()) + ")");
  }
  const SimdLevel simd = options.simd == SimdLevel::kAuto ? DetectSimdLevel() : options.simd;
  return Correlator(options, simd);
}

Status Correlator::Compute(const cv::Mat& left, const cv::Mat& right, DisparityImage* out) {
  if (out == nullptr) return InvalidArgument("output disparity image is null");
  if (left.empty()) return InvalidArgument("left image is empty");
  if (right.empty()) return InvalidArgument("right image is empty");
  if (left.type() != CV_8UC1) {
    return InvalidArgument("left image is " + Describe(left) + "; expected CV_8UC1");
  }
  if (right.type() != CV_8UC1) {
    return InvalidArgument("right image is " + Describe(right) + "; expected CV_8UC1");
  }
  if (left.size() != right.size()) {
    return InvalidArgument("left image is " + Describe(left) + " but right image is " +
                           Describe(right) + "; the pair must have equal sizes");
  }
  const int win = options_.window;
  const int half = win / 2;
  const int width = left.cols;
  const int height = left.rows;
  if (width > 16384) {
    return InvalidArgument("image " + Describe(left) + " is wider than 16384 px");
  }
  if (width < win || height < win) {
    return InvalidArgument("image " + Describe(left) + " is smaller than the " +
                           std::to_string(win) + "x" + std::to_string(win) + " window");
  }
  const int dmin = options_.min_disparity;
  const int ndisp = options_.num_disparities;
  const int dmax = dmin + ndisp - 1;
  const int min_abs_d = (dmin <= 0 && dmax >= 0) ? 0 : std::min(std::abs(dmin), std::abs(dmax));
  if (width - min_abs_d < win) {
    return InvalidArgument("disparity range [" + std::to_string(dmin) + ", " +
                           std::to_string(dmax) + "] leaves no pixel to match in an image " +
                           std::to_string(width) + " px wide with a " + std::to_string(win) +
                           " px window");
  }
  double max_l = 0.0, max_r = 0.0;
  cv::minMaxLoc(left, nullptr, &max_l);
  cv::minMaxLoc(right, nullptr, &max_r);
  const double max_value = std::max(max_l, max_r);
  if (max_value * win * win >= kInfCost) {
    return InvalidArgument("input values up to " + std::to_string(static_cast<int>(max_value)) +
                           " overflow 16-bit costs of a " + std::to_string(win) + "x" +
                           std::to_string(win) + " window; keep values below " +
                           std::to_string(kInfCost / (win * win)) +
                           " (lower the prefilter cap) or use a smaller window");
  }
  // The vector kernels need at least one full chunk of pixels per row; tiny images use scalar.
  const int lanes = simd_ == SimdLevel::kAvx2 ? 16 : simd_ == SimdLevel::kSse2 ? 8 : 1;
  const CostRowFn cost_row =
      SelectKernel(width - win + 1 >= lanes ? simd_ : SimdLevel::kScalar, win);
  ROVER_DEMAND(cost_row != nullptr);

  // Padded copies: every row gets 64 spare zero bytes so vector loads may run past the end.
  const std::size_t step = RoundUp(static_cast<std::size_t>(width) + 64, 64);
  const std::size_t bytes = step * static_cast<std::size_t>(height) + 64;
  // Zeroed when (re)allocated; the padding's content never reaches a result anyway.
  if (left_buf_.size() != bytes) left_buf_.assign(bytes, 0);
  if (right_buf_.size() != bytes) right_buf_.assign(bytes, 0);
  for (int v = 0; v < height; ++v) {
    std::memcpy(left_buf_.data() + v * step, left.ptr(v), static_cast<std::size_t>(width));
    std::memcpy(right_buf_.data() + v * step, right.ptr(v), static_cast<std::size_t>(width));
  }

  out->Reset(left.size(), PixelStatus::kBorder);
  const int rows = height - 2 * half;
  // Several bands per thread, taken dynamically (worker_pool.hpp); each band re-initialises
  // its column sums (about two rows' work), so bands are kept at least 48 rows high, and their
  // number is a multiple of the workers where possible so that the split is even.
  const int workers = pool_->workers();
  int bands = std::min(4 * workers, rows / 48);
  if (bands > workers) bands -= bands % workers;
  bands = workers == 1 ? 1 : std::max(1, bands);
  const std::size_t col_step = RoundUp(static_cast<std::size_t>(width) + 32, 16);
  const std::size_t plane = col_step * static_cast<std::size_t>(ndisp);
  const std::size_t sad_plane = col_step * static_cast<std::size_t>(ndisp + 2);  // + sentinels
  const std::size_t rb_margin_left = static_cast<std::size_t>(std::max(dmax, 0)) + 32;
  const std::size_t rb_margin_right = static_cast<std::size_t>(std::max(-dmin, 0)) + 32;
  while (static_cast<int>(scratch_.size()) < workers) {
    scratch_.push_back(std::make_unique<Scratch>());
  }
  const std::array<int, 4> layout = {width, dmin, ndisp, win};
  for (int b = 0; b < workers; ++b) {
    Scratch& s = *scratch_[static_cast<std::size_t>(b)];
    if (s.layout == layout) continue;  // buffers and their INF entries are still right
    s.layout = layout;
    s.col.assign(plane, 0);
    // Costs of disparities outside a pixel's search range stay INF: never written.
    s.sad.assign(sad_plane, static_cast<std::uint16_t>(kInfCost));
    for (auto* v : {&s.best, &s.best_k, &s.second, &s.cm, &s.cp, &s.rk}) v->assign(col_step, 0);
    // Right winners are updated at x - d for whole chunks, so lanes outside the image (whose
    // cost is INF and never wins) still touch memory: pad both sides.
    s.rbest.assign(rb_margin_left + col_step + rb_margin_right,
                   static_cast<std::uint16_t>(kInfCost));
    s.rbest_k.assign(s.rbest.size(), 0);
  }

  PostArgs post{};
  post.width = width;
  post.half = half;
  post.dmin = dmin;
  post.ndisp = ndisp;
  post.col_step = static_cast<std::ptrdiff_t>(col_step);
  post.reject_edge = options_.reject_range_edge;
  post.full_only = options_.full_search_only;
  post.full_lo = std::max(dmax, 0) + half;          // x - d - half >= 0 for every d
  post.full_hi = width - half + std::min(dmin, 0);  // x - d + half <= width - 1 for every d
  post.lr_max_diff = options_.lr_max_diff;
  post.uniqueness_q10 =
      options_.uniqueness_ratio > 0.0
          ? static_cast<int>(std::lround(1024.0 * (1.0 + options_.uniqueness_ratio)))
          : 0;
  post.min_curvature = static_cast<int>(std::ceil(options_.min_curvature * win * win));
  post.subpixel = options_.subpixel;

  const auto run_band = [&](int b, int worker) {
    Scratch& s = *scratch_[static_cast<std::size_t>(worker)];
    RowArgs a{};
    a.left = left_buf_.data();
    a.right = right_buf_.data();
    a.step = static_cast<std::ptrdiff_t>(step);
    a.width = width;
    a.dmin = dmin;
    a.ndisp = ndisp;
    a.col = s.col.data();
    a.sad = s.sad.data() + col_step;  // row -1 is the lower sentinel
    a.col_step = static_cast<std::ptrdiff_t>(col_step);
    a.best = s.best.data();
    a.best_k = s.best_k.data();
    a.rbest = s.rbest.data() + rb_margin_left;
    a.rbest_k = s.rbest_k.data() + rb_margin_left;
    a.second = s.second.data();
    a.need_second = options_.uniqueness_ratio > 0.0;
    const int y0 = half + rows * b / bands;
    const int y1 = half + rows * (b + 1) / bands;
    for (int y = y0; y < y1; ++y) {
      cost_row(a, y, y == y0);
      PostRow(post, a, s.cm.data(), s.cp.data(), s.rk.data(), out->disparity.ptr<float>(y),
              out->status.ptr<std::uint8_t>(y));
    }
  };

  pool_->Run(bands, run_band);
  return Status::Ok();
}

}  // namespace rover::dl::stereo
