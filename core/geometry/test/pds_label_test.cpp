#include "rover/geometry/pds_label.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace rover::geometry {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> MslLabels() {
  const fs::path dir = fs::path(ROVER_SHARED_DATA_DIR) / "msl-navcam-sol555";
  std::vector<std::string> labels;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return labels;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.path().extension() == ".LBL") labels.push_back(entry.path().string());
  }
  std::sort(labels.begin(), labels.end());
  return labels;
}

// MODEL_COMPONENT_k as printed in the label, read independently of the parser (the MSL labels
// print each of C, A, H, V on one line).
Eigen::Vector3d RawComponent(const std::string& path, int k) {
  std::ifstream in(path);
  std::string line;
  const std::string key = "MODEL_COMPONENT_" + std::to_string(k);
  while (std::getline(in, line)) {
    if (line.find(key) == std::string::npos) continue;
    double x = 0, y = 0, z = 0;
    const std::size_t open = line.find('(');
    if (open != std::string::npos &&
        std::sscanf(line.c_str() + open, "(%lf,%lf,%lf)", &x, &y, &z) == 3) {
      return {x, y, z};
    }
  }
  return Eigen::Vector3d::Constant(std::nan(""));
}

#define SKIP_WITHOUT_MSL_DATA(labels)                                                             \
  if ((labels).empty()) {                                                                         \
    GTEST_SKIP() << "no MSL NAVCAM labels in " << ROVER_SHARED_DATA_DIR                           \
                 << "/msl-navcam-sol555 (set -DROVER_SHARED_DATA_DIR to the shared data folder)"; \
  }

TEST(PdsLabelMsl, ParsesEveryLabelWithItsFrames) {
  const auto labels = MslLabels();
  SKIP_WITHOUT_MSL_DATA(labels);
  EXPECT_EQ(labels.size(), 41u);
  for (const std::string& path : labels) {
    const auto label = ReadPdsCameraLabel(path);
    ASSERT_TRUE(label.ok()) << label.status().ToString();
    EXPECT_EQ(label->model_type, "CAHVOR");
    EXPECT_EQ(label->model.kind(), CameraModel::Kind::kCahvor);
    EXPECT_EQ(label->model.width(), 256);
    EXPECT_EQ(label->model.height(), 256);
    EXPECT_EQ(label->model_frame, "ROVER_NAV_FRAME");
    EXPECT_EQ(label->model_frame_index.size(), 10u);
    const PdsCoordinateSystem* rover = label->FindByName("ROVER_NAV_FRAME");
    ASSERT_NE(rover, nullptr);
    EXPECT_EQ(rover->group, "ROVER_COORD_SYSTEM_PARMS");
    EXPECT_EQ(rover->reference_name, "SITE_FRAME");
    const PdsCoordinateSystem* site = label->FindByName("SITE_FRAME");
    ASSERT_NE(site, nullptr);
    EXPECT_EQ(site->reference_name, "SITE_FRAME");  // the previous site
    const PdsCoordinateSystem* head = label->FindByName("RSM_HEAD_FRAME");
    ASSERT_NE(head, nullptr);
    EXPECT_EQ(head->reference_name, "ROVER_NAV_FRAME");
    const PdsCoordinateSystem* arm = label->FindByGroup("ARM_COORD_SYSTEM_PARMS");
    ASSERT_NE(arm, nullptr);
    EXPECT_EQ(arm->reference_name, "ROVER_MECH_FRAME");
    const PdsCoordinateSystem* initial = label->FindByGroup("INITIAL_STATE_PARMS");
    ASSERT_NE(initial, nullptr);
    EXPECT_EQ(initial->reference_name, "");
    // The onboard rover pose: within 100 m of the site origin, nearly level.
    EXPECT_LT(rover->origin_offset.norm(), 100.0);
    const Eigen::Vector3d up_nav = rover->ReferenceFromFrame().linear().col(2);  // z down
    EXPECT_GT(up_nav.z(), std::cos(15.0 * std::numbers::pi / 180.0));
    // Quaternion convention check: the mast head's x axis (its boresight), rotated into the
    // rover-nav frame, is the camera model's axis A to within 1 deg.
    const Eigen::Vector3d head_x = head->ReferenceFromFrame().linear().col(0);
    const Cahvor& m = *label->model.As<Cahvor>();
    EXPECT_GT(head_x.dot(m.a.normalized()), std::cos(1.0 * std::numbers::pi / 180.0)) << path;
  }
}

TEST(PdsLabelMsl, IntrinsicsMatchTheNavcam) {
  const auto labels = MslLabels();
  SKIP_WITHOUT_MSL_DATA(labels);
  for (const std::string& path : labels) {
    const auto label = ReadPdsCameraLabel(path);
    ASSERT_TRUE(label.ok()) << label.status().ToString();
    const Cahvor& m = *label->model.As<Cahvor>();
    const Intrinsics in = ComputeIntrinsics(m);
    // What the components imply. The label's A has |A| = 1 - 8.5e-6; Create divides A, H, V by
    // |A| (projection unchanged), which scales A.H, |A x H| etc. by 1 / |A|^2 = 1 + 1.7e-5,
    // i.e. by up to 5e-3 px, relative to the raw label values.
    const Eigen::Vector3d raw_a = RawComponent(path, 2);
    const Eigen::Vector3d raw_h = RawComponent(path, 3);
    const Eigen::Vector3d raw_v = RawComponent(path, 4);
    const double n2 = raw_a.squaredNorm();
    EXPECT_NEAR(n2, 1.0, 2e-5);
    EXPECT_NEAR(in.hc * n2, raw_a.dot(raw_h), 1e-9);
    EXPECT_NEAR(in.vc * n2, raw_a.dot(raw_v), 1e-9);
    EXPECT_NEAR(in.hs * n2, raw_a.cross(raw_h).norm(), 1e-9);
    EXPECT_NEAR(in.vs * n2, raw_a.cross(raw_v).norm(), 1e-9);
    EXPECT_NEAR(in.hc, raw_a.dot(raw_h), 6e-3);
    EXPECT_NEAR(in.vc, raw_a.dot(raw_v), 6e-3);
    EXPECT_NEAR(in.hs, raw_a.cross(raw_h).norm(), 6e-3);
    EXPECT_NEAR(in.vs, raw_a.cross(raw_v).norm(), 6e-3);
    EXPECT_NEAR(m.a.norm(), 1.0, 1e-15);
    // Principal point within 3 px of the centre of the 256 x 256 image (127.5, 127.5).
    EXPECT_NEAR(in.hc, 127.5, 3.0) << path;
    EXPECT_NEAR(in.vc, 127.5, 3.0) << path;
    // 45 deg field of view over 256 px: f = 128 / tan(22.5 deg) = 309 px; within 2 %.
    const double f = 128.0 / std::tan(22.5 * std::numbers::pi / 180.0);
    EXPECT_NEAR(in.hs, f, 0.02 * f) << path;
    EXPECT_NEAR(in.vs, f, 0.02 * f) << path;
    EXPECT_NEAR(in.theta, std::numbers::pi / 2, 1e-3) << path;
    // The first label's values, computed independently from its text.
    if (path.find("NLB_446763623EDR_D0280304TRAV00187M1.LBL") != std::string::npos) {
      // A.H etc. of the raw label vectors: 126.2831, 125.2876, 306.1786, 306.2075; with
      // |A| = 0.99999151 normalised out they are divided by |A|^2.
      EXPECT_NEAR(in.hc, 126.2831 / (0.99999151 * 0.99999151), 1e-4);
      EXPECT_NEAR(in.vc, 125.2876 / (0.99999151 * 0.99999151), 1e-4);
      EXPECT_NEAR(in.hs, 306.1786 / (0.99999151 * 0.99999151), 1e-4);
      EXPECT_NEAR(in.vs, 306.2075 / (0.99999151 * 0.99999151), 1e-4);
      EXPECT_TRUE(m.c.isApprox(Eigen::Vector3d(0.920061, 0.344876, -1.88112)));
      EXPECT_TRUE(
          (m.a * 0.99999151).isApprox(Eigen::Vector3d(0.880773, -0.00456061, 0.473499), 1e-7));
      EXPECT_TRUE(m.r.isApprox(Eigen::Vector3d(0.0, 0.000130128, 0.00637786)));
    }
  }
}

TEST(PdsLabelMsl, PointsOnTheAxisProjectToThePrincipalPoint) {
  const auto labels = MslLabels();
  SKIP_WITHOUT_MSL_DATA(labels);
  double worst = 0.0;
  for (const std::string& path : labels) {
    const auto label = ReadPdsCameraLabel(path);
    ASSERT_TRUE(label.ok());
    const Cahvor& m = *label->model.As<Cahvor>();
    const Intrinsics in = ComputeIntrinsics(m);
    for (const double t : {0.5, 1.0, 10.0, 100.0}) {
      const auto px = label->model.Project(m.c + t * m.a);
      ASSERT_TRUE(px);
      // O is 1.7e-4 deg off A, so the distortion moves the axis by ~1e-10 px. (With the raw,
      // non-unit A of the label the axis would land on (hc, vc) / |A|^2, 2e-3 px away.)
      worst = std::max(worst, (*px - Eigen::Vector2d(in.hc, in.vc)).norm());
    }
    // And the principal point's ray is A.
    const auto ray = label->model.Unproject({in.hc, in.vc});
    ASSERT_TRUE(ray);
    EXPECT_LT((ray->direction - m.a).norm(), 1e-9);
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(PdsLabelMsl, RoundTripsAndConversionsOnRealModels) {
  const auto labels = MslLabels();
  SKIP_WITHOUT_MSL_DATA(labels);
  const auto label = ReadPdsCameraLabel(labels.front());
  ASSERT_TRUE(label.ok());
  const CameraModel& m = label->model;
  double worst = 0.0;
  for (int j = 0; j <= 16; ++j) {
    for (int i = 0; i <= 16; ++i) {
      const Eigen::Vector2d px(255.0 * i / 16, 255.0 * j / 16);
      const auto ray = m.Unproject(px);
      ASSERT_TRUE(ray);
      for (const double t : {1.0, 20.0}) {
        worst = std::max(worst, (*m.Project(ray->origin + t * ray->direction) - px).norm());
      }
    }
  }
  EXPECT_LT(worst, 1e-6);
  // The equivalent pinhole with Brown radial distortion: 0.01 px over the image.
  const auto fit = ToPinholeRadial(m);
  ASSERT_TRUE(fit.ok()) << fit.status().ToString();
  EXPECT_LT(fit->max_error_px, 0.01);
  RecordProperty("msl_navcam_pinhole_fit_max_px", ::testing::PrintToString(fit->max_error_px));
  RecordProperty("msl_navcam_pinhole_fit_rms_px", ::testing::PrintToString(fit->rms_error_px));
  // In the stack's rover frame (x fwd, y left, z up) the NAVCAM sits ~1.9 m up, looking down
  // and forward.
  const CameraModel rover = Transform(m, RoverFromMslNav());
  EXPECT_GT(rover.Center().z(), 1.5);
  const Eigen::Vector3d a = rover.As<Cahvor>()->a;
  EXPECT_LT(a.z(), -0.3);
  EXPECT_GT(a.x(), 0.8);
}

// --- synthetic labels: formats and errors --------------------------------------------------

const char* kCahvoreLabel = R"(PDS_VERSION_ID = PDS3
/* A HAZCAM-like label */
GROUP                             = GEOMETRIC_CAMERA_MODEL_PARMS
  MODEL_TYPE                      = CAHVORE
  MODEL_COMPONENT_1               = (0.1, 0.2, -1.0)
  MODEL_COMPONENT_2               = (1.0, 0.0, 0.0)
  MODEL_COMPONENT_3               = (511.0, 330.0,
                                     0.0)
  MODEL_COMPONENT_4               = (512.0, 0.0, 331.0)
  MODEL_COMPONENT_5               = (1.0, 0.0, 0.0)
  MODEL_COMPONENT_6               = (0.0, -0.01, 0.002)
  MODEL_COMPONENT_7               = (0.01, 0.005, -0.001)
  MODEL_COMPONENT_8               = 3.0
  MODEL_COMPONENT_9               = 0.4
  REFERENCE_COORD_SYSTEM_NAME     = "ROVER_NAV_FRAME"
END_GROUP                         = GEOMETRIC_CAMERA_MODEL_PARMS
GROUP = ROVER_COORD_SYSTEM_PARMS
  COORDINATE_SYSTEM_NAME = "ROVER_NAV_FRAME"
  ORIGIN_OFFSET_VECTOR = (1.0, 2.0, 3.0)
  ORIGIN_ROTATION_QUATERNION = (0.7071067811865476, 0.0, 0.0, 0.7071067811865476)
  REFERENCE_COORD_SYSTEM_NAME = "SITE_FRAME"
END_GROUP = ROVER_COORD_SYSTEM_PARMS
OBJECT = IMAGE
  LINES = 1024
  LINE_SAMPLES = 1024
END_OBJECT = IMAGE
END
)";

TEST(PdsLabel, ParsesCahvoreAndPoses) {
  const auto label = ParsePdsCameraLabel(kCahvoreLabel, "haz.LBL");
  ASSERT_TRUE(label.ok()) << label.status().ToString();
  const Cahvore* m = label->model.As<Cahvore>();
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->type, CahvoreType::kGeneral);
  EXPECT_EQ(m->parameter, 0.4);
  EXPECT_EQ(m->h, Eigen::Vector3d(511.0, 330.0, 0.0));
  EXPECT_EQ(m->e, Eigen::Vector3d(0.01, 0.005, -0.001));
  ASSERT_EQ(label->coordinate_systems.size(), 1u);
  const Eigen::Isometry3d t = label->coordinate_systems[0].ReferenceFromFrame();
  // 90 deg about z: the frame's x axis is the reference's y axis.
  EXPECT_TRUE((t.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_TRUE(t.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_EQ(label->coordinate_systems[0].line, 19);
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos) std::abort();
  return text.replace(at, from.size(), to);
}

TEST(PdsLabel, ErrorsNameFileLineAndKey) {
  // A malformed component.
  auto r = ParsePdsCameraLabel(Replace(kCahvoreLabel, "(1.0, 0.0, 0.0)\n  MODEL_COMPONENT_3",
                                       "(1.0, x)\n  MODEL_COMPONENT_3"),
                               "haz.LBL");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("haz.LBL:6: GEOMETRIC_CAMERA_MODEL_PARMS.MODEL_COMPONENT_2"),
            std::string::npos)
      << r.status().ToString();
  // A missing component: names the group's line.
  r = ParsePdsCameraLabel(Replace(kCahvoreLabel, "MODEL_COMPONENT_5", "MODEL_COMPONENT_X"),
                          "haz.LBL");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("haz.LBL:3: GEOMETRIC_CAMERA_MODEL_PARMS.MODEL_COMPONENT_5: "
                                      "missing"),
            std::string::npos)
      << r.status().ToString();
  // An invalid model (|A| = 2).
  r = ParsePdsCameraLabel(Replace(kCahvoreLabel, "(1.0, 0.0, 0.0)\n  MODEL_COMPONENT_3",
                                  "(2.0, 0.0, 0.0)\n  MODEL_COMPONENT_3"),
                          "haz.LBL");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("|A|"), std::string::npos) << r.status().ToString();
  // Unsupported model type, bad CAHVORE type, missing image size, bad quaternion, syntax.
  r = ParsePdsCameraLabel(Replace(kCahvoreLabel, "= CAHVORE", "= PSPH"), "haz.LBL");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("haz.LBL:4: GEOMETRIC_CAMERA_MODEL_PARMS.MODEL_TYPE"),
            std::string::npos);
  r = ParsePdsCameraLabel(Replace(kCahvoreLabel, "= 3.0", "= 5.0"), "haz.LBL");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("MODEL_COMPONENT_8"), std::string::npos);
  r = ParsePdsCameraLabel(Replace(kCahvoreLabel, "LINE_SAMPLES = 1024", ""), "haz.LBL");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("IMAGE.LINE_SAMPLES: missing"), std::string::npos)
      << r.status().ToString();
  r = ParsePdsCameraLabel(
      Replace(kCahvoreLabel, "(0.7071067811865476, 0.0, 0.0, 0.7071067811865476)",
              "(0.5, 0.0, 0.0, 0.5)"),
      "haz.LBL");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("haz.LBL:20: ROVER_COORD_SYSTEM_PARMS.ORIGIN_ROTATION_"
                                      "QUATERNION"),
            std::string::npos)
      << r.status().ToString();
  r = ParsePdsCameraLabel(Replace(kCahvoreLabel, "(0.0, -0.01, 0.002)", "(0.0, -0.01, 0.002"),
                          "haz.LBL");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("haz.LBL:11:"), std::string::npos) << r.status().ToString();
  r = ParsePdsCameraLabel("PDS_VERSION_ID = PDS3\nEND\n", "empty.LBL");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("empty.LBL"), std::string::npos);
  r = ReadPdsCameraLabel("/nonexistent/x.LBL");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kNotFound);
}

TEST(PdsLabel, RoverFromMslNavFlipsYAndZ) {
  const Eigen::Isometry3d t = RoverFromMslNav();
  EXPECT_EQ(t * Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, -2, -3));
  EXPECT_NEAR(t.linear().determinant(), 1.0, 1e-15);
}

}  // namespace
}  // namespace rover::geometry
