#include "rover/msg/range_idl.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

TEST(RangeIdl, RequestRoundTripKeepsAnUnknownCamera) {
  RangeRequest r;
  r.stamp = Time{3};
  r.request_id = 12;
  r.camera = CameraId::kRearHazcam;
  r.width = 256;
  rover_dl_RangeRequest w{};
  RangeRequestToIdl(r, &w);
  EXPECT_EQ(w.header.stamp_ns, 3);
  EXPECT_EQ(w.camera, rover_CAMERA_REAR_HAZCAM);
  EXPECT_EQ(w.width, 256);
  const RangeRequest back = RangeRequestFromIdl(w);
  EXPECT_EQ(back.stamp, r.stamp);
  EXPECT_EQ(back.request_id, 12u);
  EXPECT_EQ(back.camera, CameraId::kRearHazcam);
  EXPECT_EQ(back.width, 256);
  idl::SetRawEnum(&w.camera, 7);
  EXPECT_FALSE(IsKnownCamera(RangeRequestFromIdl(w).camera));
}

TEST(RangeIdl, ImageRoundTripBorrowsOutAndCopiesIn) {
  RangeImage img;
  img.stamp = Time{500};
  img.request_id = 4;
  img.camera = CameraId::kFrontHazcam;
  img.width = 3;
  img.height = 2;
  img.rover_pose.translation() = Eigen::Vector3d(1, 2, 0);
  img.rover_pose.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (int i = 0; i < 6; ++i) {
    const bool ok = i != 4;
    img.valid.push_back(ok ? 1 : 0);
    img.disparity.push_back(ok ? 10.0F + static_cast<float>(i) : -1.0F);
    for (int k = 0; k < 3; ++k) {
      img.xyz.push_back(ok ? static_cast<float>(i + k) : std::numeric_limits<float>::quiet_NaN());
    }
  }
  rover_dl_RangeImage w{};
  ASSERT_TRUE(RangeImageToIdl(img, &w).ok());
  EXPECT_EQ(w.header.stamp_ns, 500);
  EXPECT_EQ(w.xyz._buffer, img.xyz.data());  // borrowed, not copied
  EXPECT_EQ(w.valid._length, 6u);
  EXPECT_FALSE(w.disparity._release);
  auto back = RangeImageFromIdl(w);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->stamp, img.stamp);
  EXPECT_EQ(back->request_id, 4u);
  EXPECT_EQ(back->camera, CameraId::kFrontHazcam);
  EXPECT_EQ(back->width, 3);
  EXPECT_EQ(back->height, 2);
  EXPECT_LT((back->rover_pose.matrix() - img.rover_pose.matrix()).norm(), 1e-12);
  EXPECT_EQ(back->valid, img.valid);
  EXPECT_EQ(back->disparity, img.disparity);
  ASSERT_EQ(back->xyz.size(), 18u);
  EXPECT_TRUE(std::isnan(back->xyz[12]));
  EXPECT_EQ(back->xyz[17], 7.0F);
  EXPECT_NE(back->xyz.data(), img.xyz.data());

  // Sizes that disagree are refused both ways.
  w.height = 3;
  auto bad = RangeImageFromIdl(w);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("expected 27 for 3x3"), std::string::npos)
      << bad.status().message();
  img.valid.pop_back();
  EXPECT_FALSE(RangeImageToIdl(img, &w).ok());
}

}  // namespace
}  // namespace rover::msg
