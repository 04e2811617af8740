#include "sun_idl.hpp"

#include <gtest/gtest.h>

namespace rover::ddl {
namespace {

TEST(SunIdl, FieldByField) {
  rover_hw_SunSensorRaw raw{};
  raw.header.stamp_ns = 9;
  raw.spot[0] = -32768;
  raw.spot[1] = 1234;
  raw.intensity = 4095;
  const hw::SunSensorRaw r = SunSensorRawFromIdl(raw);
  EXPECT_EQ(r.stamp_ns, 9);
  EXPECT_EQ(r.spot[0], -32768);
  EXPECT_EQ(r.spot[1], 1234);
  EXPECT_EQ(r.intensity, 4095);

  SunSensor s;
  s.sun_vector = Eigen::Vector3d(0.6, 0.0, 0.8);
  s.valid = true;
  s.intensity = 0.75;
  s.health = SensorHealth::kFailed;
  rover_ddl_SunSensor out{};
  SunSensorToIdl(s, &out);
  EXPECT_EQ(out.sun_vector.x, 0.6);
  EXPECT_EQ(out.sun_vector.z, 0.8);
  EXPECT_TRUE(out.valid);
  EXPECT_EQ(out.intensity, 0.75);
  EXPECT_EQ(out.health, rover_HEALTH_FAILED);
}

}  // namespace
}  // namespace rover::ddl
