#include "camera_idl.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "rover/geometry/transforms.hpp"
#include "rover/runtime/dds.hpp"

namespace rover::ddl {
namespace {

TEST(CameraIdl, RequestsFramesAndJointStates) {
  rover_ddl_StereoRequest r{};
  r.request_id = 12;
  r.camera = rover_CAMERA_REAR_HAZCAM;
  r.exposure_us = 5000;
  r.width = 256;
  StereoRequest q = StereoRequestFromIdl(r);
  EXPECT_EQ(q.request_id, 12u);
  EXPECT_EQ(q.camera, 2);
  EXPECT_EQ(q.exposure_us, 5000u);
  EXPECT_EQ(q.width, 256);
  const std::int32_t nine = 9;  // a camera no enum value names, as a corrupt sample could carry
  std::memcpy(&r.camera, &nine, sizeof nine);
  EXPECT_EQ(StereoRequestFromIdl(r).camera, 9);

  rover_hw_CameraRequest hw{};
  HwCameraRequestToIdl({77, 1, 300}, &hw);
  EXPECT_EQ(hw.request_id, 77u);
  EXPECT_EQ(hw.camera, rover_CAMERA_FRONT_HAZCAM);
  EXPECT_EQ(hw.exposure_us, 300u);

  std::vector<std::uint8_t> left(6, 1), right(5, 2);
  rover_hw_CameraFrame f{};
  f.header.stamp_ns = 99;
  f.request_id = 77;
  f.camera = rover_CAMERA_FRONT_HAZCAM;
  f.exposure_us = 250;
  f.width = 3;
  f.height = 2;
  dds::BorrowSequence(f.left, left);
  dds::BorrowSequence(f.right, right);
  const CameraFrameView v = CameraFrameViewFromIdl(f);
  EXPECT_EQ(v.stamp_ns, 99);
  EXPECT_EQ(v.request_id, 77u);
  EXPECT_EQ(v.camera, 1);
  EXPECT_EQ(v.exposure_us, 250u);
  EXPECT_EQ(v.width, 3);
  EXPECT_EQ(v.height, 2);
  EXPECT_EQ(v.left.size(), 6u);
  EXPECT_EQ(v.right.size(), 5u);  // sizes are checked by the driver, not here
  EXPECT_EQ(v.left.data(), left.data());

  rover_ddl_JointState js{};
  js.header.stamp_ns = 5;
  js.mast_pan = 0.25;
  js.mast_tilt = -0.5;
  js.health = rover_HEALTH_STALE;
  const MastSample m = MastSampleFromIdl(js);
  EXPECT_EQ(m.stamp_ns, 5);
  EXPECT_EQ(m.pan, 0.25);
  EXPECT_EQ(m.tilt, -0.5);
  EXPECT_EQ(RawHealth(js.health), rover_HEALTH_STALE);
}

TEST(CameraIdl, ModelAndFrameFields) {
  geometry::Cahvor c;
  c.c = Eigen::Vector3d(0.4, 0.1, 1.5);
  const Eigen::Matrix3d r = geometry::RotationFromRpy(0.1, 0.3, -0.7);
  c.a = r.col(0);
  c.h = 300.0 * (-r.col(1)) + 127.5 * c.a;
  c.v = 300.0 * (-r.col(2)) + 95.5 * c.a;
  c.o = c.a;
  c.r = Eigen::Vector3d(0.0, -0.02, 0.001);
  const auto model = *geometry::CameraModel::Create(c, 256, 192);
  auto fields = ToCameraModelFields(model);
  ASSERT_TRUE(fields.ok());
  rover_ddl_CameraModel m{};
  CameraModelToIdl(*fields, &m);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(m.c[i], c.c[i]);
    EXPECT_NEAR(m.a[i], c.a[i], 1e-15);
    EXPECT_NEAR(m.h[i], c.h[i], 1e-12);
    EXPECT_NEAR(m.v[i], c.v[i], 1e-12);
    EXPECT_NEAR(m.r[i], c.r[i], 1e-15);
  }
  EXPECT_EQ(m.fx, fields->fx);
  EXPECT_EQ(m.k2, fields->k2);
  EXPECT_EQ(m.width, 256);
  EXPECT_EQ(m.height, 192);
  // The pose is the pinhole camera frame (z = A) at C, quaternion w first with w >= 0.
  EXPECT_NEAR(m.pose.position.x, 0.4, 1e-12);
  EXPECT_NEAR(m.pose.position.z, 1.5, 1e-12);
  const Eigen::Quaterniond q(m.pose.orientation.w, m.pose.orientation.x, m.pose.orientation.y,
                             m.pose.orientation.z);
  EXPECT_GE(q.w(), 0.0);
  EXPECT_NEAR(q.norm(), 1.0, 1e-12);
  EXPECT_LT((q.toRotationMatrix().col(2) - c.a).norm(), 1e-9);

  StereoFrameData d{
      1000,
      4,
      0,
      800,
      DownsampledStereo{GrayImage{2, 1, {7, 8}}, GrayImage{2, 1, {9, 10}}, model, model, 1.0, 1.0},
      *fields,
      *fields,
      0.1,
      0.2,
      SensorHealth::kDegraded,
      "why",
      ""};
  rover_ddl_StereoFrame out{};
  StereoFrameToIdl(d, &out);
  EXPECT_EQ(out.request_id, 4u);
  EXPECT_EQ(out.camera, rover_CAMERA_NAVCAM);
  EXPECT_EQ(out.exposure_us, 800u);
  EXPECT_EQ(out.width, 2);
  EXPECT_EQ(out.height, 1);
  ASSERT_EQ(out.left._length, 2u);
  EXPECT_EQ(out.left._buffer, d.pair.left.pixels.data());  // borrowed, not copied
  EXPECT_EQ(out.right._buffer[1], 10);
  EXPECT_FALSE(out.left._release);
  EXPECT_EQ(out.health, rover_HEALTH_DEGRADED);
  EXPECT_EQ(out.left_model.width, 256);
}

}  // namespace
}  // namespace rover::ddl
