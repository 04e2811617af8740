#include "rover/dl/stereo/raw_stereo_pair.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rover/idl/types.hpp"

namespace rover::dl::stereo {
namespace {

// A ddl/stereo_frame with w x h images whose pixel (u, v) of the left image is u + v and of the
// right image 2u; models are only sized (their content is not checked here).
struct Frame {
  Frame(int w, int h) : left(static_cast<std::size_t>(w * h)), right(left.size()) {
    msg.header.stamp_ns = 5'000'000'000;
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
    Attach();
  }
  void Attach() {
    msg.left._buffer = left.data();
    msg.left._length = static_cast<std::uint32_t>(left.size());
    msg.right._buffer = right.data();
    msg.right._length = static_cast<std::uint32_t>(right.size());
  }
  rover_ddl_StereoFrame msg{};
  std::vector<std::uint8_t> left, right;
};

TEST(RawStereoPair, ViewsTheMessageImagesRowMajor) {
  Frame f(16, 8);
  auto p = RawStereoPairFromMessage(f.msg);
  ASSERT_TRUE(p.ok()) << p.status().ToString();
  EXPECT_EQ(p->stamp.ns, 5'000'000'000);
  EXPECT_EQ(p->left.cols, 16);
  EXPECT_EQ(p->left.rows, 8);
  EXPECT_EQ(p->left.type(), CV_8UC1);
  EXPECT_EQ(p->left.at<std::uint8_t>(3, 5), 8);
  EXPECT_EQ(p->right.at<std::uint8_t>(7, 6), 12);
  EXPECT_EQ(p->left.data, f.left.data());  // a view, no copy
  EXPECT_EQ(p->left_model.fx, 1.0);
  EXPECT_EQ(p->right_model.width, 16);
}

TEST(RawStereoPair, WrongByteCountSizeOrStampIsAnError) {
  Frame f(16, 8);
  f.right.pop_back();
  f.Attach();
  auto p = RawStereoPairFromMessage(f.msg);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("right image has 127 bytes; expected 16x8 = 128"),
            std::string::npos)
      << p.status().message();

  Frame g(16, 8);
  g.msg.right_model.width = 32;
  p = RawStereoPairFromMessage(g.msg);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("right camera model is for 32x8"), std::string::npos)
      << p.status().message();

  Frame e(16, 8);
  e.msg.width = 0;
  e.msg.left._length = e.msg.right._length = 0;
  p = RawStereoPairFromMessage(e.msg);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("empty"), std::string::npos) << p.status().message();

  Frame s(16, 8);
  s.msg.header.stamp_ns = 0;
  p = RawStereoPairFromMessage(s.msg);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message().find("stamp"), std::string::npos) << p.status().message();
}

TEST(RawStereoPair, CheckRejectsImagesOfTheWrongType) {
  RawStereoPair p;
  p.stamp = Time{1};
  p.width = 4;
  p.height = 4;
  p.left = cv::Mat(4, 4, CV_16UC1, cv::Scalar(0));
  p.right = cv::Mat(4, 4, CV_8UC1, cv::Scalar(0));
  p.left_model.width = p.right_model.width = 4;
  p.left_model.height = p.right_model.height = 4;
  const Status s = CheckRawStereoPair(p);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("left image is 4x4 CV_16UC1"), std::string::npos) << s.message();
  p.left = cv::Mat(4, 4, CV_8UC1, cv::Scalar(0));
  EXPECT_TRUE(CheckRawStereoPair(p).ok());
}

}  // namespace
}  // namespace rover::dl::stereo
