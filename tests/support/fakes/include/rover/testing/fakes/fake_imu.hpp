#pragma once
/// @file
/// Fake ddl-imu (header only; target rover_test_fakes): publishes calibrated ddl/imu samples of
/// a rover that turns about its own z axis at `yaw_rate` while the specific force it feels is
/// `specific_force` (rover frame at body yaw 0) turned with it. No noise, no bias: what an ideal
/// driver would report. Used by the dl-pose service test.
///
///   testing::FakeImu imu;
///   ASSERT_TRUE(imu.Create(harness.peer()).ok());
///   imu.yaw_rate = 0.2;
///   ASSERT_TRUE(imu.Publish(t, 0.01).ok());  // one 10 ms step ending at t

#include <Eigen/Geometry>

#include "rover/base/clock.hpp"
#include "rover/base/status.hpp"
#include "rover/runtime/dds.hpp"

namespace rover::testing {

class FakeImu {
 public:
  Status Create(const dds::Participant& p) {
    auto w = dds::Writer<rover_ddl_Imu>::Create(p, "ddl/imu");
    if (!w.ok()) return w.status();
    writer_ = std::move(*w);
    return Status::Ok();
  }
  bool Matched(int readers = 1) const { return writer_.MatchedReaders() >= readers; }

  /// Advances the body yaw by one step of `dt` [s] at `yaw_rate` (the rate holds over the step)
  /// and returns the sample stamped `stamp` at the end of it.
  rover_ddl_Imu Step(Time stamp, double dt) {
    body_yaw_ += yaw_rate * dt;
    // The rover turned by body_yaw_ about its z axis: gravity turns the other way in its frame.
    const Eigen::Vector3d f =
        Eigen::AngleAxisd(-body_yaw_, Eigen::Vector3d::UnitZ()).toRotationMatrix() * specific_force;
    rover_ddl_Imu imu{};
    imu.header.stamp_ns = stamp.ns;
    imu.angular_velocity = {0.0, 0.0, yaw_rate};
    imu.linear_acceleration = {f.x(), f.y(), f.z()};
    imu.health = rover_HEALTH_OK;
    return imu;
  }
  /// Step, then publishes the sample.
  Status Publish(Time stamp, double dt) { return writer_.Write(Step(stamp, dt)); }

  /// [rad] rotation about the rover z axis since the start.
  double body_yaw() const { return body_yaw_; }

  double yaw_rate = 0.0;                            ///< [rad/s] about the rover z axis
  Eigen::Vector3d specific_force{0.0, 0.0, 3.711};  ///< [m/s^2] at body yaw 0 (Mars, at rest)

 private:
  dds::Writer<rover_ddl_Imu> writer_;
  double body_yaw_ = 0.0;
};

}  // namespace rover::testing
