// dl-stereo on the simulator's own HAZCAM images, in process and without DDS: the front HAZCAM
// pair of a rover standing on gently rolling ground, read out two ways, both 256 px wide as the
// autonav set asks (docs/sim.md "Readouts", docs/services/ddl-camera.md):
//   - binned: a 256-px readout of the 1024-px sensor (4 x 4 binning, what ddl-camera asks of
//     the simulator), the models geometry::Scale'd by 1/4;
//   - full: the 1024-px frame area-averaged to 256 px by ddl-camera's AreaDownsample.
// Both are ranged by dl-stereo's StereoRanger with its defaults and the vehicle mask, and each
// valid point's height is compared with the true ground under it. The binned readout must range
// as well as the full frame: the same share of points more than 10 cm off and no larger RMS,
// per band of distance. (With the full per-pixel noise applied to the binned image, before the
// sensor model summed the binned charge, 1.5-3 m out 2-3 times as many points were 10 cm off,
// and GESTALT marked half of an open field as obstacles.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "rover/ddl/camera/camera_calibration.hpp"
#include "rover/ddl/camera/downsample.hpp"
#include "rover/dl/stereo/stereo_ranger.hpp"
#include "rover/dl/stereo/vehicle_mask.hpp"
#include "rover/geometry/camera_model.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/msg/camera.hpp"
#include "rover/sim/render/cameras.hpp"
#include "rover/sim/rover_sim/camera_head.hpp"
#include "rover/sim/terrain/terrain.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {

constexpr int kSensor = 1024;
constexpr int kWidth = 256;  // dl-stereo's default processing width

// Distance bands (horizontal, from the rover origin) [m].
constexpr double kBands[] = {0.5, 1.5, 2.5, 3.5};
constexpr int kNumBands = 3;

struct BandStats {
  int points = 0;
  int off_10cm = 0;
  double sum_sq = 0.0;
  double Rms() const { return points > 0 ? std::sqrt(sum_sq / points) : 0.0; }
  double OffShare() const { return points > 0 ? static_cast<double>(off_10cm) / points : 0.0; }
};

class StereoOnSimImagesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    sim::terrain::TerrainParams p;
    p.size_x = p.size_y = 20;
    p.center_x = 4;
    p.hills.amplitude = 0.05;
    p.craters.count = 0;
    p.rocks.preset = sim::terrain::RockPreset::kNone;
    p.seed = 1;
    auto t = sim::terrain::GenerateTerrain(p);
    ASSERT_TRUE(t.ok()) << t.status().message();
    terrain_ = std::make_shared<const sim::terrain::Terrain>(std::move(*t));
    auto cal =
        ddl::camera::LoadCameraCalibration(testing::SourceDir() + "/deploy/config/cameras.yaml");
    ASSERT_TRUE(cal.ok()) << cal.status().message();
    calibration_ = *cal;
  }

  // Ranges one pair (kWidth x kWidth, models valid for it) and compares heights with the truth.
  std::vector<BandStats> RangeAndCompare(const std::vector<std::uint8_t>& left,
                                         const std::vector<std::uint8_t>& right,
                                         const Eigen::Isometry3d& site_from_rover) {
    const auto& haz = calibration_.cameras[static_cast<int>(msg::CameraId::kFrontHazcam)];
    const double s = static_cast<double>(kWidth) / haz.left.width();
    auto lf = msg::CameraModelFieldsFromModel(geometry::Scale(haz.left, s));
    auto rf = msg::CameraModelFieldsFromModel(geometry::Scale(haz.right, s));
    EXPECT_TRUE(lf.ok() && rf.ok());
    msg::StereoFrame frame;
    frame.stamp = Time::FromSeconds(1);
    frame.request_id = 1;
    frame.camera = msg::CameraId::kFrontHazcam;
    frame.width = frame.height = kWidth;
    frame.left_model = *lf;
    frame.right_model = *rf;
    frame.left = left;
    frame.right = right;
    dl::stereo::StereoRanger ranger(dl::stereo::StereoRangerOptions{},
                                    dl::stereo::VehicleMask(hwconfig::RoverDescription{},
                                                            dl::stereo::VehicleMaskOptions{}));
    dl::stereo::PoseLookup no_pose;
    no_pose.required = false;
    auto image = ranger.Range(frame, 1, no_pose);
    EXPECT_TRUE(image.ok()) << image.status().message();
    std::vector<BandStats> bands(kNumBands);
    if (!image.ok()) return bands;
    for (std::size_t k = 0; k < image->valid.size(); ++k) {
      if (image->valid[k] == 0) continue;
      const Eigen::Vector3d p(image->xyz[3 * k], image->xyz[3 * k + 1], image->xyz[3 * k + 2]);
      const double d = std::hypot(p.x(), p.y());
      const Eigen::Vector3d q = site_from_rover * p;
      const double err = q.z() - terrain_->natural.Height(q.x(), q.y());
      for (int b = 0; b < kNumBands; ++b) {
        if (d >= kBands[b] && d < kBands[b + 1]) {
          ++bands[b].points;
          bands[b].sum_sq += err * err;
          if (std::abs(err) > 0.10) ++bands[b].off_10cm;
        }
      }
    }
    return bands;
  }

  std::shared_ptr<const sim::terrain::Terrain> terrain_;
  ddl::camera::CameraCalibration calibration_;
};

std::vector<std::uint8_t> Bytes(const cv::Mat& m) {
  EXPECT_TRUE(m.isContinuous() && m.type() == CV_8UC1);
  return {m.data, m.data + m.total()};
}

TEST_F(StereoOnSimImagesTest, BinnedHazcamReadoutRangesAsWellAsTheFullFrameDownsampled) {
  sim::rover_sim::CameraHeadOptions options;
  options.image_size = kSensor;
  sim::rover_sim::CameraHead head(options, terrain_, hwconfig::RoverDescription{});
  const Eigen::Vector3d sun = Eigen::Vector3d(0.4, 0.3, 0.8).normalized();
  std::vector<BandStats> binned_sum(kNumBands), full_sum(kNumBands);
  // Three poses, so that one lucky or unlucky patch of ground does not decide.
  const double poses[][3] = {{0.0, 0.0, 0.0}, {1.0, -0.5, 0.6}, {2.0, 0.5, -0.8}};
  for (const auto& xyyaw : poses) {
    const Eigen::Isometry3d pose =
        sim::render::RoverPoseOnGround(terrain_->ground, xyyaw[0], xyyaw[1], xyyaw[2]);
    auto binned = head.Take("front_hazcam", 0, pose, sim::render::MastState{}, sun, kWidth);
    if (!binned.ok() && binned.status().code() == StatusCode::kUnavailable) {
      GTEST_SKIP() << "no EGL renderer: " << binned.status().message();
    }
    ASSERT_TRUE(binned.ok()) << binned.status().message();
    auto full = head.Take("front_hazcam", 0, pose, sim::render::MastState{}, sun, 0);
    ASSERT_TRUE(full.ok()) << full.status().message();
    ASSERT_EQ(binned->images.left.image.cols, kWidth);
    ASSERT_EQ(full->images.left.image.cols, kSensor);

    auto down = [](const cv::Mat& m) {
      ddl::camera::GrayImage in{m.cols, m.rows, Bytes(m)};
      auto out = ddl::camera::AreaDownsample(in, kWidth, kWidth);
      EXPECT_TRUE(out.ok()) << out.status().message();
      return out.ok() ? out->pixels : std::vector<std::uint8_t>{};
    };
    const auto b = RangeAndCompare(Bytes(binned->images.left.image),
                                   Bytes(binned->images.right.image), pose);
    const auto f = RangeAndCompare(down(full->images.left.image),
                                   down(full->images.right.image), pose);
    for (int k = 0; k < kNumBands; ++k) {
      for (auto [sum, one] : {std::pair{&binned_sum[k], &b[k]}, std::pair{&full_sum[k], &f[k]}}) {
        sum->points += one->points;
        sum->off_10cm += one->off_10cm;
        sum->sum_sq += one->sum_sq;
      }
    }
  }
  for (int k = 0; k < kNumBands; ++k) {
    const BandStats& b = binned_sum[k];
    const BandStats& f = full_sum[k];
    std::printf("[ info ] %.1f-%.1f m: binned %d points, RMS %.1f cm, %.2f %% > 10 cm | full "
                "downsampled %d points, RMS %.1f cm, %.2f %% > 10 cm\n",
                kBands[k], kBands[k + 1], b.points, 100 * b.Rms(), 100 * b.OffShare(), f.points,
                100 * f.Rms(), 100 * f.OffShare());
    ASSERT_GT(f.points, 500) << "band " << k;
    // About as many points (binning loses none of the texture the correlator needs) ...
    EXPECT_GT(b.points, 0.8 * f.points) << "band " << k;
    // ... and as accurate: tolerances for the two images' independent noise.
    EXPECT_LT(b.Rms(), 1.3 * f.Rms() + 0.005) << "band " << k;
    EXPECT_LT(b.OffShare(), 1.5 * f.OffShare() + 0.005) << "band " << k;
  }
}

}  // namespace
}  // namespace rover
