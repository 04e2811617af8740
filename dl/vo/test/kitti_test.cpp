#include "rover/dl/vo/kitti.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <opencv2/imgcodecs.hpp>

namespace rover::dl::vo::kitti {
namespace {

namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() /
            ("dl_vo_kitti_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter_++));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  static inline int counter_ = 0;
  fs::path path_;
};

void WriteFile(const fs::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
}

const char* kCalib =
    "7.070912e+02 0 6.018873e+02 0 0 7.070912e+02 1.831104e+02 0 0 0 1 0\n"
    "7.070912e+02 0 6.018873e+02 -3.798145e+02 0 7.070912e+02 1.831104e+02 0 0 0 1 0\n";

TEST(ParseCalibration, PlainAndPrefixedForms) {
  Eigen::Matrix<double, 3, 4> l, r;
  ASSERT_TRUE(ParseCalibration(kCalib, "calib.txt", &l, &r).ok());
  EXPECT_DOUBLE_EQ(r(0, 3), -379.8145);
  const std::string prefixed = std::string("P0: ") + "7 0 6 0 0 7 1 0 0 0 1 0\n" +
                               "P1: 7 0 6 -3 0 7 1 0 0 0 1 0\nP2: 1 2 3\n";
  ASSERT_TRUE(ParseCalibration(prefixed, "calib.txt", &l, &r).ok());
  EXPECT_DOUBLE_EQ(r(0, 3), -3.0);
}

TEST(ParseCalibration, ErrorsNameFileAndLine) {
  Eigen::Matrix<double, 3, 4> l, r;
  Status s = ParseCalibration("1 2 3\n", "cal.txt", &l, &r);
  EXPECT_NE(s.message().find("cal.txt:1"), std::string::npos) << s.message();
  s = ParseCalibration(std::string(kCalib).substr(0, 80) + "\n1 2 x 4 5 6 7 8 9 10 11 12\n",
                       "cal.txt", &l, &r);
  EXPECT_FALSE(s.ok());
  s = ParseCalibration(std::string("1 0 1 0 0 1 1 0 0 0 1 0\n"), "cal.txt", &l, &r);
  EXPECT_NE(s.message().find("two projection matrices"), std::string::npos);
  s = ParseCalibration("", "cal.txt", &l, &r);
  EXPECT_FALSE(s.ok());
}

TEST(Poses, WriteReadRoundTrip) {
  TempDir dir;
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < 4; ++i) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d::UnitY()).toRotationMatrix();
    t.translation() = Eigen::Vector3d(0.1 * i, -0.02 * i, 1.2 * i);
    poses.push_back(t);
  }
  const std::string path = (dir.path() / "poses.txt").string();
  ASSERT_TRUE(WritePoses(path, poses).ok());
  const auto back = ReadPoses(path);
  ASSERT_TRUE(back.ok());
  ASSERT_EQ(back->size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_TRUE((*back)[i].isApprox(poses[i], 1e-6));
  }
  std::istringstream line(FormatPose(poses[1]));
  double v = 0;
  int n = 0;
  while (line >> v) ++n;
  EXPECT_EQ(n, 12);
  WriteFile(dir.path() / "bad.txt", "1 2 3\n");
  const auto bad = ReadPoses((dir.path() / "bad.txt").string());
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("bad.txt:1"), std::string::npos);
  EXPECT_EQ(ReadPoses((dir.path() / "none.txt").string()).status().code(), StatusCode::kNotFound);
  EXPECT_FALSE(WritePoses((dir.path() / "no" / "such" / "dir.txt").string(), poses).ok());
}

std::vector<Eigen::Isometry3d> Straight(int n, double step, double yaw_per_step = 0.0) {
  std::vector<Eigen::Isometry3d> out;
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d d = Eigen::Isometry3d::Identity();
  d.translation() = Eigen::Vector3d(0, 0, step);
  d.linear() = Eigen::AngleAxisd(yaw_per_step, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (int i = 0; i < n; ++i) {
    out.push_back(p);
    p = p * d;
  }
  return out;
}

TEST(Evaluate, ZeroForPerfectAndScaleErrorInPercent) {
  const auto truth = Straight(51, 1.2);
  ErrorMetrics m = Evaluate(truth, truth, {10, 20});
  EXPECT_GT(m.segments, 50);
  EXPECT_NEAR(m.translation_percent, 0.0, 1e-9);
  EXPECT_NEAR(m.path_length, 60.0, 1e-9);
  // 2 % too long steps: 2 % translational error (segments end at the first frame past L).
  const auto longer = Straight(51, 1.2 * 1.02);
  m = Evaluate(truth, longer, {10, 20});
  EXPECT_NEAR(m.endpoint_percent, 2.0, 1e-9);
  EXPECT_GT(m.translation_percent, 2.0);
  EXPECT_LT(m.translation_percent, 2.0 * 1.2 / 1.0 + 0.01);
  // A constant extra yaw of 0.01 deg per 1.2 m step: segments of L = 11.5 m end 10 steps on.
  const double yaw = 0.01 * std::numbers::pi / 180.0;
  m = Evaluate(truth, Straight(51, 1.2, yaw), {11.5});
  EXPECT_NEAR(m.rotation_deg_per_m, 10 * 0.01 / 11.5, 1e-6);
  // Lengths longer than the sequence give no segment.
  EXPECT_EQ(Evaluate(truth, truth, {100}).segments, 0);
}

TEST(SegmentLengths, KittiLengthsOrFractionsOfShortPaths) {
  EXPECT_EQ(SegmentLengths(59.9), (std::vector<double>{10, 20, 30, 40, 50}));
  EXPECT_EQ(SegmentLengths(350.0), (std::vector<double>{100, 200, 300}));
  EXPECT_EQ(SegmentLengths(5000.0).size(), 8u);
  EXPECT_NEAR(PathLength(Straight(51, 1.2)), 60.0, 1e-9);
}

TEST(OpenSequence, ClearErrorsForMissingFolderImagesAndCalib) {
  TempDir dir;
  auto r = OpenSequence((dir.path() / "nope").string());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kNotFound);
  EXPECT_NE(r.status().message().find("nope"), std::string::npos);
  r = OpenSequence(dir.path().string());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("image_l"), std::string::npos);
  fs::create_directories(dir.path() / "image_l");
  fs::create_directories(dir.path() / "image_r");
  const cv::Mat img(40, 60, CV_8UC1, cv::Scalar(9));
  ASSERT_TRUE(cv::imwrite((dir.path() / "image_l" / "000000.png").string(), img));
  r = OpenSequence(dir.path().string());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("right image"), std::string::npos);
  ASSERT_TRUE(cv::imwrite((dir.path() / "image_r" / "000000.png").string(), img));
  r = OpenSequence(dir.path().string());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("calib.txt"), std::string::npos);
  WriteFile(dir.path() / "calib.txt", "1 2 3\n");
  r = OpenSequence(dir.path().string());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("calib.txt:1"), std::string::npos);
  WriteFile(dir.path() / "calib.txt", kCalib);
  r = OpenSequence(dir.path().string());
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ(r->size(), 1u);
  EXPECT_EQ(r->camera.width, 60);
  EXPECT_NEAR(r->times[0], 0.0, 1e-12);
  EXPECT_TRUE(r->poses_file.empty());
  const auto f = LoadFrame(*r, 0);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f->left.type(), CV_8UC1);
  EXPECT_EQ(LoadFrame(*r, 1).status().code(), StatusCode::kOutOfRange);
}

TEST(OpenSequence, KittiOwnFolderNamesAndTimes) {
  TempDir dir;
  fs::create_directories(dir.path() / "image_0");
  fs::create_directories(dir.path() / "image_1");
  const cv::Mat img(40, 60, CV_8UC1, cv::Scalar(9));
  for (const char* n : {"000000.png", "000001.png"}) {
    ASSERT_TRUE(cv::imwrite((dir.path() / "image_0" / n).string(), img));
    ASSERT_TRUE(cv::imwrite((dir.path() / "image_1" / n).string(), img));
  }
  WriteFile(dir.path() / "calib.txt", kCalib);
  WriteFile(dir.path() / "times.txt", "0.0\n0.1037\n");
  const auto r = OpenSequence(dir.path().string());
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  ASSERT_EQ(r->size(), 2u);
  EXPECT_DOUBLE_EQ(r->times[1], 0.1037);
  WriteFile(dir.path() / "times.txt", "0.0\n");
  EXPECT_FALSE(OpenSequence(dir.path().string()).ok());
}

TEST(ConstantVelocityModel, FirstStepWideThenLastMotion) {
  const ConstantVelocityModel model;
  MotionEstimate first;  // kNoReference
  const MotionPrior p0 = model.Next(first);
  EXPECT_TRUE(p0.delta.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_NEAR(p0.covariance(0, 0), 4.0, 1e-12);
  MotionEstimate e;
  e.status = MotionStatus::kConverged;
  e.delta.translation() = Eigen::Vector3d(0, 0, 1.2);
  const MotionPrior p1 = model.Next(e);
  EXPECT_NEAR(p1.delta.translation().z(), 1.2, 1e-12);
  EXPECT_NEAR(p1.covariance(5, 5), 0.02 * 0.02, 1e-12);
}

TEST(OpenSequence, RealKittiData) {
  const std::string dir = std::string(ROVER_SHARED_DATA_DIR) + "/kitti-seq1";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "KITTI data not found at " << dir;
  const auto r = OpenSequence(dir);
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ(r->size(), 51u);
  EXPECT_EQ(r->camera.width, 1226);
  EXPECT_EQ(r->camera.height, 370);
  EXPECT_NEAR(r->camera.baseline, 0.537, 0.001);
  const auto poses = ReadPoses(r->poses_file);
  ASSERT_TRUE(poses.ok());
  EXPECT_EQ(poses->size(), 51u);
}

}  // namespace
}  // namespace rover::dl::vo::kitti
