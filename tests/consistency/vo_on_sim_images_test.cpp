// Visual odometry on the simulator's own images, in process and without DDS: the HAZCAM pair
// rendered by sim/render at two rover poses, downsampled as ddl-camera does, rectified from the
// driver's calibration (deploy/config/cameras.yaml) as dl-vo does, and the motion estimated by
// dl_vo must match the true motion. This is the chain behind `deploy/scenarios/sand_slope_vo.yaml`
// with every process boundary removed, so a failure here points at the images or the models.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/imgcodecs.hpp>

#include "rover/ddl/camera/camera_calibration.hpp"
#include "rover/dl/stereo/geometry_adapter.hpp"
#include "rover/dl/stereo/rectification.hpp"
#include "rover/dl/vo/visual_odometry.hpp"
#include "rover/geometry/camera_model.hpp"
#include "rover/sim/render/cameras.hpp"
#include "rover/sim/render/renderer.hpp"
#include "rover/sim/terrain/terrain.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {

constexpr int kWidth = 512;
// The step between the two pairs [m]; ROVER_TEST_STEP overrides it for exploring. On the
// rendered sand, with the HAZCAM 0.5 m above the ground looking 45 deg down, the tracks that
// survive a step fall fast with its length (measured, 512 px: 0.02 m 297, 0.1 m 52, 0.15 m 21,
// 0.2 m 8, 0.3 m 1; without template warping 0.1 m gave 12): dl-vo runs the HAZCAM at 0.1 m.
double StepFromEnv() {
  const char* s = std::getenv("ROVER_TEST_STEP");
  return s ? std::atof(s) : 0.1;
}  // dl-vo's default processing width

struct Pair {
  cv::Mat left, right;
};

class VoOnSimImagesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    sim::terrain::TerrainParams p;
    p.size_x = 30;
    p.size_y = 16;
    p.center_x = 8;
    p.slope.angle_deg = 15;
    p.hills.amplitude = 0;
    p.craters.count = 0;
    p.rocks.preset = sim::terrain::RockPreset::kNone;
    p.soil.sand_fraction = 1.0;
    p.soil.bedrock_fraction = 0.0;
    p.seed = 1;
    auto t = sim::terrain::GenerateTerrain(p);
    ASSERT_TRUE(t.ok()) << t.status().message();
    terrain_ = std::make_shared<sim::terrain::Terrain>(std::move(*t));
    auto r = sim::render::Renderer::Create(terrain_, sim::render::RenderOptions{});
    if (!r.ok()) GTEST_SKIP() << "no EGL renderer: " << r.status().message();
    renderer_ = std::move(*r);
    auto cal =
        ddl::camera::LoadCameraCalibration(testing::SourceDir() + "/deploy/config/cameras.yaml");
    ASSERT_TRUE(cal.ok()) << cal.status().message();
    calibration_ = *cal;
  }

  // The pair the driver would publish at `site_from_rover`: rendered at 1024, area-averaged to
  // kWidth.
  Pair Capture(const Eigen::Isometry3d& site_from_rover, std::uint64_t frame) {
    auto def =
        sim::render::FindStereoCamera(sim::render::DefaultStereoCameras(1024), "front_hazcam");
    EXPECT_TRUE(def.ok());
    auto spec = sim::render::MakeCameraPairSpec(*def, {});
    EXPECT_TRUE(spec.ok());
    auto images = renderer_->RenderStereoPair(site_from_rover, *spec, frame);
    EXPECT_TRUE(images.ok()) << images.status().message();
    Pair out;
    cv::resize(images->left.image, out.left, cv::Size(kWidth, kWidth), 0, 0, cv::INTER_AREA);
    cv::resize(images->right.image, out.right, cv::Size(kWidth, kWidth), 0, 0, cv::INTER_AREA);
    return out;
  }

  std::shared_ptr<sim::terrain::Terrain> terrain_;
  std::unique_ptr<sim::render::Renderer> renderer_;
  ddl::camera::CameraCalibration calibration_;
};

TEST_F(VoOnSimImagesTest, HazcamStepUpTheSandSlopeMatchesTruth) {
  const auto& haz = calibration_.cameras[1];  // front_hazcam
  ASSERT_EQ(haz.name, "front_hazcam");
  const double s = static_cast<double>(kWidth) / haz.left.width();
  auto setup = dl::stereo::MakeStereoSetup(geometry::Scale(haz.left, s), geometry::Scale(haz.right, s));
  ASSERT_TRUE(setup.ok()) << setup.status().message();
  const auto& cam_model = setup->camera.model;
  dl::vo::StereoCamera cam;
  cv::Mat rl, rr;

  const Eigen::Isometry3d a = sim::render::RoverPoseOnGround(terrain_->ground, 1.0, 0.0, 0.0);
  const Eigen::Isometry3d b =
      sim::render::RoverPoseOnGround(terrain_->ground, 1.0 + StepFromEnv(), 0.005, 0.01);
  const Pair pa = Capture(a, 1);
  const Pair pb = Capture(b, 2);

  ASSERT_TRUE(dl::stereo::Rectify(setup->maps, pa.left, pa.right, &rl, &rr).ok());
  cam.width = rl.cols;
  cam.height = rl.rows;
  cam.fx = cam.fy = cam_model.focal_px;
  cam.cx = cam_model.cx;
  cam.cy = cam_model.cy;
  cam.baseline = cam_model.baseline_m;
  if (const char* dump = std::getenv("ROVER_TEST_DUMP")) {
    cv::imwrite(std::string(dump) + "/raw_left.png", pa.left);
    cv::imwrite(std::string(dump) + "/rect_left.png", rl);
    cv::imwrite(std::string(dump) + "/rect_right.png", rr);
  }
  dl::vo::Options options = dl::vo::Options::Rover();
  if (std::getenv("ROVER_TEST_NOWARP")) options.warp_templates = false;
  auto vo = dl::vo::VisualOdometry::Create(options, cam);
  ASSERT_TRUE(vo.ok()) << vo.status().message();
  dl::vo::StereoFrame fa{Time::FromSeconds(1), rl.clone(), rr.clone()};
  auto first = vo->Process(fa, dl::vo::MotionPrior{});
  ASSERT_TRUE(first.ok()) << first.status().message();
  std::printf("[ info ] rectified %dx%d f %.1f px baseline %.3f m\n", cam.width, cam.height,
              cam.fx, cam.baseline);

  ASSERT_TRUE(dl::stereo::Rectify(setup->maps, pb.left, pb.right, &rl, &rr).ok());
  // Prior from the truth with wheel-odometry-like uncertainty (10 cm, 2 deg): what dl-vo
  // gets from dl/pose, here without its error so that only the image chain is tested.
  const Eigen::Isometry3d t_rc = setup->camera.rover_from_camera;
  const Eigen::Isometry3d truth_cam = t_rc.inverse() * a.inverse() * b * t_rc;
  dl::vo::MotionPrior prior;
  prior.delta = truth_cam;
  prior.covariance.setZero();
  prior.covariance.diagonal() << 0.01, 0.01, 0.01, 1.2e-3, 1.2e-3, 1.2e-3;
  dl::vo::StereoFrame fb{Time::FromSeconds(2), rl.clone(), rr.clone()};
  auto est = vo->Process(fb, prior);
  ASSERT_TRUE(est.ok()) << est.status().message();
  std::printf("[ info ] step: %s, %d selected, %d stereo, %d tracked, %d inliers, translation "
              "error %.4f m of %.3f m\n",
              est->converged() ? "converged" : est->message.c_str(), est->features_selected,
              est->features_stereo, est->features_tracked,
              est->inliers, (est->delta.translation() - truth_cam.translation()).norm(),
              truth_cam.translation().norm());
  ASSERT_TRUE(est->converged()) << est->message;
  EXPECT_GE(est->features_stereo, 200);  // the reference pair's texture is rich enough
  EXPECT_GE(est->inliers, 30);
  // MER's VO goal was 1 % of the distance over a drive; one step well within that.
  EXPECT_LT((est->delta.translation() - truth_cam.translation()).norm(),
            0.005 * truth_cam.translation().norm());
}

}  // namespace
}  // namespace rover
