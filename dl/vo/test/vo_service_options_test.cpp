#include "rover/dl/vo/vo_service_options.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rover::dl::vo {
namespace {

TEST(VoServiceOptions, KeysDefaultsAndTheStepRule) {
  ParamSet ps("dl-vo");
  DeclareParams<VoServiceOptions>(ps, "");
  EXPECT_EQ(ps.GetString("camera"), "front_hazcam");
  EXPECT_EQ(ps.GetInt("width"), 512);
  EXPECT_EQ(ps.GetInt("request_id_prefix"), 2);
  EXPECT_EQ(ps.GetDouble("retry_delay_s"), 1.0);
  EXPECT_EQ(ps.GetDouble("step_distance"), CadenceOptions().step_distance);
  EXPECT_EQ(ps.GetInt("rectification_cache_size"), 2);
  ASSERT_TRUE(
      ps.LoadYamlString("camera: navcam\nretry_delay_s: 2\nexposure_us: 300\n", "v.yaml").ok());
  auto o = ReadParams<VoServiceOptions>(ps, "");
  ASSERT_TRUE(o.ok()) << o.status().ToString();
  EXPECT_EQ(o->camera, msg::CameraId::kNavcam);
  EXPECT_EQ(o->Client().retry_delay_s, 2.0);
  EXPECT_EQ(o->Client().request_id_prefix, 2);
  EXPECT_EQ(o->Client().exposure_us, 300u);

  ParamSet bad("dl-vo");
  DeclareParams<VoServiceOptions>(bad, "");
  ASSERT_TRUE(
      bad.LoadYamlString("step_distance: 0.8\nvo:\n  max_translation: 0.5\n", "v.yaml").ok());
  const auto r = ReadParams<VoServiceOptions>(bad, "");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("step_distance 0.8 m must be below vo.max_translation 0.5"),
            std::string::npos)
      << r.status().message();
}

}  // namespace
}  // namespace rover::dl::vo
