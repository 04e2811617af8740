#include "rover/ddl/camera/camera_calibration.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "rover/base/units.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::ddl::camera {
namespace {

const std::string kDeployFile = std::string(ROVER_SOURCE_DIR) + "/deploy/config/cameras.yaml";
// The design of deploy/config/cameras.yaml rebuilt with core/geometry (see the file's header).
geometry::Cahvor Design(const Eigen::Vector3d& c, const Eigen::Matrix3d& r, double f) {
  geometry::Cahvor m;
  m.c = c;
  m.a = r.col(0);
  m.h = f * (-r.col(1)) + 511.5 * m.a;
  m.v = f * (-r.col(2)) + 511.5 * m.a;
  m.o = m.a;
  m.r = Eigen::Vector3d(0.0, -0.01, 0.0);
  return m;
}

void ExpectSame(const geometry::CameraModel& got, const geometry::Cahvor& want, const char* what) {
  const auto* m = got.As<geometry::Cahvor>();
  ASSERT_NE(m, nullptr) << what;
  EXPECT_LT((m->c - want.c).norm(), 1e-12) << what;
  EXPECT_LT((m->a - want.a).norm(), 1e-12) << what;
  EXPECT_LT((m->h - want.h).norm(), 1e-9) << what;
  EXPECT_LT((m->v - want.v).norm(), 1e-9) << what;
  EXPECT_LT((m->o - want.o).norm(), 1e-12) << what;
  EXPECT_LT((m->r - want.r).norm(), 1e-15) << what;
  EXPECT_EQ(got.width(), 1024);
  EXPECT_EQ(got.height(), 1024);
}

// Angle [rad] between the rays of two pixels on the middle row's outer edges.
double HorizontalFov(const geometry::CameraModel& m) {
  const double y = 0.5 * (m.height() - 1);
  auto a = m.Unproject({-0.5, y});
  auto b = m.Unproject({m.width() - 0.5, y});
  EXPECT_TRUE(a && b);
  return std::acos(a->direction.dot(b->direction));
}

TEST(CameraCalibration, DeployFileIsTheMerLikeDesign) {
  auto cal = LoadCameraCalibration(kDeployFile);
  ASSERT_TRUE(cal.ok()) << cal.status().message();
  ASSERT_EQ(cal->cameras.size(), 3u);
  EXPECT_LT((cal->mast.pan_joint - Eigen::Vector3d(0.35, 0.0, 0.65)).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(cal->mast.head_height, 0.85);

  const auto& nav = cal->cameras[0];
  EXPECT_EQ(nav.name, "navcam");
  EXPECT_EQ(nav.mount, CameraMount::kMastHead);
  const double fn = 512.0 / std::tan(22.5 * kDegree);
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  ExpectSame(nav.left, Design({0.05, 0.10, 0.0}, id, fn), "navcam left");
  ExpectSame(nav.right, Design({0.05, -0.10, 0.0}, id, fn), "navcam right");
  EXPECT_NEAR(HorizontalFov(nav.left) / kDegree, 45.0, 0.1);  // 45.07 with the barrel term

  const double t = std::tan(60.0 * kDegree);
  const double fh = 512.0 / (t * (1.0 - 0.01 * t * t));
  for (int i = 1; i <= 2; ++i) {
    const auto& hz = cal->cameras[static_cast<std::size_t>(i)];
    EXPECT_EQ(hz.mount, CameraMount::kBody);
    const double yaw = i == 1 ? 0.0 : std::numbers::pi;
    const Eigen::Matrix3d r = geometry::RotationFromRpy(0.0, 45.0 * kDegree, yaw);
    const Eigen::Vector3d centre(i == 1 ? 0.52 : -0.52, 0.0, 0.50);
    ExpectSame(hz.left, Design(centre + r * Eigen::Vector3d(0, 0.05, 0), r, fh), hz.name.c_str());
    ExpectSame(hz.right, Design(centre + r * Eigen::Vector3d(0, -0.05, 0), r, fh), hz.name.c_str());
    EXPECT_NEAR(HorizontalFov(hz.left) / kDegree, 120.0, 1e-6);
    const auto* m = hz.left.As<geometry::Cahvor>();
    EXPECT_NEAR(std::asin(-m->a.z()) / kDegree, 45.0, 1e-9);  // looks 45 deg down
    EXPECT_NEAR((hz.left.Center() - hz.right.Center()).norm(), 0.10, 1e-12);
    EXPECT_EQ(m->a.x() > 0, i == 1);  // front / rear
  }
  EXPECT_EQ(cal->cameras[1].name, "front_hazcam");
  EXPECT_EQ(cal->cameras[2].name, "rear_hazcam");

  // NAVCAM at pan = tilt = 0: 0.20 m baseline, 1.50 m above the ground, looking forward.
  auto [l, r] = nav.InRover(0.0, 0.0, cal->mast);
  EXPECT_NEAR((l.Center() - r.Center()).norm(), 0.20, 1e-12);
  EXPECT_NEAR(l.Center().z(), 1.50, 1e-12);
  EXPECT_GT(l.Center().y(), r.Center().y());  // left camera on the rover's left
}

TEST(CameraCalibration, MastHeadPairFollowsPanAndTilt) {
  auto cal = LoadCameraCalibration(kDeployFile);
  ASSERT_TRUE(cal.ok());
  const auto& nav = cal->cameras[0];
  const double pan = 0.5, tilt = 0.3;
  auto [l, r] = nav.InRover(pan, tilt, cal->mast);
  const auto* m = l.As<geometry::Cahvor>();
  ASSERT_NE(m, nullptr);
  // Boresight: azimuth = pan (left of forward), elevation = tilt (up).
  EXPECT_NEAR(std::atan2(m->a.y(), m->a.x()), pan, 1e-12);
  EXPECT_NEAR(std::asin(m->a.z()), tilt, 1e-12);
  // A point fixed in the head frame lands on the same pixel before and after the move.
  const Eigen::Isometry3d rover_from_head = MastHeadPose(pan, tilt, cal->mast);
  const Eigen::Vector3d p_head(4.0, 0.7, -0.4);
  auto a = nav.left.Project(p_head);
  auto b = l.Project(rover_from_head * p_head);
  ASSERT_TRUE(a && b);
  EXPECT_LT((*a - *b).norm(), 1e-9);
  // Body pairs do not move.
  auto [fl, fr] = cal->cameras[1].InRover(pan, tilt, cal->mast);
  EXPECT_LT((fl.Center() - cal->cameras[1].left.Center()).norm(), 1e-15);
  (void)r;
  (void)fr;
}

TEST(CameraCalibration, MastHeadPoseConventions) {
  const MastGeometry g;
  const Eigen::Isometry3d t0 = MastHeadPose(0.0, 0.0, g);
  EXPECT_LT((t0.translation() - Eigen::Vector3d(0.35, 0.0, 1.5)).norm(), 1e-15);
  EXPECT_TRUE(t0.linear().isIdentity(1e-15));
  const Eigen::Isometry3d left = MastHeadPose(std::numbers::pi / 2, 0.0, g);
  EXPECT_LT((left.linear().col(0) - Eigen::Vector3d::UnitY()).norm(), 1e-12);  // pan + = left
  const Eigen::Isometry3d up = MastHeadPose(0.0, 0.4, g);
  EXPECT_GT(up.linear().col(0).z(), 0.0);  // tilt + = up
}

class CalibrationFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("ddl_camera_cal_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // The deploy file with one line replaced (`from` must occur).
  std::string Edited(const std::string& from, const std::string& to) {
    std::ifstream in(kDeployFile);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    const auto pos = text.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    if (pos != std::string::npos) text.replace(pos, from.size(), to);
    const std::string path = dir_ + "/cameras.yaml";
    std::ofstream(path) << text;
    return path;
  }
  // 1-based line of the first occurrence of `needle` in the deploy file.
  static int Line(const std::string& needle) {
    std::ifstream in(kDeployFile);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    const auto pos = text.find(needle);
    EXPECT_NE(pos, std::string::npos) << needle;
    return 1 +
           static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
  }
  std::string dir_;
};

TEST_F(CalibrationFile, BadModelNamesFileLineAndCamera) {
  const std::string path = Edited("    a: [1.0, 0.0, 0.0]\n    h: [511.5, -1236.07734393502, 0.0]",
                                  "    a: [0.5, 0.0, 0.0]\n    h: [511.5, -1236.07734393502, 0.0]");
  auto cal = LoadCameraCalibration(path);
  ASSERT_FALSE(cal.ok());
  const std::string where =
      path + ":" + std::to_string(Line("    a: [1.0, 0.0, 0.0]")) + ": navcam.left (CAHVOR)";
  EXPECT_NE(cal.status().message().find(where), std::string::npos) << cal.status().message();
}

TEST_F(CalibrationFile, MissingDistortionTermsAreNamed) {
  const std::string path =
      Edited("    o: [1.0, 0.0, 0.0]\n    r: [0.0, -0.01, 0.0]\n  right:", "  right:");
  auto cal = LoadCameraCalibration(path);
  ASSERT_FALSE(cal.ok());
  EXPECT_NE(cal.status().message().find("key 'navcam.left.o': CAHVOR needs 3 numbers, got 0"),
            std::string::npos)
      << cal.status().message();
}

TEST_F(CalibrationFile, UnknownKeysAndBadValuesAreRejectedWithTheirLine) {
  auto cal = LoadCameraCalibration(Edited("  mount: mast_head", "  mount: mast_top"));
  ASSERT_FALSE(cal.ok());
  const std::string where = ":" + std::to_string(Line("  mount: mast_head")) +
                            ": key 'navcam.mount': 'mast_top' is not one of";
  EXPECT_NE(cal.status().message().find(where), std::string::npos) << cal.status().message();
  cal = LoadCameraCalibration(Edited("  width: 1024\n  height: 1024\n  left:\n    c: [0.52",
                                     "  widht: 1024\n  height: 1024\n  left:\n    c: [0.52"));
  ASSERT_FALSE(cal.ok());
  EXPECT_NE(cal.status().message().find("widht"), std::string::npos) << cal.status().message();
  EXPECT_FALSE(LoadCameraCalibration(dir_ + "/missing.yaml").ok());
}

TEST_F(CalibrationFile, CahvAndCahvoreKindsLoad) {
  auto cal = LoadCameraCalibration(Edited("navcam:\n  mount: mast_head\n  model: CAHVOR",
                                          "navcam:\n  mount: mast_head\n  model: CAHV"));
  ASSERT_TRUE(cal.ok()) << cal.status().message();
  EXPECT_EQ(cal->cameras[0].left.kind(), geometry::CameraModel::Kind::kCahv);
  // CAHVORE needs E.
  cal = LoadCameraCalibration(Edited("navcam:\n  mount: mast_head\n  model: CAHVOR",
                                     "navcam:\n  mount: mast_head\n  model: CAHVORE"));
  ASSERT_FALSE(cal.ok());
  EXPECT_NE(cal.status().message().find("navcam.left.e"), std::string::npos)
      << cal.status().message();
}

}  // namespace
}  // namespace rover::ddl::camera
