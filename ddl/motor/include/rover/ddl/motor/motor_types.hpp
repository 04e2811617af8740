#pragma once
/// @file
/// The motor driver's view of ddl/motor_command and ddl/motor_status (the message types are
/// rover/msg/motor.hpp), the typed reasons for rejecting a command, the options of the
/// motor-group manager, and the conversion of hw/motor_telemetry into engineering units.

#include <array>
#include <cstdint>
#include <string>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/hwconfig/hardware_config.hpp"
#include "rover/hwconfig/hw_bus.hpp"
#include "rover/msg/motor.hpp"

namespace rover::ddl::motor {

// The message types of ddl/motor_command and ddl/motor_status (rover/msg/motor.hpp).
using msg::GroupMode;
using msg::GroupModeName;
using msg::GroupState;
using msg::GroupStateName;
using msg::MotorCommand;
using msg::MotorFault;
using msg::MotorFaultName;

/// Why a command was rejected (GROUP_REJECTED); kNone for accepted commands.
enum class CommandError : int {
  kNone = 0,
  kUnknownMode,      ///< mode is not one of GroupMode
  kEmptyMask,        ///< no motor selected (position / velocity)
  kUnknownMotor,     ///< a mask bit beyond motor 11
  kNonFiniteGoal,    ///< NaN or infinite goal
  kBadRate,          ///< NaN, infinite or negative max_rate
  kRateAboveLimit,   ///< max_rate (position) or |goal| (velocity) above the motor's max_rate
  kGoalOutOfRange,   ///< position goal beyond the joint limits (or the encoder range)
  kBadTimeout,       ///< NaN, infinite or negative timeout_s
  kTimeoutTooShort,  ///< timeout_s shorter than the planned synchronised move
  kNoTelemetry,      ///< no fresh telemetry to plan from
};

const char* CommandErrorName(CommandError e);

/// ddl/motor_status (rover/msg/motor.hpp) and the typed reason of a rejection.
struct MotorStatus : msg::MotorStatus {
  CommandError error = CommandError::kNone;  ///< typed reason of kRejected (not in the IDL)
};

/// Telemetry in engineering units (position straight from the int32 register: wheels are
/// absolute within +-2^31 counts, i.e. +-140,000 rad).
struct MotorReadings {
  std::int64_t stamp_ns = 0;
  std::uint32_t command_id = 0;
  std::array<double, hw::kNumMotors> position{};     ///< [rad]
  std::array<double, hw::kNumMotors> velocity{};     ///< [rad/s]
  std::array<double, hw::kNumMotors> current{};      ///< [A]
  std::array<double, hw::kNumMotors> temperature{};  ///< [deg C]
  std::array<std::uint16_t, hw::kNumMotors> flags{};
};
MotorReadings DecodeMotorTelemetry(const HardwareConfig& config, const hw::MotorTelemetry& t);

/// Tuning of the motor-group manager (MER's MOT). Times on the run clock.
struct MotorManagerOptions {
  double stall_window_s = 1.0;       ///< progress is judged over this window
  double stall_fraction = 0.25;      ///< stall if progress < fraction of the planned progress
  double stall_min_motion = 0.01;    ///< [rad] windows planning less motion are not judged
  /// [rad] ... and only when the motor is also this far behind where its plan puts it since the
  /// group started: a motor that ran ahead of its profile and settles back (a wheel slipping back
  /// at the end of an arc) makes little progress over a window without being stuck.
  double stall_max_lag = 0.2;
  /// The goals ask the controller to saturate at MotorSpec::current_limit; a motor held at that
  /// saturation (a wheel against an obstacle) is a stall, not an over-current. The driver's own
  /// over-current monitor is the backstop for a controller that fails to limit: it trips above
  /// current_limit * (1 + overcurrent_margin) (the margin covers current-sense gain and offset
  /// errors and the no-load current).
  double overcurrent_margin = 0.15;
  double overcurrent_time_s = 0.1;   ///< current above that level this long
  double overtemp_time_s = 0.2;      ///< temperature above MotorSpec::max_temperature this long
  double telemetry_timeout_s = 0.5;  ///< no telemetry this long while running: NO_TELEMETRY
  double apply_timeout_s = 0.5;      ///< goals not echoed by the controller this long: NO_TELEMETRY
  double timeout_factor = 1.5;       ///< default timeout = factor * planned duration + margin
  double timeout_margin_s = 2.0;
  double velocity_timeout_s = 10.0;  ///< default run time of velocity groups
  double settle_rate = 0.02;         ///< [rad/s] "at goal" also needs |rate| below this
  bool brake_when_done = true;       ///< brake the group's motors once it is done
  /// Positive finite times, fraction in (0, 1], factor >= 1, margin in [0, 2].
  Status Validate() const;
};

/// Keys `<prefix>.stall_window_s`, ... (defaults and ranges as above).
void DeclareMotorManagerParams(ParamSet& params, const std::string& prefix = "motor_manager");
Result<MotorManagerOptions> MotorManagerOptionsFromParams(
    const ParamSet& params, const std::string& prefix = "motor_manager");

}  // namespace rover::ddl::motor
