#include "rover/sim/render/sensor_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::sim::render {
namespace {

SensorOptions Plain() {
  SensorOptions o;
  o.vignetting = 0.0;
  o.bias_dn = 0.0;
  return o;
}

TEST(SensorModelTest, ValidateNamesField) {
  SensorOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.read_noise_e = -1;
  EXPECT_NE(o.Validate().message().find("sensor.read_noise_e"), std::string::npos);
  o = {};
  o.vignetting = 1.0;
  EXPECT_NE(o.Validate().message().find("sensor.vignetting"), std::string::npos);
  o = {};
  o.binning = 0;
  EXPECT_NE(o.Validate().message().find("sensor.binning"), std::string::npos);
}

TEST(SensorModelTest, NoiseFreeLevelsAndClamp) {
  SensorOptions o = Plain();
  o.noise = false;
  cv::Mat r(8, 8, CV_32FC1, cv::Scalar(0.3F));
  r.at<float>(0, 0) = 5.0F;  // saturates
  const cv::Mat dn = ApplySensorModel(r, o, 2.0, 1);
  EXPECT_EQ(dn.at<std::uint8_t>(3, 3), 153);  // round(0.3 * 2 * 255)
  EXPECT_EQ(dn.at<std::uint8_t>(0, 0), 255);
}

TEST(SensorModelTest, NoiseStatisticsMatchShotAndReadNoise) {
  SensorOptions o = Plain();
  cv::Mat r(256, 256, CV_32FC1, cv::Scalar(0.2F));
  const double exposure = 1.0;
  const cv::Mat dn = ApplySensorModel(r, o, exposure, 7);
  cv::Scalar mean, sd;
  cv::meanStdDev(dn, mean, sd);
  const double s = 0.2 * exposure * o.full_well_e;  // 4000 e-
  const double expect_sd = std::sqrt(s + o.read_noise_e * o.read_noise_e) * 255.0 / o.full_well_e;
  EXPECT_NEAR(mean[0], s * 255.0 / o.full_well_e, 0.1);
  EXPECT_NEAR(sd[0], std::sqrt(expect_sd * expect_sd + 1.0 / 12.0), 0.05 * expect_sd);
}

// A 4 x 4 binned pixel sums sixteen pixels' charge and reads once: the same brightness, the shot
// noise a quarter and the read noise a sixteenth of one pixel's (in DN).
TEST(SensorModelTest, BinnedReadoutKeepsBrightnessAndSumsChargeBeforeOneRead) {
  SensorOptions o = Plain();
  o.gain = 4.0;  // DN large enough that rounding does not hide the binned noise
  cv::Mat r(256, 256, CV_32FC1, cv::Scalar(0.2F));
  const double s = 0.2 * o.full_well_e;  // 4000 e- per sensor pixel at exposure 1
  const double dn_per_e = o.gain * 255.0 / o.full_well_e;
  for (const int b : {1, 4}) {
    o.binning = b;
    const cv::Mat dn = ApplySensorModel(r, o, 1.0, 3);
    cv::Scalar mean, sd;
    cv::meanStdDev(dn, mean, sd);
    const double n = b * b;
    const double expect_sd = std::sqrt(n * s + o.read_noise_e * o.read_noise_e) * dn_per_e / n;
    EXPECT_NEAR(mean[0], s * dn_per_e, 0.1) << "binning " << b;
    EXPECT_NEAR(sd[0], std::sqrt(expect_sd * expect_sd + 1.0 / 12.0), 0.05 * expect_sd)
        << "binning " << b;
  }
}

TEST(SensorModelTest, SeededNoise) {
  SensorOptions o = Plain();
  cv::Mat r(64, 64, CV_32FC1, cv::Scalar(0.3F));
  const cv::Mat a = ApplySensorModel(r, o, 1.0, 11), b = ApplySensorModel(r, o, 1.0, 11);
  const cv::Mat c = ApplySensorModel(r, o, 1.0, 12);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1), 0.0);
}

TEST(SensorModelTest, VignettingDarkensCorners) {
  SensorOptions o = Plain();
  o.noise = false;
  o.vignetting = 0.3;
  cv::Mat r(101, 101, CV_32FC1, cv::Scalar(0.4F));
  const cv::Mat dn = ApplySensorModel(r, o, 2.0, 1);
  EXPECT_EQ(dn.at<std::uint8_t>(50, 50), 204);
  EXPECT_NEAR(dn.at<std::uint8_t>(0, 0), 204 * 0.7, 1.0);
}

TEST(SensorModelTest, AutoExposurePlacesPercentile) {
  SensorOptions o;
  cv::Mat r(100, 100, CV_32FC1);
  for (int i = 0; i < r.rows; ++i)
    for (int j = 0; j < r.cols; ++j) r.at<float>(i, j) = static_cast<float>(i * r.cols + j) / 10000.0F;
  o.auto_percentile = 0.9;
  o.auto_target = 0.8;
  EXPECT_NEAR(AutoExposure(r, o), 0.8 / 0.9, 1e-3);
  // A small very bright patch (1 %) may clip rather than darken the rest.
  cv::Mat scene(100, 100, CV_32FC1, cv::Scalar(0.1F));
  scene(cv::Rect(0, 0, 10, 10)).setTo(0.9F);
  o.auto_percentile = 0.995;
  EXPECT_NEAR(AutoExposure(scene, o), 2.0 * 0.8 / 0.9, 1e-3);  // capped at 2x the percentile rule
  cv::Mat black(10, 10, CV_32FC1, cv::Scalar(0.0F));
  EXPECT_EQ(AutoExposure(black, o), o.exposure);
}

}  // namespace
}  // namespace rover::sim::render
