// stereo-bench: accuracy and speed of the dl_stereo pipeline against OpenCV's StereoBM and
// StereoSGBM, run on the same images in the same process.
//   (a) Middlebury Cones (450x375, disparities ~0-55): bad-pixel rates (>1 px, >2 px, on
//       non-occluded pixels with an estimate) and density, for all three methods.
//   (b) Speed at 256x256 and 512x512, 64 disparities, 7x7 window, 2 threads: medians of
//       interleaved repeated runs and the ratio ours / StereoBM.
// Usage: stereo-bench [--data-dir DIR] [--repeats N] [--threads N]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "rover/dl/stereo/disparity_io.hpp"
#include "rover/dl/stereo/evaluation.hpp"
#include "rover/dl/stereo/pipeline.hpp"

namespace st = rover::dl::stereo;
using Clock = std::chrono::steady_clock;

namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

double Ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

st::StereoOptions OurOptions(int threads) {
  st::StereoOptions o;
  o.correlator.window = 7;
  o.correlator.min_disparity = 0;
  o.correlator.num_disparities = 64;
  o.correlator.num_threads = threads;
  return o;
}

cv::Ptr<cv::StereoBM> MakeBm() {
  // OpenCV defaults apart from range and window: prefilter XSOBEL cap 31, texture threshold 10,
  // uniqueness 15 %, no speckle filter, no left-right check.
  return cv::StereoBM::create(64, 7);
}

cv::Ptr<cv::StereoSGBM> MakeSgbm() {
  const int bs = 7;
  return cv::StereoSGBM::create(/*minDisparity=*/0, /*numDisparities=*/64, bs,
                                /*P1=*/8 * bs * bs, /*P2=*/32 * bs * bs,
                                /*disp12MaxDiff=*/1, /*preFilterCap=*/63,
                                /*uniquenessRatio=*/10, /*speckleWindowSize=*/100,
                                /*speckleRange=*/2, cv::StereoSGBM::MODE_SGBM);
}

void PrintScore(const char* name, const st::DisparityScore& s, double ms) {
  std::printf("  %-28s %8.2f %8.2f %9.2f %9.2f %7.3f %9.2f\n", name, 100 * s.bad_1px,
              100 * s.bad_2px, 100 * s.density, 100 * s.density_nonocc, s.mean_abs_error, ms);
}

int Accuracy(const std::string& dir, int threads) {
  const std::string cones = dir + "/middlebury-cones";
  if (!std::filesystem::exists(cones + "/left.png")) {
    std::printf("(a) accuracy: SKIPPED, no Middlebury Cones under '%s'\n", cones.c_str());
    return 0;
  }
  auto left = st::LoadGrayImage(cones + "/left.png");
  auto right = st::LoadGrayImage(cones + "/right.png");
  if (!left.ok() || !right.ok()) {
    std::fprintf(stderr, "cannot load Cones: %s %s\n", left.status().ToString().c_str(),
                 right.status().ToString().c_str());
    return 1;
  }
  const cv::Mat gt = cv::imread(cones + "/disp_left.tif", cv::IMREAD_UNCHANGED);
  const cv::Mat nonocc = cv::imread(cones + "/occlusion.png", cv::IMREAD_GRAYSCALE);
  if (gt.empty() || gt.type() != CV_32FC1 || nonocc.empty()) {
    std::fprintf(stderr, "cannot load Cones ground truth or occlusion mask\n");
    return 1;
  }
  std::printf("(a) Middlebury Cones %dx%d, disparities [0, 64), 7x7 window\n", left->cols,
              left->rows);
  std::printf("  %-28s %8s %8s %9s %9s %7s %9s\n", "method", "bad>1%", "bad>2%", "density%",
              "dens.noc%", "MAE px", "time ms");

  auto pipe = st::StereoPipeline::Create(OurOptions(threads));
  if (!pipe.ok()) {
    std::fprintf(stderr, "%s\n", pipe.status().ToString().c_str());
    return 1;
  }
  st::StereoInput in;
  in.left = *left;
  in.right = *right;
  st::StereoOutput out;
  std::vector<double> t_ours;
  for (int i = 0; i < 5; ++i) {
    const auto a = Clock::now();
    if (auto s = pipe->Process(in, &out); !s.ok()) {
      std::fprintf(stderr, "%s\n", s.ToString().c_str());
      return 1;
    }
    t_ours.push_back(Ms(a, Clock::now()));
  }
  auto ours = st::ScoreDisparity(out.disparity.disparity, gt, nonocc);

  cv::Mat fixed;
  std::vector<double> t_bm, t_sgbm;
  auto bm = MakeBm();
  for (int i = 0; i < 5; ++i) {
    const auto a = Clock::now();
    bm->compute(*left, *right, fixed);
    t_bm.push_back(Ms(a, Clock::now()));
  }
  auto bm_disp = st::FromOpenCvDisparity(fixed, 0);
  auto bm_score = st::ScoreDisparity(*bm_disp, gt, nonocc);
  auto sgbm = MakeSgbm();
  for (int i = 0; i < 3; ++i) {
    const auto a = Clock::now();
    sgbm->compute(*left, *right, fixed);
    t_sgbm.push_back(Ms(a, Clock::now()));
  }
  auto sgbm_disp = st::FromOpenCvDisparity(fixed, 0);
  auto sgbm_score = st::ScoreDisparity(*sgbm_disp, gt, nonocc);
  if (!ours.ok() || !bm_score.ok() || !sgbm_score.ok()) {
    std::fprintf(stderr, "scoring failed\n");
    return 1;
  }
  PrintScore("dl_stereo (ours)", *ours, Median(t_ours));
  PrintScore("OpenCV StereoBM", *bm_score, Median(t_bm));
  PrintScore("OpenCV StereoSGBM", *sgbm_score, Median(t_sgbm));
  std::printf("  ours / StereoBM: density x%.2f, bad>1 x%.2f, bad>2 x%.2f\n",
              ours->density / bm_score->density, ours->bad_1px / bm_score->bad_1px,
              ours->bad_2px / bm_score->bad_2px);
  std::printf("  ours, pixels per status:");
  for (int i = 0; i < st::kNumPixelStatus; ++i) {
    if (out.counts[static_cast<std::size_t>(i)] > 0) {
      std::printf(" %s=%d", st::PixelStatusName(static_cast<st::PixelStatus>(i)),
                  out.counts[static_cast<std::size_t>(i)]);
    }
  }
  std::printf("\n");
  return 0;
}

// A pair of size n x n: Cones resized if available, else seeded smooth random texture shifted
// by 12 px.
void MakePair(const std::string& dir, int n, cv::Mat* left, cv::Mat* right) {
  auto l = st::LoadGrayImage(dir + "/middlebury-cones/left.png");
  auto r = st::LoadGrayImage(dir + "/middlebury-cones/right.png");
  if (l.ok() && r.ok() && l->type() == CV_8UC1) {
    cv::resize(*l, *left, cv::Size(n, n), 0, 0, cv::INTER_AREA);
    cv::resize(*r, *right, cv::Size(n, n), 0, 0, cv::INTER_AREA);
    return;
  }
  cv::Mat tex(n, n + 16, CV_8UC1);
  cv::RNG rng(12345);
  rng.fill(tex, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(tex, tex, cv::Size(5, 5), 1.2);
  *left = tex(cv::Rect(12, 0, n, n)).clone();
  *right = tex(cv::Rect(0, 0, n, n)).clone();
}

int Speed(const std::string& dir, int threads, int repeats) {
  std::printf("(b) speed: 64 disparities, 7x7 window, %d threads each, %d interleaved runs\n",
              threads, repeats);
  std::printf("  %-9s %9s %9s %9s %9s %9s   %s\n", "size", "BM med", "ours med", "ratio",
              "pair med", "min ratio", "ours median stages: prefilter / correlate / filters ms");
  for (const int n : {256, 512}) {
    cv::Mat left, right;
    MakePair(dir, n, &left, &right);
    auto pipe = st::StereoPipeline::Create(OurOptions(threads));
    if (!pipe.ok()) return 1;
    auto bm = MakeBm();
    st::StereoInput in;
    in.left = left;
    in.right = right;
    st::StereoOutput out;
    cv::Mat fixed;
    std::vector<double> t_ours, t_bm, t_pair, t_pre, t_cor, t_fil;
    for (int i = 0; i < repeats + 3; ++i) {
      const auto a = Clock::now();
      if (!pipe->Process(in, &out).ok()) return 1;
      const auto b = Clock::now();
      bm->compute(left, right, fixed);
      const auto c = Clock::now();
      if (i < 3) continue;  // warm-up
      t_ours.push_back(Ms(a, b));
      t_bm.push_back(Ms(b, c));
      t_pair.push_back(Ms(a, b) / Ms(b, c));
      t_pre.push_back(out.timings.prefilter_ms + out.timings.prepare_ms);
      t_cor.push_back(out.timings.correlate_ms);
      t_fil.push_back(out.timings.filter_ms);
    }
    const double bm_ms = Median(t_bm);
    const double ours_ms = Median(t_ours);
    const double min_ratio = *std::min_element(t_ours.begin(), t_ours.end()) /
                             *std::min_element(t_bm.begin(), t_bm.end());
    std::printf("  %4dx%-4d %9.3f %9.3f %9.2f %9.2f %9.2f   %.3f / %.3f / %.3f\n", n, n, bm_ms,
                ours_ms, ours_ms / bm_ms, Median(t_pair), min_ratio, Median(t_pre), Median(t_cor),
                Median(t_fil));
  }
  std::printf(
      "  ratio = ours median / BM median; pair med = median of per-run ratios (each run of ours\n"
      "  is followed by one of BM); min ratio = fastest ours / fastest BM. ours = the full\n"
      "  pipeline: prefilter, correlation with all tests, sub-pixel, border, blob and overhang\n"
      "  filters, status counts.\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"stereo-bench: dl_stereo against OpenCV StereoBM / StereoSGBM"};
  std::string dir;
  if (const char* env = std::getenv("ROVER_SHARED_DATA_DIR")) dir = env;
#ifdef ROVER_SHARED_DATA_DIR
  if (dir.empty()) dir = ROVER_SHARED_DATA_DIR;
#endif
  int repeats = 50;
  int threads = 2;
  bool skip_accuracy = false, skip_speed = false;
  app.add_option("--data-dir", dir, "folder holding middlebury-cones/")->capture_default_str();
  app.add_option("--repeats", repeats, "timed runs per size")->check(CLI::Range(1, 100000));
  app.add_option("--threads", threads, "threads for ours and OpenCV")->check(CLI::Range(1, 64));
  app.add_flag("--no-accuracy", skip_accuracy, "skip part (a)");
  app.add_flag("--no-speed", skip_speed, "skip part (b)");
  CLI11_PARSE(app, argc, argv);
  cv::setNumThreads(threads);
  st::StereoOptions o = OurOptions(threads);
  std::printf(
      "ours: prefilter %s sigma %.2f gain %.2f cap %d; SAD %dx%d; uniqueness %.2f; "
      "min curvature %.2f; L/R max diff %d; blob min area %d; overhang %s; simd %s\n",
      st::PrefilterKindName(o.prefilter.kind), o.prefilter.sigma, o.prefilter.gain, o.prefilter.cap,
      o.correlator.window, o.correlator.window, o.correlator.uniqueness_ratio,
      o.correlator.min_curvature, o.correlator.lr_max_diff, o.filters.blob_min_area,
      o.filters.overhang ? "on" : "off", st::SimdLevelName(st::DetectSimdLevel()));
  std::printf(
      "StereoBM: numDisparities 64, blockSize 7, OpenCV defaults otherwise "
      "(XSOBEL prefilter cap 31, textureThreshold 10, uniquenessRatio 15)\n");
  std::printf(
      "StereoSGBM: numDisparities 64, blockSize 7, P1 392, P2 1568, disp12MaxDiff 1, "
      "preFilterCap 63, uniquenessRatio 10, speckle 100/2, MODE_SGBM\n");
  int rc = 0;
  if (!skip_accuracy) rc |= Accuracy(dir, threads);
  if (!skip_speed) rc |= Speed(dir, threads, repeats);
  return rc;
}
