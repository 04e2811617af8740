#pragma once
/// @file
/// ddl-imu: the IMU driver service. Binds the ImuDriver (ddl_imu) to topics:
///   in:  hw/imu (stream, 100 Hz; raw LSB in the IMU case frame)
///   out: ddl/imu (stream), one sample per accepted input, frame "rover", stamped with the raw
///        sample's stamp: rad/s and m/s^2 in the rover frame, deg C, and the sample's health
///        (FAILED: self-test bit or an axis beyond full scale; DEGRADED: a saturation bit).
/// Health (heartbeat), judged every 1/watchdog_rate_hz of the run clock: the worst sample health
/// since the last check with its reason, STALE when hw/imu has not arrived for stale_after_s.
/// Samples stamped more than max_future_s ahead of the run clock are dropped (logged).
/// See docs/services/ddl-imu.md.

#include <optional>
#include <string>

#include "rover/ddl/driver_support/driver_health.hpp"
#include "rover/ddl/imu/imu_driver.hpp"
#include "rover/runtime/service.hpp"

namespace rover::ddl::imu {

class ImuService final : public Service {
 public:
  ImuService() : Service("ddl-imu") {}

  void DeclareParameters(ParamSet& p) override;
  /// Cross-parameter checks that `--validate` (and so `roverctl up`) reports before start-up.
  Status ValidateParameters(const ParamSet& p) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& p) override;

 private:
  Time Now();
  void OnSample(const rover_hw_ImuRaw& raw);
  void OnWatchdog();

  ServiceContext* ctx_ = nullptr;
  std::optional<ImuDriver> driver_;
  std::optional<driver_support::InputMonitor> input_;
  driver_support::ClockJumpDetector clock_jump_;
  driver_support::HealthSummary since_check_;  // worst sample health since the last watchdog run
  std::uint64_t unhealthy_samples_ = 0;
  std::string last_reason_;  // of the previous sample (log on change)
  dds::Writer<rover_ddl_Imu> writer_;
};

}  // namespace rover::ddl::imu
