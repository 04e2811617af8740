#pragma once
/// @file
/// ddl-sun-sensor: the sun-sensor driver service. Binds the SunSensorDriver (ddl_sun_sensor):
///   in:  hw/sun_sensor (stream, 2 Hz; spot centroid and intensity in counts)
///   out: ddl/sun_sensor (state), one sample per accepted input, frame "rover", stamped with the
///        raw sample's stamp: unit sun vector in the rover frame (zero when not valid), valid,
///        relative intensity, and the sample's health (FAILED: a bright spot outside the field of
///        view; no sun or a dim spot is valid = false with health OK).
/// Health (heartbeat), judged every 1/watchdog_rate_hz of the run clock: the worst sample health
/// since the last check with its reason, STALE when hw/sun_sensor has not arrived for
/// stale_after_s. Samples stamped more than max_future_s ahead of the run clock are dropped.
/// See docs/services/ddl-sun-sensor.md.

#include <optional>
#include <string>

#include "rover/ddl/driver_support/driver_health.hpp"
#include "rover/ddl/sun_sensor/sun_sensor_driver.hpp"
#include "rover/runtime/service.hpp"

namespace rover::ddl::sun_sensor {

class SunService final : public Service {
 public:
  SunService() : Service("ddl-sun-sensor") {}

  void DeclareParameters(ParamSet& p) override;
  /// Cross-parameter checks that `--validate` (and so `roverctl up`) reports before start-up.
  Status ValidateParameters(const ParamSet& p) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& p) override;

 private:
  Time Now();
  Status OnSample(const rover_hw_SunSensorRaw& raw);
  void OnWatchdog();

  ServiceContext* ctx_ = nullptr;
  std::optional<SunSensorDriver> driver_;
  std::optional<driver_support::InputMonitor> input_;
  driver_support::ClockJumpDetector clock_jump_;
  driver_support::HealthSummary since_check_;
  std::uint64_t unhealthy_samples_ = 0;
  std::string last_reason_;
  dds::Writer<rover_ddl_SunSensor> writer_;
};

}  // namespace rover::ddl::sun_sensor
