#include "rover/dl/stereo/disparity_io.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

namespace rover::dl::stereo {
namespace {

class DisparityIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("dl_stereo_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  static cv::Mat Sample() {
    cv::Mat m(3, 4, CV_32FC1);
    for (int v = 0; v < 3; ++v) {
      for (int u = 0; u < 4; ++u) m.at<float>(v, u) = 0.25f * static_cast<float>(u + 10 * v);
    }
    m.at<float>(1, 2) = std::nanf("");
    return m;
  }

  std::filesystem::path dir_;
};

void ExpectSameWithNan(const cv::Mat& a, const cv::Mat& b) {
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(b.type(), CV_32FC1);
  for (int v = 0; v < a.rows; ++v) {
    for (int u = 0; u < a.cols; ++u) {
      const float x = a.at<float>(v, u), y = b.at<float>(v, u);
      if (std::isnan(x)) {
        EXPECT_TRUE(std::isnan(y)) << v << "," << u;
      } else {
        EXPECT_EQ(x, y) << v << "," << u;
      }
    }
  }
}

TEST_F(DisparityIoTest, PfmRoundTripKeepsRowsAndInvalid) {
  const cv::Mat m = Sample();
  ASSERT_TRUE(WritePfm(Path("d.pfm"), m).ok());
  auto back = ReadPfm(Path("d.pfm"));
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  ExpectSameWithNan(m, *back);
  // Header as Middlebury expects.
  std::ifstream f(Path("d.pfm"), std::ios::binary);
  std::string magic;
  int w = 0, h = 0;
  f >> magic >> w >> h;
  EXPECT_EQ(magic, "Pf");
  EXPECT_EQ(w, 4);
  EXPECT_EQ(h, 3);
}

TEST_F(DisparityIoTest, TiffRoundTrip) {
  const cv::Mat m = Sample();
  ASSERT_TRUE(WriteFloatImage(Path("d.tif"), m).ok());
  const cv::Mat back = cv::imread(Path("d.tif"), cv::IMREAD_UNCHANGED);
  ExpectSameWithNan(m, back);
  EXPECT_FALSE(WriteFloatImage(Path("d.png"), m).ok());
  EXPECT_FALSE(WriteFloatImage(Path("d.tif"), cv::Mat(2, 2, CV_8UC1)).ok());
  EXPECT_FALSE(WritePfm(Path("x.pfm"), cv::Mat()).ok());
  EXPECT_FALSE(WritePfm(Path("no_such_dir/x.pfm"), m).ok());
}

TEST_F(DisparityIoTest, ReadPfmErrors) {
  EXPECT_EQ(ReadPfm(Path("missing.pfm")).status().code(), StatusCode::kNotFound);
  {
    std::ofstream f(Path("bad.pfm"));
    f << "P6\n2 2\n255\n";
  }
  EXPECT_EQ(ReadPfm(Path("bad.pfm")).status().code(), StatusCode::kInvalidArgument);
  {
    std::ofstream f(Path("short.pfm"), std::ios::binary);
    f << "Pf\n100 100\n-1\n" << std::string(16, '\0');
  }
  auto s = ReadPfm(Path("short.pfm"));
  EXPECT_NE(s.status().message().find("truncated"), std::string::npos) << s.status().message();
}

TEST_F(DisparityIoTest, LoadGrayImageConvertsAndReportsErrors) {
  cv::Mat colour(5, 6, CV_8UC3, cv::Scalar(10, 200, 30));
  ASSERT_TRUE(cv::imwrite(Path("c.png"), colour));
  auto g = LoadGrayImage(Path("c.png"));
  ASSERT_TRUE(g.ok()) << g.status().ToString();
  EXPECT_EQ(g->type(), CV_8UC1);
  cv::Mat sixteen(5, 6, CV_16UC1, cv::Scalar(4000));
  ASSERT_TRUE(cv::imwrite(Path("s.png"), sixteen));
  auto s = LoadGrayImage(Path("s.png"));
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->type(), CV_16UC1);
  EXPECT_EQ(LoadGrayImage(Path("none.png")).status().code(), StatusCode::kNotFound);
  {
    std::ofstream f(Path("text.png"));
    f << "not an image";
  }
  auto t = LoadGrayImage(Path("text.png"));
  EXPECT_EQ(t.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(t.status().message().find("text.png"), std::string::npos);
  EXPECT_FALSE(LoadGrayImage(dir_.string()).ok());
}

TEST_F(DisparityIoTest, ColorizeMarksInvalidBlack) {
  const cv::Mat m = Sample();
  auto c = ColorizeDisparity(m, 0, 6);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->type(), CV_8UC3);
  EXPECT_EQ(c->at<cv::Vec3b>(1, 2), cv::Vec3b(0, 0, 0));
  EXPECT_NE(c->at<cv::Vec3b>(2, 3), c->at<cv::Vec3b>(0, 0));
  auto automatic = ColorizeDisparity(m);
  ASSERT_TRUE(automatic.ok());
  EXPECT_FALSE(ColorizeDisparity(cv::Mat(2, 2, CV_8UC1)).ok());
  EXPECT_FALSE(ColorizeDisparity(cv::Mat()).ok());
}

}  // namespace
}  // namespace rover::dl::stereo
