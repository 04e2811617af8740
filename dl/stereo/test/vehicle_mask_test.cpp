#include "rover/dl/stereo/vehicle_mask.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "rover/base/param_binder.hpp"
#include "rover/base/units.hpp"
#include "rover/dl/stereo/disparity_image.hpp"

namespace rover::dl::stereo {
namespace {

using Eigen::Vector3d;
using hwconfig::RoverDescription;
Vector3d FrontEye(const RoverDescription& rover) {
  return rover.front_hazcam.CameraCentre(hwconfig::kLeft);
}

// Points on the outer half of a wheel's tread and on its outer side face, the parts a HAZCAM sees.
std::vector<Vector3d> WheelSurface(const RoverDescription& rover, int wheel) {
  std::vector<Vector3d> pts;
  const Vector3d c = rover.WheelCentre(wheel);
  const double r = rover.wheel_radius;
  for (double a = 0.0; a < 2.0 * kPi; a += kPi / 12.0) {
    for (double dy : {-0.45, 0.0, 0.45}) {
      pts.push_back(c + Vector3d(r * std::cos(a), dy * rover.wheel_width, r * std::sin(a)));
    }
    pts.push_back(c + Vector3d(0.6 * r * std::cos(a), 0.5 * rover.wheel_width, 0.6 * r * std::sin(a)));
  }
  return pts;
}

TEST(VehicleMask, RemovesPointsOnTheWheelsAndKeepsTheGroundAhead) {
  const RoverDescription rover;
  const VehicleMask mask(rover, VehicleMaskOptions());
  ASSERT_EQ(mask.volumes().size(), 7u);
  const Vector3d eye = FrontEye(rover);
  for (int wheel : {hwconfig::kWheelLF, hwconfig::kWheelRF, hwconfig::kWheelLM}) {
    for (const Vector3d& p : WheelSurface(rover, wheel)) {
      EXPECT_EQ(mask.Hides(eye, p), VehiclePart::kWheel)
          << hwconfig::WheelName(wheel) << " point " << p.transpose();
    }
  }
  // Flat ground in front of the rover and between the front wheels: kept.
  int kept = 0;
  for (double x = 1.5; x <= 4.0; x += 0.1) {
    for (double y = -2.0; y <= 2.0; y += 0.1) {
      EXPECT_EQ(mask.Hides(eye, Vector3d(x, y, 0.0)), VehiclePart::kNone) << x << " " << y;
      ++kept;
    }
  }
  for (double x = 0.9; x <= 1.5; x += 0.05) {
    for (double y = -0.25; y <= 0.25; y += 0.05) {
      EXPECT_EQ(mask.Hides(eye, Vector3d(x, y, 0.0)), VehiclePart::kNone) << x << " " << y;
    }
  }
  EXPECT_GT(kept, 500);
}

TEST(VehicleMask, RemovesMismatchesBehindAWheelButNotRealDepressions) {
  const RoverDescription rover;
  const VehicleMask mask(rover, VehicleMaskOptions());
  const Vector3d eye = FrontEye(rover);
  // A wheel pixel matched at too small a disparity: a point on the ray through the LF wheel,
  // 1.1 m below the ground (seed 1's outliers in the VL-1 run).
  const Vector3d wheel = rover.WheelCentre(hwconfig::kWheelLF);
  const double t = (eye.z() + 1.1) / (eye.z() - wheel.z());
  const Vector3d outlier = eye + t * (wheel - eye);
  EXPECT_NEAR(outlier.z(), -1.1, 1e-9);
  EXPECT_EQ(mask.Hides(eye, outlier), VehiclePart::kWheel);
  // Under a wheel: the ground it stands on hides it.
  EXPECT_EQ(mask.Hides(eye, Vector3d(wheel.x(), wheel.y(), -0.4)), VehiclePart::kWheel);
  // A real hole ahead, away from the wheels' lines of sight: kept (no cut below the ground).
  EXPECT_EQ(mask.Hides(eye, Vector3d(2.5, 0.0, -0.5)), VehiclePart::kNone);
  EXPECT_EQ(mask.Hides(eye, Vector3d(2.0, 1.0, -0.3)), VehiclePart::kNone);
}

TEST(VehicleMask, RearCameraAndNavcamSeeTheirOwnParts) {
  const RoverDescription rover;
  const VehicleMask mask(rover, VehicleMaskOptions());
  const Vector3d rear_eye = rover.rear_hazcam.CameraCentre(hwconfig::kRight);
  for (const Vector3d& p : WheelSurface(rover, hwconfig::kWheelLR)) {
    EXPECT_EQ(mask.Hides(rear_eye, p), VehiclePart::kWheel) << p.transpose();
  }
  EXPECT_EQ(mask.Hides(rear_eye, Vector3d(-2.5, 0.0, 0.0)), VehiclePart::kNone);
  // The NAVCAM looking down at the deck sees the body.
  const Vector3d nav_eye =
      rover.mast.HeadPose(0.0, -1.2) * rover.navcam.CameraCentre(hwconfig::kLeft);
  const Vector3d deck(0.0, 0.0, rover.body_centre.z() + 0.5 * rover.body_size.z());
  EXPECT_EQ(mask.Hides(nav_eye, deck), VehiclePart::kBody);
  EXPECT_EQ(mask.Hides(nav_eye, Vector3d(4.0, 0.0, 0.0)), VehiclePart::kNone);
}

TEST(VehicleMask, DisabledMasksNothing) {
  const RoverDescription rover;
  VehicleMaskOptions o;
  o.enabled = false;
  const VehicleMask mask(rover, o);
  const Vector3d eye = FrontEye(rover);
  EXPECT_EQ(mask.Hides(eye, rover.WheelCentre(hwconfig::kWheelLF)), VehiclePart::kNone);
}

TEST(VehicleMask, AppliesToAnImageOfPoints) {
  const RoverDescription rover;
  const VehicleMask mask(rover, VehicleMaskOptions());
  const Vector3d eye = FrontEye(rover);
  const Vector3d w = rover.WheelCentre(hwconfig::kWheelRF) + Vector3d(0.1, 0.0, 0.05);
  cv::Mat xyz(1, 3, CV_32FC3);
  cv::Mat status(1, 3, CV_8UC1, cv::Scalar(static_cast<int>(PixelStatus::kValid)));
  xyz.at<cv::Vec3f>(0, 0) = cv::Vec3f(static_cast<float>(w.x()), static_cast<float>(w.y()),
                                      static_cast<float>(w.z()));
  xyz.at<cv::Vec3f>(0, 1) = cv::Vec3f(2.0F, 0.0F, 0.0F);
  xyz.at<cv::Vec3f>(0, 2) = xyz.at<cv::Vec3f>(0, 0);
  status.at<std::uint8_t>(0, 2) = static_cast<std::uint8_t>(PixelStatus::kBlob);
  auto n = mask.Apply(eye, &xyz, &status);
  ASSERT_TRUE(n.ok()) << n.status().ToString();
  EXPECT_EQ(*n, 1);
  EXPECT_EQ(status.at<std::uint8_t>(0, 0), static_cast<std::uint8_t>(PixelStatus::kWheel));
  EXPECT_TRUE(std::isnan(xyz.at<cv::Vec3f>(0, 0)[0]));
  EXPECT_EQ(status.at<std::uint8_t>(0, 1), static_cast<std::uint8_t>(PixelStatus::kValid));
  EXPECT_EQ(status.at<std::uint8_t>(0, 2), static_cast<std::uint8_t>(PixelStatus::kBlob));

  cv::Mat small(1, 2, CV_8UC1);
  const auto bad = mask.Apply(eye, &xyz, &small);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("3x1 vs 2x1"), std::string::npos)
      << bad.status().message();
}

TEST(VehicleMask, SegmentMeetsBox) {
  const Eigen::AlignedBox3d box(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  EXPECT_TRUE(SegmentMeetsBox(Vector3d(-1, 0.5, 0.5), Vector3d(2, 0.5, 0.5), box));   // through
  EXPECT_TRUE(SegmentMeetsBox(Vector3d(-1, 0.5, 0.5), Vector3d(0.5, 0.5, 0.5), box)); // ends in
  EXPECT_FALSE(SegmentMeetsBox(Vector3d(-1, 0.5, 0.5), Vector3d(-0.1, 0.5, 0.5), box));  // short
  EXPECT_FALSE(SegmentMeetsBox(Vector3d(-1, 1.5, 0.5), Vector3d(2, 1.5, 0.5), box));  // parallel
  EXPECT_FALSE(SegmentMeetsBox(Vector3d(-1, -1, 0.5), Vector3d(0.4, -0.1, 0.5), box));
  EXPECT_TRUE(SegmentMeetsBox(Vector3d(-1, -1, 0.5), Vector3d(2, 2, 0.5), box));  // diagonal
}

TEST(VehicleMask, CameraInsideAVolumeOnlyMasksPointsInsideIt) {
  RoverDescription rover;
  VehicleMaskOptions o;
  o.body_margin_m = 0.1;  // the body box now reaches over the front HAZCAM (x 0.52)
  const VehicleMask mask(rover, o);
  const Vector3d eye = FrontEye(rover);
  EXPECT_EQ(mask.Hides(eye, Vector3d(2.0, 0.0, 0.0)), VehiclePart::kNone);
  EXPECT_EQ(mask.Hides(eye, Vector3d(0.55, 0.0, 0.45)), VehiclePart::kBody);
}

TEST(VehicleMask, LoadsAFixedPixelMask) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("vehicle_mask_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  cv::Mat img(4, 6, CV_8UC1, cv::Scalar(0));
  img.at<std::uint8_t>(3, 0) = 7;
  const std::string path = (dir / "front.png").string();
  ASSERT_TRUE(cv::imwrite(path, img));
  auto m = LoadPixelMask(path);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->type(), CV_8UC1);
  EXPECT_EQ(m->size(), cv::Size(6, 4));
  EXPECT_EQ(m->at<std::uint8_t>(3, 0), 255);
  EXPECT_EQ(cv::countNonZero(*m), 1);
  const auto missing = LoadPixelMask((dir / "nope.png").string());
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("nope.png"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(VehicleMaskOptions, ValidateAndParameters) {
  EXPECT_TRUE(VehicleMaskOptions().Validate().ok());
  VehicleMaskOptions o;
  o.wheel_lift_m = -0.1;
  EXPECT_NE(o.Validate().message().find("wheel_lift_m"), std::string::npos);
  o = VehicleMaskOptions();
  o.support_depth_m = std::nan("");
  EXPECT_FALSE(o.Validate().ok());
  ParamSet ps("dl-stereo");
  DeclareParams<VehicleMaskOptions>(ps, "vehicle_mask.");
  EXPECT_TRUE(ps.GetBool("vehicle_mask.enabled"));
  ASSERT_TRUE(
      ps.LoadYamlString("vehicle_mask:\n  wheel_margin_m: 0.05\n  enabled: false\n", "m.yaml").ok());
  auto read = ReadParams<VehicleMaskOptions>(ps, "vehicle_mask.");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_FALSE(read->enabled);
  EXPECT_DOUBLE_EQ(read->wheel_margin_m, 0.05);
  const Status bad = ps.LoadYamlString("vehicle_mask:\n  support_depth_m: -1\n", "m.yaml");
  EXPECT_FALSE(bad.ok() && ReadParams<VehicleMaskOptions>(ps, "vehicle_mask.").ok());
}

}  // namespace
}  // namespace rover::dl::stereo
