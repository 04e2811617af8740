#pragma once
/// @file
/// Validation of a structure read from a keyed file (hardware calibration, terrain parameters):
/// checks run in order and the first failure is kept with the key it concerns, so the caller
/// can point at the file line of that key. Messages read "<key>: <what is wrong>":
///
///   "motors.wheel_drive.gear_ratio: -3 must be > 0"
///   "imu.gyro.scale: 2 is out of range [0.5, 1.5]"
///   "resolution: nan is not a finite number"
///
/// Each check returns whether it passed, so dependent checks can be chained with &&. Numbers
/// use FormatNumber.

#include <string>

#include "rover/base/status.hpp"

namespace rover {

class KeyChecker {
 public:
  /// Records InvalidArgument("<key>: <message>") unless a failure is already recorded.
  /// Always returns false.
  bool Fail(const std::string& key, const std::string& message);
  bool Finite(const std::string& key, double v);
  /// Finite and > 0.
  bool Positive(const std::string& key, double v);
  /// Finite and >= lo.
  bool AtLeast(const std::string& key, double v, double lo);
  /// Finite and in [lo, hi].
  bool InRange(const std::string& key, double v, double lo, double hi);

  bool ok() const { return status_.ok(); }
  /// Ok, or the first failure.
  const Status& status() const { return status_; }
  /// The key of the first failure (empty while ok()).
  const std::string& key() const { return key_; }

 private:
  Status status_ = Status::Ok();
  std::string key_;
};

}  // namespace rover
