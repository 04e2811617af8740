#pragma once
/// @file
/// ddl-joints: the encoder and potentiometer reader service. Binds the JointReader
/// (ddl_joints) to topics:
///   in:  hw/motor_telemetry (stream, 100 Hz), hw/suspension_pots (stream, 50 Hz)
///   out: ddl/joint_state (stream) every 1/rate_hz of the run clock (50 Hz), frame "rover",
///        stamped with the newest input's stamp (time of validity; the run-clock time before any
///        input), with the reader's health: STALE when an input stopped (older than
///        joint_reader.stale_after_s by stamp, or not arrived for that long), FAILED for a pot at
///        an ADC rail, DEGRADED for joints beyond their limits or inconsistent rockers.
/// The same health and its reason go into the heartbeat. Samples stamped more than
/// max_future_s ahead of the run clock are dropped; when the run clock goes back (simulator
/// reset) the reader starts afresh. See docs/services/ddl-joints.md.

#include <optional>

#include "rover/ddl/driver_support/driver_health.hpp"
#include "rover/ddl/joints/joint_reader.hpp"
#include "rover/runtime/service.hpp"

namespace rover::ddl::joints {

class JointsService final : public Service {
 public:
  JointsService() : Service("ddl-joints") {}

  void DeclareParameters(ParamSet& p) override;
  /// Cross-parameter checks that `--validate` (and so `roverctl up`) reports before start-up.
  Status ValidateParameters(const ParamSet& p) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& p) override;

 private:
  Time Now();
  Status OnTelemetry(const rover_hw_MotorTelemetry& t);
  Status OnPots(const rover_hw_SuspensionPots& p);
  Status OnContact(const rover_hw_ArmContact& c);
  void OnTimer();

  ServiceContext* ctx_ = nullptr;
  HardwareConfig hardware_;
  JointReaderOptions options_;
  std::optional<JointReader> reader_;
  std::optional<driver_support::InputMonitor> telemetry_;
  std::optional<driver_support::InputMonitor> pots_;
  std::optional<driver_support::InputMonitor> contact_;  // not part of the health (joint_reader.hpp)
  driver_support::ClockJumpDetector clock_jump_;
  dds::Writer<rover_ddl_JointState> writer_;
  std::optional<std::int64_t> last_stamp_ns_;  // header.stamp_ns of the last ddl/joint_state
};

}  // namespace rover::ddl::joints
