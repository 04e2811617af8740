#include "rover/base/range_check.hpp"

#include "rover/base/format.hpp"

namespace rover {
namespace {

std::string Indexed(std::string_view name, std::size_t i) {
  return std::string(name) + "[" + std::to_string(i) + "]";
}

std::string NotFinite(std::string_view name, double v) {
  return std::string(name) + " is " + FormatNumber(v) + " (must be finite)";
}

}  // namespace

std::string Bounds::ToString() const {
  // An infinite end is never reached: it prints open.
  return std::string(open_lo || std::isinf(lo) ? "(" : "[") + FormatNumber(lo) + ", " +
         FormatNumber(hi) + (open_hi || std::isinf(hi) ? ")" : "]");
}

std::string Describe(std::string_view name, double v, std::string_view unit) {
  std::string out = std::string(name) + " = " + FormatNumber(v);
  if (!unit.empty()) out += " " + std::string(unit);
  return out;
}

Status CheckFinite(std::string_view name, double v) {
  if (std::isfinite(v)) return Status::Ok();
  return InvalidArgument(NotFinite(name, v));
}

Status CheckAllFinite(std::string_view name, std::span<const double> v) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) return InvalidArgument(NotFinite(Indexed(name, i), v[i]));
  }
  return Status::Ok();
}

Status CheckRange(std::string_view name, double v, const Bounds& bounds, std::string_view unit) {
  if (!std::isfinite(v)) return InvalidArgument(NotFinite(name, v));
  if (bounds.Contains(v)) return Status::Ok();
  return InvalidArgument(Describe(name, v, unit) + " is outside " + bounds.ToString());
}

Status CheckAllInRange(std::string_view name, std::span<const double> v, const Bounds& bounds,
                       std::string_view unit) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    ROVER_RETURN_IF_ERROR(CheckRange(Indexed(name, i), v[i], bounds, unit));
  }
  return Status::Ok();
}

Status CheckIntRange(std::string_view name, long long v, long long lo, long long hi) {
  if (v >= lo && v <= hi) return Status::Ok();
  return InvalidArgument(std::string(name) + " = " + std::to_string(v) + " is outside [" +
                         std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

}  // namespace rover
