#include "rover/dl/vo/kitti.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "rover/dl/vo/rigid_motion.hpp"

namespace rover::dl::vo::kitti {

namespace fs = std::filesystem;

namespace {

Result<std::string> ReadText(const std::string& path) {
  std::ifstream in(path);
  if (!in) return NotFound("cannot open '" + path + "'");
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

bool IsImage(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".pgm" || ext == ".tif" ||
         ext == ".tiff" || ext == ".bmp";
}

std::vector<std::string> ListImages(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.is_regular_file() && IsImage(e.path())) out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

Status ParseCalibration(const std::string& text, const std::string& source,
                        Eigen::Matrix<double, 3, 4>* p_left, Eigen::Matrix<double, 3, 4>* p_right) {
  std::istringstream in(text);
  std::string line;
  std::vector<Eigen::Matrix<double, 3, 4>> mats;
  int line_no = 0;
  while (std::getline(in, line) && mats.size() < 2) {
    ++line_no;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    std::string body = line.substr(first);
    if (const auto colon = body.find(':'); colon != std::string::npos) {
      body = body.substr(colon + 1);  // "P0: ..." prefix
    }
    std::istringstream ls(body);
    std::vector<double> v;
    std::string tok;
    while (ls >> tok) {
      char* end = nullptr;
      const double d = std::strtod(tok.c_str(), &end);
      if (end == tok.c_str() || *end != '\0' || !std::isfinite(d)) {
        return InvalidArgument(source + ":" + std::to_string(line_no) + ": '" + tok +
                               "' is not a finite number");
      }
      v.push_back(d);
    }
    if (v.size() != 12) {
      return InvalidArgument(source + ":" + std::to_string(line_no) +
                             ": expected 12 numbers "
                             "(a 3x4 projection matrix), got " +
                             std::to_string(v.size()));
    }
    Eigen::Matrix<double, 3, 4> m;
    for (int k = 0; k < 12; ++k) m(k / 4, k % 4) = v[static_cast<std::size_t>(k)];
    mats.push_back(m);
  }
  if (mats.size() < 2) {
    return InvalidArgument(source + ": expected two projection matrices (left, right), found " +
                           std::to_string(mats.size()));
  }
  *p_left = mats[0];
  *p_right = mats[1];
  return Status::Ok();
}

Result<Sequence> OpenSequence(const std::string& folder) {
  const fs::path root(folder);
  std::error_code ec;
  if (!fs::is_directory(root, ec)) {
    return NotFound("sequence folder '" + folder + "' does not exist or is not a folder");
  }
  Sequence seq;
  seq.folder = folder;
  fs::path ldir = root / "image_l", rdir = root / "image_r";
  if (!fs::is_directory(ldir, ec) && fs::is_directory(root / "image_0", ec)) {
    ldir = root / "image_0";
    rdir = root / "image_1";
  }
  if (!fs::is_directory(ldir, ec)) {
    return NotFound("'" + folder + "' has no image_l/ (or image_0/) folder of left images");
  }
  if (!fs::is_directory(rdir, ec)) {
    return NotFound("'" + folder + "' has no " + rdir.filename().string() +
                    "/ folder of right images");
  }
  seq.left_files = ListImages(ldir);
  if (seq.left_files.empty()) return NotFound("no images in '" + ldir.string() + "'");
  for (const std::string& l : seq.left_files) {
    const fs::path r = rdir / fs::path(l).filename();
    if (!fs::is_regular_file(r, ec)) {
      return NotFound("right image '" + r.string() + "' missing for left image '" + l + "'");
    }
    seq.right_files.push_back(r.string());
  }
  const std::string calib_path = (root / "calib.txt").string();
  if (!fs::is_regular_file(calib_path, ec)) {
    return NotFound("calibration file '" + calib_path + "' is missing");
  }
  const Result<std::string> text = ReadText(calib_path);
  if (!text.ok()) return text.status();
  Eigen::Matrix<double, 3, 4> pl, pr;
  ROVER_RETURN_IF_ERROR(ParseCalibration(*text, calib_path, &pl, &pr));
  const cv::Mat first = cv::imread(seq.left_files.front(), cv::IMREAD_GRAYSCALE);
  if (first.empty()) return InvalidArgument("cannot read image '" + seq.left_files.front() + "'");
  Result<StereoCamera> cam = StereoCamera::FromProjectionMatrices(pl, pr, first.cols, first.rows);
  if (!cam.ok()) return cam.status().WithPrefix(calib_path);
  seq.camera = *cam;
  const std::string times_path = (root / "times.txt").string();
  if (fs::is_regular_file(times_path, ec)) {
    std::ifstream in(times_path);
    double t = 0.0;
    while (in >> t) seq.times.push_back(t);
    if (seq.times.size() < seq.size()) {
      return InvalidArgument(times_path + ": " + std::to_string(seq.times.size()) + " times for " +
                             std::to_string(seq.size()) + " frames");
    }
  } else {
    for (std::size_t i = 0; i < seq.size(); ++i) seq.times.push_back(0.1 * static_cast<double>(i));
  }
  if (fs::is_regular_file(root / "poses.txt", ec)) seq.poses_file = (root / "poses.txt").string();
  return seq;
}

Result<StereoFrame> LoadFrame(const Sequence& sequence, std::size_t index) {
  if (index >= sequence.size()) {
    return OutOfRange("frame " + std::to_string(index) + " of a " +
                      std::to_string(sequence.size()) + "-frame sequence");
  }
  StereoFrame f;
  f.stamp = Time::FromSeconds(sequence.times[index]);
  f.left = cv::imread(sequence.left_files[index], cv::IMREAD_GRAYSCALE);
  f.right = cv::imread(sequence.right_files[index], cv::IMREAD_GRAYSCALE);
  if (f.left.empty()) return InvalidArgument("cannot read '" + sequence.left_files[index] + "'");
  if (f.right.empty()) return InvalidArgument("cannot read '" + sequence.right_files[index] + "'");
  return f;
}

Result<std::vector<Eigen::Isometry3d>> ReadPoses(const std::string& path) {
  const Result<std::string> text = ReadText(path);
  if (!text.ok()) return text.status();
  std::istringstream in(*text);
  std::string line;
  std::vector<Eigen::Isometry3d> poses;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::vector<double> v;
    double d = 0.0;
    while (ls >> d) v.push_back(d);
    if (v.empty() && line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (v.size() != 12) {
      return InvalidArgument(path + ":" + std::to_string(line_no) + ": expected 12 numbers, got " +
                             std::to_string(v.size()));
    }
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    for (int k = 0; k < 12; ++k) t.matrix()(k / 4, k % 4) = v[static_cast<std::size_t>(k)];
    poses.push_back(t);
  }
  return poses;
}

std::string FormatPose(const Eigen::Isometry3d& pose) {
  std::string out;
  char buf[32];
  for (int k = 0; k < 12; ++k) {
    std::snprintf(buf, sizeof(buf), "%e", pose.matrix()(k / 4, k % 4));
    if (k > 0) out += ' ';
    out += buf;
  }
  return out;
}

Status WritePoses(const std::string& path, const std::vector<Eigen::Isometry3d>& poses) {
  std::ofstream out(path);
  if (!out) return Unavailable("cannot write '" + path + "'");
  for (const auto& p : poses) out << FormatPose(p) << '\n';
  out.flush();
  if (!out) return Unavailable("error writing '" + path + "'");
  return Status::Ok();
}

MotionPrior ConstantVelocityModel::Next(const MotionEstimate& last) const {
  if (last.status == MotionStatus::kNoReference) {
    return MotionPrior::Stationary(first_sigma_translation, first_sigma_rotation);
  }
  MotionPrior p = MotionPrior::Stationary(sigma_translation, sigma_rotation);
  p.delta = last.delta;  // converged: the measurement; otherwise the previous prior
  return p;
}

std::vector<double> SegmentLengths(double path_length) {
  std::vector<double> out;
  for (int l = 100; l <= 800; l += 100) {
    if (l < path_length) out.push_back(l);
  }
  if (out.size() >= 2) return out;
  out.clear();
  const double step = std::max(1.0, std::round(path_length / 6.0));
  for (int k = 1; k <= 5; ++k) out.push_back(k * step);
  return out;
}

double PathLength(const std::vector<Eigen::Isometry3d>& poses) {
  double d = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    d += (poses[i].translation() - poses[i - 1].translation()).norm();
  }
  return d;
}

ErrorMetrics Evaluate(const std::vector<Eigen::Isometry3d>& truth,
                      const std::vector<Eigen::Isometry3d>& estimate,
                      const std::vector<double>& lengths, int step) {
  ErrorMetrics m;
  const std::size_t n = std::min(truth.size(), estimate.size());
  if (n < 2) return m;
  std::vector<double> dist(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    dist[i] = dist[i - 1] + (truth[i].translation() - truth[i - 1].translation()).norm();
  }
  m.path_length = dist[n - 1];
  double terr = 0.0, rerr = 0.0;
  for (std::size_t i = 0; i < n; i += static_cast<std::size_t>(std::max(1, step))) {
    for (double len : lengths) {
      std::size_t j = i;
      while (j < n && dist[j] - dist[i] < len) ++j;
      if (j >= n) continue;
      const Eigen::Isometry3d dg = truth[i].inverse() * truth[j];
      const Eigen::Isometry3d de = estimate[i].inverse() * estimate[j];
      const Eigen::Isometry3d e = dg.inverse() * de;
      terr += e.translation().norm() / len;
      rerr += RotationAngle(e.linear()) / len;
      ++m.segments;
    }
  }
  if (m.segments > 0) {
    m.translation_percent = 100.0 * terr / m.segments;
    m.rotation_deg_per_m = rerr / m.segments * 180.0 / std::numbers::pi;
  }
  m.endpoint_m = (estimate[n - 1].translation() - truth[n - 1].translation()).norm();
  if (m.path_length > 0.0) m.endpoint_percent = 100.0 * m.endpoint_m / m.path_length;
  return m;
}

}  // namespace rover::dl::vo::kitti
