#include "rover/msg/camera_idl.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "rover/geometry/transforms.hpp"
#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

geometry::CameraModel TiltedCahvor() {
  geometry::Cahvor c;
  c.c = Eigen::Vector3d(0.4, 0.1, 1.5);
  const Eigen::Matrix3d r = geometry::RotationFromRpy(0.1, 0.3, -0.7);
  c.a = r.col(0);
  c.h = 300.0 * (-r.col(1)) + 127.5 * c.a;
  c.v = 300.0 * (-r.col(2)) + 95.5 * c.a;
  c.o = c.a;
  c.r = Eigen::Vector3d(0.0, -0.02, 0.001);
  return *geometry::CameraModel::Create(c, 256, 192);
}

TEST(CameraIdl, CameraIds) {
  EXPECT_EQ(CameraIdToIdl(CameraId::kRearHazcam), rover_CAMERA_REAR_HAZCAM);
  auto c = CameraIdFromIdl(rover_CAMERA_FRONT_HAZCAM);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(*c, CameraId::kFrontHazcam);
  rover_CameraId bad{};
  idl::SetRawEnum(&bad, 5);
  auto r = CameraIdFromIdl(bad);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(), "camera = 5 is not a CameraId (0..2)");
}

TEST(CameraIdl, ModelFieldsRoundTripExactly) {
  const geometry::CameraModel model = TiltedCahvor();
  auto fields = CameraModelFieldsFromModel(model);
  ASSERT_TRUE(fields.ok()) << fields.status().ToString();
  rover_ddl_CameraModel m{};
  CameraModelToIdl(*fields, &m);
  const auto* c = model.As<geometry::Cahvor>();
  ASSERT_NE(c, nullptr);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(m.c[i], c->c[i]);
    EXPECT_NEAR(m.a[i], c->a[i], 1e-15);
    EXPECT_NEAR(m.h[i], c->h[i], 1e-12);
    EXPECT_NEAR(m.v[i], c->v[i], 1e-12);
    EXPECT_NEAR(m.r[i], c->r[i], 1e-15);
  }
  EXPECT_EQ(m.fx, fields->fx);
  EXPECT_EQ(m.k2, fields->k2);
  EXPECT_EQ(m.width, 256);
  EXPECT_EQ(m.height, 192);
  EXPECT_DOUBLE_EQ(m.pose.orientation.w, fields->orientation[0]);
  // The pose is the pinhole camera frame (z = A) at C, quaternion w first with w >= 0.
  EXPECT_NEAR(m.pose.position.x, 0.4, 1e-12);
  EXPECT_NEAR(m.pose.position.z, 1.5, 1e-12);
  const Eigen::Quaterniond q(m.pose.orientation.w, m.pose.orientation.x, m.pose.orientation.y,
                             m.pose.orientation.z);
  EXPECT_GE(q.w(), 0.0);
  EXPECT_NEAR(q.norm(), 1.0, 1e-12);
  EXPECT_LT((q.toRotationMatrix().col(2) - c->a).norm(), 1e-9);
  EXPECT_EQ(CameraModelFieldsFromIdl(m), *fields);
}

TEST(CameraIdl, GeometryModelRoundTrip) {
  const geometry::CameraModel model = TiltedCahvor();
  rover_ddl_CameraModel m{};
  ASSERT_TRUE(CameraModelToIdl(model, &m).ok());
  auto back = CameraModelFromIdl(m);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->kind(), geometry::CameraModel::Kind::kCahvor);
  const Eigen::Vector3d p =
      model.Unproject({30.0, 40.0})->origin + 5.0 * model.Unproject({30.0, 40.0})->direction;
  EXPECT_LT((*back->Project(p) - *model.Project(p)).norm(), 1e-9);
  // A corrupt model is refused naming the field.
  m.k2 = std::numeric_limits<double>::infinity();
  auto bad = CameraModelFromIdl(m);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("'k2'"), std::string::npos) << bad.status().message();
}

TEST(CameraIdl, RequestRoundTripKeepsAnUnknownCamera) {
  rover_ddl_StereoRequest r{};
  r.header.stamp_ns = 4;
  r.request_id = 12;
  r.camera = rover_CAMERA_REAR_HAZCAM;
  r.exposure_us = 5000;
  r.width = 256;
  StereoRequest q = StereoRequestFromIdl(r);
  EXPECT_EQ(q.stamp.ns, 4);
  EXPECT_EQ(q.request_id, 12u);
  EXPECT_EQ(q.camera, CameraId::kRearHazcam);
  EXPECT_EQ(q.exposure_us, 5000u);
  EXPECT_EQ(q.width, 256);
  rover_ddl_StereoRequest back{};
  StereoRequestToIdl(q, &back);
  EXPECT_EQ(back.header.stamp_ns, 4);
  EXPECT_EQ(back.request_id, 12u);
  EXPECT_EQ(back.camera, rover_CAMERA_REAR_HAZCAM);
  EXPECT_EQ(back.exposure_us, 5000u);
  EXPECT_EQ(back.width, 256);
  idl::SetRawEnum(&r.camera, 9);  // a camera no enum value names, as a corrupt sample could carry
  EXPECT_EQ(static_cast<int>(StereoRequestFromIdl(r).camera), 9);
}

// A ddl/stereo_frame with w x h images whose pixel (u, v) of the left image is u + v and of the
// right image 2u; models are only sized (their content is not checked here).
struct Frame {
  Frame(int w, int h) : left(static_cast<std::size_t>(w * h)), right(left.size()) {
    msg.header.stamp_ns = 5'000'000'000;
    msg.request_id = 4;
    msg.camera = rover_CAMERA_NAVCAM;
    msg.exposure_us = 800;
    msg.width = static_cast<std::uint16_t>(w);
    msg.height = static_cast<std::uint16_t>(h);
    for (int v = 0; v < h; ++v) {
      for (int u = 0; u < w; ++u) {
        left[static_cast<std::size_t>(v * w + u)] = static_cast<std::uint8_t>(u + v);
        right[static_cast<std::size_t>(v * w + u)] = static_cast<std::uint8_t>(2 * u);
      }
    }
    msg.left_model.width = msg.right_model.width = msg.width;
    msg.left_model.height = msg.right_model.height = msg.height;
    msg.left_model.fx = 1.0;
    msg.health = rover_HEALTH_DEGRADED;
    Attach();
  }
  void Attach() {
    idl::BorrowSequence(msg.left, left);
    idl::BorrowSequence(msg.right, right);
  }
  rover_ddl_StereoFrame msg{};
  std::vector<std::uint8_t> left, right;
};

TEST(CameraIdl, StereoFrameViewsTheMessageImagesAndRoundTrips) {
  Frame f(16, 8);
  auto p = StereoFrameFromIdl(f.msg);
  ASSERT_TRUE(p.ok()) << p.status().ToString();
  EXPECT_EQ(p->stamp.ns, 5'000'000'000);
  EXPECT_EQ(p->request_id, 4u);
  EXPECT_EQ(p->camera, CameraId::kNavcam);
  EXPECT_EQ(p->exposure_us, 800u);
  EXPECT_EQ(p->width, 16);
  EXPECT_EQ(p->height, 8);
  EXPECT_EQ(p->left[3 * 16 + 5], 8);  // row-major
  EXPECT_EQ(p->right[7 * 16 + 6], 12);
  EXPECT_EQ(p->left.data(), f.left.data());  // a view, no copy
  EXPECT_EQ(p->left_model.fx, 1.0);
  EXPECT_EQ(p->right_model.width, 16);
  EXPECT_EQ(p->health, SensorHealth::kDegraded);

  rover_ddl_StereoFrame out{};
  StereoFrameToIdl(*p, &out);
  EXPECT_EQ(out.header.stamp_ns, 5'000'000'000);
  EXPECT_EQ(out.request_id, 4u);
  EXPECT_EQ(out.camera, rover_CAMERA_NAVCAM);
  EXPECT_EQ(out.exposure_us, 800u);
  EXPECT_EQ(out.width, 16);
  EXPECT_EQ(out.height, 8);
  ASSERT_EQ(out.left._length, 128u);
  EXPECT_EQ(out.left._buffer, f.left.data());  // borrowed, not copied
  EXPECT_EQ(out.right._buffer[7 * 16 + 6], 12);
  EXPECT_FALSE(out.left._release);
  EXPECT_EQ(out.health, rover_HEALTH_DEGRADED);
  EXPECT_EQ(out.left_model.width, 16);
  EXPECT_EQ(out.left_model.fx, 1.0);
}

TEST(CameraIdl, BadFramesAreErrorsNamingTheProblem) {
  Frame f(16, 8);
  f.right.pop_back();
  f.Attach();
  auto p = StereoFrameFromIdl(f.msg);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("right image has 127 bytes; expected 16x8 = 128"),
            std::string::npos)
      << p.status().message();

  Frame g(16, 8);
  g.msg.right_model.width = 32;
  p = StereoFrameFromIdl(g.msg);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("right camera model is for 32x8"), std::string::npos)
      << p.status().message();

  Frame n(16, 8);
  n.msg.left._buffer = nullptr;
  p = StereoFrameFromIdl(n.msg);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("null"), std::string::npos) << p.status().message();

  Frame c(16, 8);
  idl::SetRawEnum(&c.msg.camera, 3);
  p = StereoFrameFromIdl(c.msg);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("camera = 3"), std::string::npos) << p.status().message();

  Frame h(16, 8);
  idl::SetRawEnum(&h.msg.health, 6);
  EXPECT_FALSE(StereoFrameFromIdl(h.msg).ok());

  Frame s(16, 8);
  s.msg.header.stamp_ns = 0;
  p = StereoFrameFromIdl(s.msg);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("stamp"), std::string::npos) << p.status().message();
}

}  // namespace
}  // namespace rover::msg
