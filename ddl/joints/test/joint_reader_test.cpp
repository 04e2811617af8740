#include "rover/ddl/joints/joint_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>

#ifdef ROVER_HAVE_SIM_SENSORS
#include "rover/sim/sensors/motor_telemetry_model.hpp"
#include "rover/sim/sensors/pot_model.hpp"
#include "rover/sim/sensors/sim_sensor_options.hpp"
#endif

namespace rover::ddl::joints {
namespace {

// Exact encoding with the nominal calibration (the inverse of the driver's conversion).
hw::MotorTelemetry Telemetry(const HardwareConfig& c, std::int64_t stamp,
                             const std::array<double, hw::kNumMotors>& angle) {
  hw::MotorTelemetry t;
  t.stamp_ns = stamp;
  for (std::size_t i = 0; i < angle.size(); ++i) {
    t.motors[i].position = hw::WrapCounter(std::llround(angle[i] * c.motors[i].CountsPerRad()));
  }
  return t;
}

hw::SuspensionPots Pots(const HardwareConfig& c, std::int64_t stamp,
                        const std::array<double, hw::kNumPots>& angle) {
  hw::SuspensionPots p;
  p.stamp_ns = stamp;
  for (int i = 0; i < hw::kNumPots; ++i) {
    const double counts = c.pots.CountsFromAngle(i, angle[static_cast<std::size_t>(i)]);
    p.adc[static_cast<std::size_t>(i)] =
        static_cast<std::uint16_t>(std::lround(std::clamp(counts, 0.0, 4095.0)));
  }
  return p;
}

TEST(JointReader, ConvertsCountsToAnglesWithTheCalibration) {
  const HardwareConfig c;
  auto reader = JointReader::Create(c);
  ASSERT_TRUE(reader.ok());
  std::array<double, hw::kNumMotors> a{0.5, -1.0, 2.0, 3.0,  -4.0, 5.0,  // wheels
                                       0.3, -0.2, 0.1, -0.4,             // steering
                                       1.2, -0.3,                        // mast
                                       0.4, 1.1, -2.5, 0.9};             // arm
  reader->OnMotorTelemetry(Telemetry(c, 1'000'000, a));
  reader->OnSuspensionPots(Pots(c, 2'000'000, {0.12, -0.12, -0.3, 0.25}));
  const JointState s = reader->State(Time{3'000'000});
  EXPECT_EQ(s.health, msg::SensorHealth::kOk) << s.health_reason;
  EXPECT_EQ(s.stamp.ns, 2'000'000);
  for (std::size_t w = 0; w < 6; ++w) {
    EXPECT_NEAR(s.wheel_angle[w], a[w], 0.5 / c.motors[w].CountsPerRad());
  }
  for (std::size_t j = 0; j < 4; ++j) {
    EXPECT_NEAR(s.steer_angle[j], a[6 + j], 0.5 / c.motors[6 + j].CountsPerRad());
  }
  EXPECT_NEAR(s.mast_pan, 1.2, 0.5 / c.motors[10].CountsPerRad());
  EXPECT_NEAR(s.mast_tilt, -0.3, 0.5 / c.motors[11].CountsPerRad());
  for (std::size_t j = 0; j < 4; ++j) {
    EXPECT_NEAR(s.arm_angle[j], a[12 + j], 0.5 / c.motors[12 + j].CountsPerRad());
  }
  EXPECT_FALSE(s.arm_contact);  // no hw/arm_contact yet: open, and the health does not mind
  EXPECT_NEAR(s.rocker_angle[0], 0.12, 0.5 / 690.0 + 1e-12);
  EXPECT_NEAR(s.rocker_angle[1], -0.12, 0.5 / 690.0 + 1e-12);
  EXPECT_NEAR(s.bogie_angle[0], -0.3, 0.5 / 690.0 + 1e-12);
  EXPECT_NEAR(s.bogie_angle[1], 0.25, 0.5 / 690.0 + 1e-12);
}

TEST(JointReader, TheContactSwitchIsReportedWhileFresh) {
  const HardwareConfig c;
  auto reader = JointReader::Create(c);
  ASSERT_TRUE(reader.ok());
  reader->OnMotorTelemetry(Telemetry(c, 1'000'000, {}));
  reader->OnSuspensionPots(Pots(c, 1'000'000, {0.0, 0.0, 0.0, 0.0}));
  reader->OnArmContact({1'000'000, true});
  EXPECT_TRUE(reader->State(Time{1'100'000}).arm_contact);
  reader->OnArmContact({900'000, false});  // older: ignored
  EXPECT_TRUE(reader->State(Time{1'100'000}).arm_contact);
  reader->OnArmContact({1'020'000'000, false});
  EXPECT_FALSE(reader->State(Time{1'030'000'000}).arm_contact);
  reader->OnArmContact({1'040'000'000, true});
  // Stale (older than stale_after_s): reported open, never a stale "closed".
  EXPECT_TRUE(reader->State(Time{1'100'000'000}).arm_contact);
  EXPECT_FALSE(reader->State(Time{1'040'000'000 + 300'000'000}).arm_contact);
}

TEST(JointReader, WheelAnglesAreWrapFreeAndRatesComeFromCounts) {
  const HardwareConfig c;
  auto reader = JointReader::Create(c);
  ASSERT_TRUE(reader.ok());
  // Start just below the int32 register wrap (2^31 counts = 140,548 rad) and drive through it.
  const double start = 140'540.0, rate = 0.8;
  for (int k = 0; k <= 1500; ++k) {
    std::array<double, hw::kNumMotors> a{};
    a[hw::kDriveLM] = start + rate * k * 0.01;
    reader->OnMotorTelemetry(Telemetry(c, k * 10'000'000LL, a));
  }
  reader->OnSuspensionPots(Pots(c, 15'000'000'000LL, {0.0, 0.0, 0.0, 0.0}));
  const JointState s = reader->State(Time{15'000'000'000LL});
  EXPECT_NEAR(s.wheel_angle[1], start + rate * 15.0, 1e-4);  // past the wrap, no jump
  EXPECT_NEAR(s.wheel_rate[1], rate, 1e-3);
  EXPECT_NEAR(s.wheel_rate[0], 0.0, 1e-12);
}

TEST(JointReader, HealthStaleFailedDegraded) {
  const HardwareConfig c;
  auto reader = JointReader::Create(c);
  ASSERT_TRUE(reader.ok());
  EXPECT_EQ(reader->State(Time{0}).health, msg::SensorHealth::kStale);
  reader->OnMotorTelemetry(Telemetry(c, 0, {}));
  JointState s = reader->State(Time{0});
  EXPECT_EQ(s.health, msg::SensorHealth::kStale);
  EXPECT_NE(s.health_reason.find("pots"), std::string::npos);
  reader->OnSuspensionPots(Pots(c, 0, {0.0, 0.0, 0.0, 0.0}));
  EXPECT_EQ(reader->State(Time{100'000'000}).health, msg::SensorHealth::kOk);
  s = reader->State(Time{400'000'000});  // nothing new for 0.4 s
  EXPECT_EQ(s.health, msg::SensorHealth::kStale);
  EXPECT_NE(s.health_reason.find("old"), std::string::npos);

  // Rocker differential broken (left + right should be 0).
  reader->OnMotorTelemetry(Telemetry(c, 500'000'000, {}));
  reader->OnSuspensionPots(Pots(c, 500'000'000, {0.2, 0.1, 0.0, 0.0}));
  s = reader->State(Time{500'000'000});
  EXPECT_EQ(s.health, msg::SensorHealth::kDegraded);
  EXPECT_NE(s.health_reason.find("differential"), std::string::npos);

  // A bogie beyond its mechanical stop, not at a rail.
  reader->OnSuspensionPots(Pots(c, 600'000'000, {0.0, 0.0, 0.9, 0.0}));
  s = reader->State(Time{600'000'000});
  EXPECT_EQ(s.health, msg::SensorHealth::kDegraded);
  EXPECT_NE(s.health_reason.find("left_bogie"), std::string::npos);

  // A pot at the ADC rail (open wiper): failed, whatever else is wrong.
  hw::SuspensionPots rail = Pots(c, 700'000'000, {0.2, 0.1, 0.0, 0.0});
  rail.adc[hw::kRightBogie] = 4095;
  reader->OnSuspensionPots(rail);
  s = reader->State(Time{700'000'000});
  EXPECT_EQ(s.health, msg::SensorHealth::kFailed);
  EXPECT_NE(s.health_reason.find("right_bogie"), std::string::npos);

  // Steering beyond its limits.
  reader->OnSuspensionPots(Pots(c, 800'000'000, {0.0, 0.0, 0.0, 0.0}));
  std::array<double, hw::kNumMotors> a{};
  a[hw::kSteerRR] = 1.8;
  reader->OnMotorTelemetry(Telemetry(c, 800'000'000, a));
  s = reader->State(Time{800'000'000});
  EXPECT_EQ(s.health, msg::SensorHealth::kDegraded);
  EXPECT_NE(s.health_reason.find("steer_rr"), std::string::npos);
}

TEST(JointReader, OldTelemetryIsIgnored) {
  const HardwareConfig c;
  auto reader = JointReader::Create(c);
  ASSERT_TRUE(reader.ok());
  std::array<double, hw::kNumMotors> a{};
  a[hw::kMastPan] = 1.0;
  reader->OnMotorTelemetry(Telemetry(c, 20, a));
  a[hw::kMastPan] = -1.0;
  reader->OnMotorTelemetry(Telemetry(c, 10, a));  // reordered
  reader->OnSuspensionPots(Pots(c, 20, {}));
  EXPECT_NEAR(reader->State(Time{20}).mast_pan, 1.0, 1e-3);
}

TEST(JointReader, RejectsBadOptions) {
  JointReaderOptions o;
  o.rate_window_s = 0.0;
  EXPECT_FALSE(JointReader::Create(HardwareConfig(), o).ok());
}

#ifdef ROVER_HAVE_SIM_SENSORS
TEST(JointReader, RoundTripThroughTheSimulatedSensors) {
  const HardwareConfig c;
  auto reader = JointReader::Create(c);
  ASSERT_TRUE(reader.ok());
  const sim::sensors::SimSensorOptions ideal = sim::sensors::SimSensorOptions::Ideal();
  sim::sensors::MotorTelemetryModel motors(c, ideal.motors, 0.0, 1);
  sim::sensors::SuspensionPotModel pots(c.pots, ideal.pots, 0.0, 2);
  std::array<sim::sensors::MotorPhysical, hw::kNumMotors> m{};
  const std::array<double, hw::kNumPots> susp{0.21, -0.21, -0.4, 0.33};
  for (int k = 0; k <= 100; ++k) {
    const double t = k * 0.01;
    for (int i = 0; i < 6; ++i) m[static_cast<std::size_t>(i)].position_rad = 0.1 * (i + 1) * t;
    m[hw::kSteerLR].position_rad = -0.7;
    m[hw::kMastTilt].position_rad = 0.45;
    reader->OnMotorTelemetry(motors.Pack(m, 0, Time{std::llround(t * 1e9)}));
    if (k % 2 == 0) reader->OnSuspensionPots(pots.Sample(susp, Time{std::llround(t * 1e9)}));
  }
  const JointState s = reader->State(Time{1'000'000'000});
  EXPECT_EQ(s.health, msg::SensorHealth::kOk) << s.health_reason;
  for (std::size_t w = 0; w < 6; ++w) {
    EXPECT_NEAR(s.wheel_angle[w], 0.1 * static_cast<double>(w + 1),
                0.5 / c.motors[w].CountsPerRad());
    EXPECT_NEAR(s.wheel_rate[w], 0.1 * static_cast<double>(w + 1), 1e-3);
  }
  EXPECT_NEAR(s.steer_angle[1], -0.7, 0.5 / c.motors[hw::kSteerLR].CountsPerRad());
  EXPECT_NEAR(s.mast_tilt, 0.45, 0.5 / c.motors[hw::kMastTilt].CountsPerRad());
  EXPECT_NEAR(s.rocker_angle[0], 0.21, 0.5 / 690.0 + 1e-12);
  EXPECT_NEAR(s.rocker_angle[1], -0.21, 0.5 / 690.0 + 1e-12);
  EXPECT_NEAR(s.bogie_angle[0], -0.4, 0.5 / 690.0 + 1e-12);
  EXPECT_NEAR(s.bogie_angle[1], 0.33, 0.5 / 690.0 + 1e-12);

  // With the simulator's default (true-vs-nominal) pot errors and noise the nominal calibration
  // is off by a few counts: still within 0.02 rad, and still consistent with the differential.
  const sim::sensors::SimSensorOptions real;
  sim::sensors::SuspensionPotModel noisy(c.pots, real.pots, 1.0, 3);
  reader->OnSuspensionPots(noisy.Sample(susp, Time{1'010'000'000}));
  const JointState r = reader->State(Time{1'010'000'000});
  EXPECT_EQ(r.health, msg::SensorHealth::kOk) << r.health_reason;
  EXPECT_NEAR(r.rocker_angle[0], 0.21, 0.02);
  EXPECT_NEAR(r.bogie_angle[1], 0.33, 0.02);
}
#else
TEST(JointReader, RoundTripThroughTheSimulatedSensors) {
  GTEST_SKIP() << "sim/sensors is not part of this build (ROVER_MODULE_FILTER)";
}
#endif

}  // namespace
}  // namespace rover::ddl::joints
