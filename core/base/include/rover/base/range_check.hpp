#pragma once
/// @file
/// The one family of range checks for bad input (options structs, command fields, message
/// fields). Each returns Ok or InvalidArgument with a message in one form, naming the field:
///
///   "<name> is nan (must be finite)"
///   "<name> = 95 deg is outside [0, 45]"
///   "<name> = 0 is outside (0, 10]"          (an open bound prints a parenthesis)
///   "<name>[2] is inf (must be finite)"      (element checks name the index)
///
/// `unit` (optional) is printed after the value. Numbers use FormatNumber. These are for input;
/// broken invariants use ROVER_DEMAND (check.hpp).

#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <string_view>

#include "rover/base/status.hpp"

namespace rover {

/// A closed or half-open interval; infinite ends mean "unbounded".
struct Bounds {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool open_lo = false;  ///< exclude lo
  bool open_hi = false;  ///< exclude hi

  static Bounds Closed(double lo, double hi) { return {lo, hi, false, false}; }
  /// (lo, hi]
  static Bounds OpenLow(double lo, double hi) { return {lo, hi, true, false}; }
  /// (0, inf)
  static Bounds Positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  /// [0, inf)
  static Bounds NonNegative() { return {0.0, std::numeric_limits<double>::infinity()}; }
  static Bounds AtLeast(double lo) { return {lo, std::numeric_limits<double>::infinity()}; }
  static Bounds AtMost(double hi) { return {-std::numeric_limits<double>::infinity(), hi}; }

  bool Contains(double v) const {
    return (open_lo ? v > lo : v >= lo) && (open_hi ? v < hi : v <= hi);
  }
  /// "[0, 45]", "(0, inf)", ...
  std::string ToString() const;
};

/// Ok when `v` is finite.
Status CheckFinite(std::string_view name, double v);
/// Ok when every element is finite; the message names the first bad index.
Status CheckAllFinite(std::string_view name, std::span<const double> v);
/// Ok when `v` is finite and inside `bounds`.
Status CheckRange(std::string_view name, double v, const Bounds& bounds, std::string_view unit = "");
/// Ok when `v` is finite and in [lo, hi].
inline Status CheckRange(std::string_view name, double v, double lo, double hi,
                         std::string_view unit = "") {
  return CheckRange(name, v, Bounds::Closed(lo, hi), unit);
}
/// Ok when `v` is finite and > 0.
inline Status CheckPositive(std::string_view name, double v, std::string_view unit = "") {
  return CheckRange(name, v, Bounds::Positive(), unit);
}
/// Ok when `v` is finite and >= 0.
inline Status CheckNonNegative(std::string_view name, double v, std::string_view unit = "") {
  return CheckRange(name, v, Bounds::NonNegative(), unit);
}
/// Every element finite and inside `bounds`; the message names the first bad index.
Status CheckAllInRange(std::string_view name, std::span<const double> v, const Bounds& bounds,
                       std::string_view unit = "");
/// Integer range [lo, hi].
Status CheckIntRange(std::string_view name, long long v, long long lo, long long hi);

/// "<name> = <value><unit>" for messages of rules that are not a plain range.
std::string Describe(std::string_view name, double v, std::string_view unit = "");

}  // namespace rover
