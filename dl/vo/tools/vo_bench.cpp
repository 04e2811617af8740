// vo-bench: MER visual odometry (dl_vo) over a KITTI-layout sequence, scored with KITTI's
// odometry metric, against a simple OpenCV pipeline (goodFeaturesToTrack + pyramidal LK for
// stereo and tracking + solvePnPRansac) run on the same frames in the same process.
//
//   vo-bench [--sequence DIR] [--repeat N] [--verbose]
//
// Timing covers the per-frame processing only (images are loaded beforehand); the reported
// ms/frame is the median over --repeat runs. Not a test: it prints numbers, it does not judge.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <string>
#include <vector>

#include "rover/dl/vo/kitti.hpp"
#include "rover/dl/vo/visual_odometry.hpp"

namespace {

using rover::dl::vo::Matrix6d;
using rover::dl::vo::MotionError;
using rover::dl::vo::Vector6d;
namespace vo = rover::dl::vo;
namespace kitti = rover::dl::vo::kitti;
using Clock = std::chrono::steady_clock;
constexpr double kDegPerRad = 180.0 / std::numbers::pi;

struct Run {
  std::vector<Eigen::Isometry3d> poses;   // T_0_i
  std::vector<Eigen::Isometry3d> deltas;  // T_(i-1)_i, deltas[0] = identity
  std::vector<Matrix6d> covariances;      // dl_vo only
  std::vector<bool> converged;
  double total_ms = 0.0;
};

Run RunDlVo(const vo::StereoCamera& camera, const std::vector<vo::StereoFrame>& frames,
            const vo::Options& options) {
  Run run;
  auto odo = vo::VisualOdometry::Create(options, camera);
  if (!odo.ok()) {
    std::fprintf(stderr, "vo-bench: %s\n", odo.status().ToString().c_str());
    std::exit(1);
  }
  const kitti::ConstantVelocityModel model;
  vo::MotionEstimate last;
  run.poses.push_back(Eigen::Isometry3d::Identity());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const vo::MotionPrior prior = model.Next(last);
    const auto t0 = Clock::now();
    auto est = odo->Process(frames[i], prior);
    run.total_ms += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    if (!est.ok()) {
      std::fprintf(stderr, "vo-bench: frame %zu: %s\n", i, est.status().ToString().c_str());
      std::exit(1);
    }
    last = *est;
    run.deltas.push_back(i == 0 ? Eigen::Isometry3d::Identity() : est->delta);
    run.covariances.push_back(est->covariance);
    run.converged.push_back(i == 0 || est->converged());
    if (i > 0) run.poses.push_back(run.poses.back() * est->delta);
  }
  return run;
}

// The baseline: features in the previous left image, LK into the previous right image (stereo,
// same row within 1 px) and into the new left image, PnP with RANSAC on 3D-2D.
Run RunOpenCv(const vo::StereoCamera& c, const std::vector<vo::StereoFrame>& frames) {
  Run run;
  const cv::Mat k = (cv::Mat_<double>(3, 3) << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  run.poses.push_back(Eigen::Isometry3d::Identity());
  run.deltas.push_back(Eigen::Isometry3d::Identity());
  run.converged.push_back(true);
  Eigen::Isometry3d last = Eigen::Isometry3d::Identity();
  for (std::size_t i = 1; i < frames.size(); ++i) {
    const auto t0 = Clock::now();
    const cv::Mat& pl = frames[i - 1].left;
    std::vector<cv::Point2f> p0, p0r, p1;
    std::vector<uchar> st_s, st_t;
    std::vector<float> err;
    cv::goodFeaturesToTrack(pl, p0, 1000, 0.01, 10);
    bool ok = !p0.empty();
    std::vector<cv::Point3f> xyz;
    std::vector<cv::Point2f> uv;
    if (ok) {
      cv::calcOpticalFlowPyrLK(pl, frames[i - 1].right, p0, p0r, st_s, err, cv::Size(21, 21), 3);
      cv::calcOpticalFlowPyrLK(pl, frames[i].left, p0, p1, st_t, err, cv::Size(21, 21), 3);
      for (std::size_t j = 0; j < p0.size(); ++j) {
        if (!st_s[j] || !st_t[j]) continue;
        const double d = p0[j].x - p0r[j].x;
        if (std::abs(p0[j].y - p0r[j].y) > 1.0 || d < 1.0) continue;
        const double z = c.fx * c.baseline / d;
        if (z > 80.0) continue;
        xyz.emplace_back(static_cast<float>((p0[j].x - c.cx) * z / c.fx),
                         static_cast<float>((p0[j].y - c.cy) * z / c.fy), static_cast<float>(z));
        uv.push_back(p1[j]);
      }
    }
    cv::Mat rvec, tvec;
    std::vector<int> inliers;
    ok = xyz.size() >= 6 &&
         cv::solvePnPRansac(xyz, uv, k, cv::noArray(), rvec, tvec, false, 200, 1.0f, 0.999,
                            inliers) &&
         inliers.size() >= 6;
    Eigen::Isometry3d delta = last;  // constant velocity on failure
    if (ok) {
      cv::Mat r;
      cv::Rodrigues(rvec, r);
      Eigen::Isometry3d t_cur_prev = Eigen::Isometry3d::Identity();
      for (int a = 0; a < 3; ++a) {
        t_cur_prev.translation()(a) = tvec.at<double>(a);
        for (int b = 0; b < 3; ++b) t_cur_prev.linear()(a, b) = r.at<double>(a, b);
      }
      delta = t_cur_prev.inverse();
    }
    run.total_ms += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    last = delta;
    run.deltas.push_back(delta);
    run.converged.push_back(ok);
    run.poses.push_back(run.poses.back() * delta);
  }
  return run;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

int Count(const std::vector<bool>& v) {
  return static_cast<int>(std::count(v.begin(), v.end(), true));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vo-bench: MER visual odometry on a KITTI sequence vs an OpenCV baseline"};
  std::string sequence = std::string(ROVER_SHARED_DATA_DIR) + "/kitti-seq1";
  int repeat = 3;
  bool verbose = false;
  app.add_option("--sequence", sequence, "folder in the KITTI odometry layout with poses.txt")
      ->capture_default_str();
  app.add_option("--repeat", repeat, "runs of each pipeline; ms/frame is their median")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  app.add_flag("--verbose", verbose, "print the per-frame errors");
  CLI11_PARSE(app, argc, argv);

  const auto seq = kitti::OpenSequence(sequence);
  if (!seq.ok()) {
    std::fprintf(stderr, "vo-bench: %s\n", seq.status().ToString().c_str());
    return 2;
  }
  if (seq->poses_file.empty()) {
    std::fprintf(stderr, "vo-bench: %s has no poses.txt (ground truth)\n", sequence.c_str());
    return 2;
  }
  const auto truth = kitti::ReadPoses(seq->poses_file);
  if (!truth.ok() || truth->size() < seq->size()) {
    std::fprintf(
        stderr, "vo-bench: %s\n",
        truth.ok() ? "poses.txt has fewer poses than frames" : truth.status().ToString().c_str());
    return 2;
  }
  std::vector<vo::StereoFrame> frames;
  for (std::size_t i = 0; i < seq->size(); ++i) {
    auto f = kitti::LoadFrame(*seq, i);
    if (!f.ok()) {
      std::fprintf(stderr, "vo-bench: %s\n", f.status().ToString().c_str());
      return 2;
    }
    frames.push_back(std::move(f).value());
  }
  const std::vector<Eigen::Isometry3d> gt(truth->begin(), truth->begin() + seq->size());
  const double path = kitti::PathLength(gt);
  const std::vector<double> lengths = kitti::SegmentLengths(path);

  const vo::Options options = vo::Options::Automotive();
  std::vector<double> ms_vo, ms_cv;
  Run ours, base;
  for (int r = 0; r < repeat; ++r) {
    ours = RunDlVo(seq->camera, frames, options);
    base = RunOpenCv(seq->camera, frames);
    ms_vo.push_back(ours.total_ms / static_cast<double>(frames.size() - 1));
    ms_cv.push_back(base.total_ms / static_cast<double>(frames.size() - 1));
  }
  const kitti::ErrorMetrics m_vo = kitti::Evaluate(gt, ours.poses, lengths);
  const kitti::ErrorMetrics m_cv = kitti::Evaluate(gt, base.poses, lengths);

  // Per-step errors: the mean along-track error (z) shows a scale bias shared by both pipelines
  // (camera calibration / ground truth), the NEES the consistency of dl_vo's covariance.
  double z_vo = 0.0, z_cv = 0.0, nees = 0.0, nees_t = 0.0, nees_r = 0.0;
  double rot_vo_gt = 0.0, rot_cv_gt = 0.0, rot_vo_cv = 0.0;  // sums of squared angles
  int n_nees = 0;
  for (std::size_t i = 1; i < frames.size(); ++i) {
    const Eigen::Isometry3d dg = gt[i - 1].inverse() * gt[i];
    const Vector6d e_vo = MotionError(ours.deltas[i], dg);
    const Vector6d e_cv = MotionError(base.deltas[i], dg);
    z_vo += e_vo(2);
    z_cv += e_cv(2);
    rot_vo_gt += e_vo.tail<3>().squaredNorm();
    rot_cv_gt += e_cv.tail<3>().squaredNorm();
    rot_vo_cv += MotionError(ours.deltas[i], base.deltas[i]).tail<3>().squaredNorm();
    if (ours.converged[i]) {
      const Matrix6d& c = ours.covariances[i];
      nees += e_vo.dot(c.ldlt().solve(e_vo));
      const Eigen::Vector3d et = e_vo.head<3>(), er = e_vo.tail<3>();
      nees_t += et.dot(c.topLeftCorner<3, 3>().ldlt().solve(et));
      nees_r += er.dot(c.bottomRightCorner<3, 3>().ldlt().solve(er));
      ++n_nees;
    }
    if (verbose) {
      std::printf(
          "frame %2zu  dl_vo %-4s err t [mm] %7.1f %7.1f %7.1f  r [deg] %7.3f %7.3f %7.3f"
          "   opencv err t [mm] %7.1f %7.1f %7.1f\n",
          i, ours.converged[i] ? "ok" : "FAIL", 1e3 * e_vo(0), 1e3 * e_vo(1), 1e3 * e_vo(2),
          e_vo(3) * kDegPerRad, e_vo(4) * kDegPerRad, e_vo(5) * kDegPerRad, 1e3 * e_cv(0),
          1e3 * e_cv(1), 1e3 * e_cv(2));
    }
  }
  const double steps = static_cast<double>(frames.size() - 1);
  std::string lens;
  for (double l : lengths) lens += (lens.empty() ? "" : ", ") + std::to_string(int(l));

  std::printf("vo-bench: %s, %zu frames, %.1f m ground-truth path, %d run(s)\n", sequence.c_str(),
              frames.size(), path, repeat);
  std::printf(
      "KITTI metric over sub-sequences of %s m from every frame (%d segments); KITTI's own\n"
      "100-800 m lengths do not fit a %.0f m sequence.\n\n",
      lens.c_str(), m_vo.segments, path);
  std::printf("%-28s %10s %12s %11s %10s %10s\n", "", "trans [%]", "rot [deg/m]", "end pt [%]",
              "ms/frame", "converged");
  std::printf("%-28s %10.2f %12.4f %11.2f %10.1f %7d/%d\n", "dl_vo (MER VO, automotive)",
              m_vo.translation_percent, m_vo.rotation_deg_per_m, m_vo.endpoint_percent,
              Median(ms_vo), Count(ours.converged) - 1, static_cast<int>(steps));
  std::printf("%-28s %10.2f %12.4f %11.2f %10.1f %7d/%d\n", "OpenCV GFTT+LK+PnPRansac",
              m_cv.translation_percent, m_cv.rotation_deg_per_m, m_cv.endpoint_percent,
              Median(ms_cv), Count(base.converged) - 1, static_cast<int>(steps));
  auto ratio = [](double a, double b) { return b > 0.0 ? a / b : 0.0; };
  std::printf("%-28s %10.2f %12.2f %11.2f %10.2f\n\n", "ratio dl_vo / OpenCV",
              ratio(m_vo.translation_percent, m_cv.translation_percent),
              ratio(m_vo.rotation_deg_per_m, m_cv.rotation_deg_per_m),
              ratio(m_vo.endpoint_percent, m_cv.endpoint_percent),
              ratio(Median(ms_vo), Median(ms_cv)));
  std::printf(
      "anchor (context only): libviso2 2.44 %% translational error on the KITTI leaderboard\n"
      "  (100-800 m segments over the whole benchmark, not this sequence)\n");
  std::printf("goal: dl_vo under 2 %% -> %s\n", m_vo.translation_percent < 2.0 ? "met" : "NOT met");
  std::printf(
      "mean along-track error per %.2f m step: dl_vo %+.1f mm, OpenCV %+.1f mm (a shared\n"
      "  offset points at the calibration or ground-truth scale, not at either method)\n",
      path / steps, 1e3 * z_vo / steps, 1e3 * z_cv / steps);
  const double nn = std::max(1, n_nees);
  std::printf(
      "dl_vo covariance vs ground truth over %d steps: mean NEES %.1f (6 if consistent);\n"
      "  translation part %.1f (3 if consistent), rotation part %.1f (3 if consistent)\n",
      n_nees, nees / nn, nees_t / nn, nees_r / nn);
  std::printf(
      "per-step rotation, rms: dl_vo vs truth %.4f deg, OpenCV vs truth %.4f deg, dl_vo vs\n"
      "  OpenCV %.4f deg: the two methods agree better than either agrees with the ground\n"
      "  truth, whose frame-to-frame attitude noise dominates the rotation NEES\n",
      std::sqrt(rot_vo_gt / steps) * kDegPerRad, std::sqrt(rot_cv_gt / steps) * kDegPerRad,
      std::sqrt(rot_vo_cv / steps) * kDegPerRad);
  return 0;
}
