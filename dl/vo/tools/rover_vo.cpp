// rover-vo: runs MER visual odometry (dl_vo) over a folder in the KITTI odometry layout
// (image_l/ + image_r/ or image_0/ + image_1/, calib.txt, optional times.txt and poses.txt) and
// writes the camera poses T_0_i in KITTI's format, 12 numbers per line.
//
//   rover-vo --input DIR --output poses.txt [--preset automotive|rover] [--stats stats.csv] ...
//
// Without wheel odometry the prior of each step is the previous step's motion (constant
// velocity); a step that does not converge is replaced by that prior and reported. Progress goes
// to stderr: a progress bar with ETA on a terminal, one plain line per frame otherwise.

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "rover/dl/vo/kitti.hpp"
#include "rover/dl/vo/visual_odometry.hpp"

namespace {

namespace vo = rover::dl::vo;
namespace kitti = rover::dl::vo::kitti;
using Clock = std::chrono::steady_clock;

std::string Duration(double s) {
  char buf[32];
  if (s < 60.0) {
    std::snprintf(buf, sizeof(buf), "%.1fs", s);
  } else {
    std::snprintf(buf, sizeof(buf), "%dm%02ds", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
  }
  return buf;
}

class Progress {
 public:
  Progress(std::size_t total, bool tty) : total_(total), tty_(tty), start_(Clock::now()) {}

  void Update(std::size_t done, const vo::MotionEstimate& e, double ms) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if (!tty_) {
      std::fprintf(stderr, "frame %zu/%zu %s inliers %d %.0f ms%s%s\n", done, total_,
                   vo::MotionStatusName(e.status), e.inliers, ms, e.message.empty() ? "" : ": ",
                   e.converged() ? "" : e.message.c_str());
      return;
    }
    const double frac = static_cast<double>(done) / static_cast<double>(total_);
    const int width = 30;
    const int filled = static_cast<int>(std::lround(frac * width));
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(static_cast<std::size_t>(width), '.');
    const double eta =
        done > 0 ? elapsed / static_cast<double>(done) * static_cast<double>(total_ - done) : 0.0;
    std::fprintf(stderr, "\r\033[K[%s] %zu/%zu %3.0f%%  %s elapsed  ETA %s  failed %d", bar.c_str(),
                 done, total_, 100.0 * frac, Duration(elapsed).c_str(), Duration(eta).c_str(),
                 failed_);
    std::fflush(stderr);
  }
  void CountFailure() { ++failed_; }
  void Finish() {
    if (tty_) std::fprintf(stderr, "\n");
  }

 private:
  std::size_t total_;
  bool tty_;
  Clock::time_point start_;
  int failed_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rover-vo: MER visual odometry over a KITTI-layout stereo sequence"};
  std::string input, output, stats_path, preset = "automotive";
  double max_translation = 0.0, max_rotation_deg = 0.0, pixel_sigma = 0.0;
  int first = 0, count = 0;
  bool quiet = false;
  app.add_option("-i,--input", input, "sequence folder: image_l/ image_r/ calib.txt")->required();
  app.add_option("-o,--output", output, "poses file to write (KITTI format)")->required();
  app.add_option("--preset", preset, "option defaults: automotive (KITTI-like) or rover")
      ->check(CLI::IsMember({"automotive", "rover"}))
      ->capture_default_str();
  app.add_option("--stats", stats_path, "also write a per-frame CSV (status, features, sigma)");
  app.add_option("--first", first, "first frame to process")->check(CLI::NonNegativeNumber);
  app.add_option("--count", count, "frames to process (0 = to the end)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-translation", max_translation, "sanity limit per step [m] (preset)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-rotation-deg", max_rotation_deg, "sanity limit per step [deg] (preset)")
      ->check(CLI::Range(0.001, 180.0));
  app.add_option("--pixel-sigma", pixel_sigma, "matching noise [px] (preset)")
      ->check(CLI::PositiveNumber);
  app.add_flag("-q,--quiet", quiet, "no progress output");
  CLI11_PARSE(app, argc, argv);

  const auto seq = kitti::OpenSequence(input);
  if (!seq.ok()) {
    std::fprintf(stderr, "rover-vo: %s\n", seq.status().message().c_str());
    return 2;
  }
  if (static_cast<std::size_t>(first) >= seq->size()) {
    std::fprintf(stderr, "rover-vo: --first %d but the sequence has %zu frames\n", first,
                 seq->size());
    return 2;
  }
  const std::size_t end =
      count > 0 ? std::min(seq->size(), static_cast<std::size_t>(first + count)) : seq->size();

  vo::Options options = preset == "rover" ? vo::Options::Rover() : vo::Options::Automotive();
  if (max_translation > 0.0) options.max_translation = max_translation;
  if (max_rotation_deg > 0.0) options.max_rotation = max_rotation_deg * std::numbers::pi / 180.0;
  if (pixel_sigma > 0.0) options.pixel_sigma = pixel_sigma;
  auto odo = vo::VisualOdometry::Create(options, seq->camera);
  if (!odo.ok()) {
    std::fprintf(stderr, "rover-vo: %s\n", odo.status().message().c_str());
    return 2;
  }
  std::ofstream out(output);
  if (!out) {
    std::fprintf(stderr, "rover-vo: cannot write '%s'\n", output.c_str());
    return 2;
  }
  std::ofstream stats;
  if (!stats_path.empty()) {
    stats.open(stats_path);
    if (!stats) {
      std::fprintf(stderr, "rover-vo: cannot write '%s'\n", stats_path.c_str());
      return 2;
    }
    stats << "frame,time_s,status,features_selected,features_stereo,features_tracked,inliers,"
             "sigma_x_m,sigma_y_m,sigma_z_m,sigma_rot_deg,ms,message\n";
  }

  const bool tty = ::isatty(STDERR_FILENO) != 0;
  Progress progress(end - static_cast<std::size_t>(first), tty);
  const kitti::ConstantVelocityModel model;
  vo::MotionEstimate last;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  int failures = 0;
  for (std::size_t i = static_cast<std::size_t>(first); i < end; ++i) {
    const auto frame = kitti::LoadFrame(*seq, i);
    if (!frame.ok()) {
      progress.Finish();
      std::fprintf(stderr, "rover-vo: %s\n", frame.status().message().c_str());
      return 1;
    }
    const auto t0 = Clock::now();
    const auto est = odo->Process(*frame, model.Next(last));
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    if (!est.ok()) {
      progress.Finish();
      std::fprintf(stderr, "rover-vo: frame %zu: %s\n", i, est.status().message().c_str());
      return 1;
    }
    if (i > static_cast<std::size_t>(first)) {
      pose = pose * est->delta;  // the prior on failure
      if (!est->converged()) {
        ++failures;
        progress.CountFailure();
      }
    }
    last = *est;
    out << kitti::FormatPose(pose) << '\n';
    if (stats.is_open()) {
      const vo::Vector6d sd = est->covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
      std::string msg = est->message;
      for (char& c : msg) {
        if (c == ',' || c == '"') c = ';';
      }
      stats << i << ',' << frame->stamp.seconds() << ',' << vo::MotionStatusName(est->status) << ','
            << est->features_selected << ',' << est->features_stereo << ',' << est->features_tracked
            << ',' << est->inliers << ',' << sd(0) << ',' << sd(1) << ',' << sd(2) << ','
            << sd.tail<3>().norm() * 180.0 / std::numbers::pi << ',' << ms << ',' << msg << '\n';
    }
    if (!quiet) progress.Update(i - static_cast<std::size_t>(first) + 1, *est, ms);
  }
  if (!quiet) progress.Finish();
  out.flush();
  if (!out) {
    std::fprintf(stderr, "rover-vo: error writing '%s'\n", output.c_str());
    return 1;
  }
  std::fprintf(stderr, "rover-vo: wrote %zu poses to %s (%d step(s) without a VO measurement)\n",
               end - static_cast<std::size_t>(first), output.c_str(), failures);
  if (!seq->poses_file.empty() && first == 0) {
    const auto truth = kitti::ReadPoses(seq->poses_file);
    const auto est = kitti::ReadPoses(output);
    if (truth.ok() && est.ok() && truth->size() >= est->size()) {
      const std::vector<Eigen::Isometry3d> gt(truth->begin(),
                                              truth->begin() + static_cast<long>(est->size()));
      const auto lengths = kitti::SegmentLengths(kitti::PathLength(gt));
      const kitti::ErrorMetrics m = kitti::Evaluate(gt, *est, lengths);
      std::fprintf(stderr,
                   "rover-vo: against poses.txt: %.2f %% translation, %.4f deg/m over %d "
                   "segments of %.0f-%.0f m; end point %.2f %% of %.1f m\n",
                   m.translation_percent, m.rotation_deg_per_m, m.segments, lengths.front(),
                   lengths.back(), m.endpoint_percent, m.path_length);
    }
  }
  return 0;
}
