#pragma once
/// @file
/// Plain C++ mirrors of the hw/ topics (idl/rover_hw.idl): the raw hardware bus between the
/// simulator (or real hardware) and the device-driver layer. Field meanings, units and bit
/// layouts are exactly the IDL's; a DDS binding copies field by field. The IDL Header is reduced
/// to `stamp_ns` (run-clock time of validity); frame_id and seq are the writer's business.
///
/// Also here: the helpers both sides need to treat the int32 encoder counters as free-running
/// (wrapping) counters. The conversions to and from the IDL structs are in core/msg
/// (rover/msg/hw_idl.hpp).

#include <array>
#include <cstdint>
#include <span>

namespace rover::hw {

/// Motor indices (rover_hw.idl): every array of 16 uses this order.
inline constexpr int kNumMotors = 16;
enum MotorIndex : int {
  kDriveLF = 0,
  kDriveLM = 1,
  kDriveLR = 2,
  kDriveRF = 3,
  kDriveRM = 4,
  kDriveRR = 5,
  kSteerLF = 6,
  kSteerLR = 7,
  kSteerRF = 8,
  kSteerRR = 9,
  kMastPan = 10,
  kMastTilt = 11,
  kArmAzimuth = 12,
  kArmShoulder = 13,
  kArmElbow = 14,
  kArmWrist = 15,
};
/// Every motor (bit i = motor i).
inline constexpr std::uint16_t kAllMotorsMask = 0xFFFF;
/// "drive_lf", ..., "arm_wrist"; "?" outside 0..15.
const char* MotorName(int motor);

/// Full scale of the 12-bit ADCs (pots, motor current and temperature, sun intensity).
inline constexpr int kAdcMax = 4095;

enum class MotorMode : std::uint8_t {
  kIdle = 0,      ///< leave this motor untouched
  kPosition = 1,  ///< servo to `position` at up to `velocity`
  kVelocity = 2,  ///< servo the rate to `velocity`
  kBrake = 3,     ///< hold the current position
};
const char* MotorModeName(MotorMode m);

struct MotorGoal {
  MotorMode mode = MotorMode::kIdle;
  std::int32_t position = 0;           ///< [counts] position goal (kPosition)
  std::int32_t velocity = 0;           ///< [counts/s] rate goal, or rate limit (> 0) for kPosition
  std::uint16_t current_limit_ma = 0;  ///< [mA] over-current trip level; 0 = controller default
};

/// hw/motor_goals (command, DDL -> controller).
struct MotorGoals {
  std::int64_t stamp_ns = 0;
  std::uint32_t command_id = 0;  ///< echoed in MotorTelemetry once applied
  std::array<MotorGoal, kNumMotors> goals{};
};

/// MotorReading::flags bits (latched by the controller).
inline constexpr std::uint16_t kMotorFlagEnabled = 1;
inline constexpr std::uint16_t kMotorFlagAtGoal = 2;
inline constexpr std::uint16_t kMotorFlagStall = 4;
inline constexpr std::uint16_t kMotorFlagOverCurrent = 8;
inline constexpr std::uint16_t kMotorFlagOverTemp = 16;

struct MotorReading {
  std::int32_t position = 0;          ///< [counts] free-running counter (wraps at int32)
  std::int32_t velocity = 0;          ///< [counts/s]
  std::uint16_t current_adc = 0;      ///< [ADC counts, 12 bit]
  std::uint16_t temperature_adc = 0;  ///< [ADC counts, 12 bit]
  std::uint16_t flags = 0;            ///< kMotorFlag* bits
};

/// hw/motor_telemetry (stream, 100 Hz, controller -> DDL).
struct MotorTelemetry {
  std::int64_t stamp_ns = 0;
  std::uint32_t command_id = 0;  ///< last MotorGoals::command_id applied
  std::array<MotorReading, kNumMotors> motors{};
};

/// Potentiometer order in SuspensionPots::adc.
enum PotIndex : int { kLeftRocker = 0, kRightRocker = 1, kLeftBogie = 2, kRightBogie = 3 };
inline constexpr int kNumPots = 4;
/// "left_rocker", "right_rocker", "left_bogie", "right_bogie"; "?" otherwise.
const char* PotName(int pot);

/// hw/suspension_pots (stream, 50 Hz).
struct SuspensionPots {
  std::int64_t stamp_ns = 0;
  std::array<std::uint16_t, kNumPots> adc{};  ///< [ADC counts, 12 bit]
};

/// ImuRaw::status bits.
inline constexpr std::uint16_t kImuGyroSaturated = 1;
inline constexpr std::uint16_t kImuAccelSaturated = 2;
inline constexpr std::uint16_t kImuSelfTestFail = 4;
/// ImuRaw::temperature scale [deg C per LSB].
inline constexpr double kImuTemperatureLsb = 0.01;

/// hw/arm_contact (stream, 50 Hz): the switch behind the arm instrument's face.
struct ArmContact {
  std::int64_t stamp_ns = 0;
  bool closed = false;
};

/// hw/imu (stream, 100 Hz). Raw sample in the IMU case frame.
struct ImuRaw {
  std::int64_t stamp_ns = 0;
  std::array<std::int32_t, 3> gyro{};   ///< [LSB] angular rate
  std::array<std::int32_t, 3> accel{};  ///< [LSB] specific force
  std::int16_t temperature = 0;         ///< [0.01 deg C]
  std::uint16_t status = 0;             ///< kImu* bits
};

/// hw/sun_sensor (stream, 2 Hz).
struct SunSensorRaw {
  std::int64_t stamp_ns = 0;
  std::array<std::int16_t, 2> spot{};  ///< [detector counts] centroid column, row; 0,0 = centre
  std::uint16_t intensity = 0;         ///< [ADC counts] integrated spot brightness (0 = no sun)
};

/// hw/camera_request (command, DDL camera driver -> camera head).
struct CameraRequest {
  std::int64_t stamp_ns = 0;
  std::uint32_t request_id = 0;   ///< the driver's own id, echoed in the frame
  int camera = 0;                 ///< rover_common.idl CameraId; any int (checked by the receiver)
  std::uint32_t exposure_us = 0;  ///< [us] 0 = auto exposure
  /// [px] 0 = read the full sensor out; otherwise the sensor width divided by a whole binning
  /// factor b (b x b binning: the frame is W/b x H/b). Checked by the camera head.
  int readout_width = 0;
};

// rover_description.hpp includes this header into the simulator's C++17 Simbody translation
// unit, which has no std::span; nothing there uses the camera frame.
#if __cplusplus >= 202002L
/// hw/camera_frame (camera head -> DDL): one full-resolution stereo pair, 8-bit mono,
/// row-major, taken at stamp_ns. The images VIEW the sample's (or the sender's) buffers.
struct CameraFrame {
  std::int64_t stamp_ns = 0;     ///< capture time
  std::uint32_t request_id = 0;  ///< echo of CameraRequest::request_id
  int camera = 0;
  std::uint32_t exposure_us = 0;       ///< [us] exposure actually used
  int width = 0;                       ///< [px]
  int height = 0;                      ///< [px]
  std::span<const std::uint8_t> left;  ///< width * height bytes (checked by the receiver)
  std::span<const std::uint8_t> right;
};

/// hw/mi_frame (microscopic imager -> DDL): one 8-bit mono image, row-major, taken at
/// stamp_ns. The image VIEWS the sample's (or the sender's) buffer.
struct MiFrame {
  std::int64_t stamp_ns = 0;           ///< capture time
  std::uint32_t request_id = 0;        ///< echo of MiRequest::request_id
  std::uint32_t exposure_us = 0;       ///< [us] exposure actually used
  int width = 0;                       ///< [px]
  int height = 0;                      ///< [px]
  std::span<const std::uint8_t> image; ///< width * height bytes (checked by the receiver)
};
#endif

/// hw/mi_request (command, DDL camera driver -> microscopic imager on the arm's face).
struct MiRequest {
  std::int64_t stamp_ns = 0;
  std::uint32_t request_id = 0;   ///< the driver's own id, echoed in the frame
  std::uint32_t exposure_us = 0;  ///< [us] 0 = auto exposure
};

/// The int32 counter value of an unbounded count: two's-complement wrap (what a 32-bit
/// hardware counter shows after `count` increments from 0).
std::int32_t WrapCounter(std::int64_t count);

/// Signed increment from `older` to `newer` of a wrapping int32 counter, assuming the true
/// increment lies in [-2^31, 2^31). Accumulating these deltas gives a wrap-free count.
std::int64_t CounterDelta(std::int32_t newer, std::int32_t older);

}  // namespace rover::hw
