#include "rover/msg/health.hpp"

namespace rover::msg {
namespace {

int Severity(SensorHealth h) {
  switch (h) {
    case SensorHealth::kOk:
      return 0;
    case SensorHealth::kDegraded:
      return 1;
    case SensorHealth::kStale:
      return 2;
    case SensorHealth::kFailed:
      return 3;
  }
  return 3;
}

}  // namespace

const char* SensorHealthName(SensorHealth h) {
  switch (h) {
    case SensorHealth::kOk:
      return "ok";
    case SensorHealth::kDegraded:
      return "degraded";
    case SensorHealth::kFailed:
      return "failed";
    case SensorHealth::kStale:
      return "stale";
  }
  return "?";
}

SensorHealth WorseHealth(SensorHealth a, SensorHealth b) {
  return Severity(a) >= Severity(b) ? a : b;
}

}  // namespace rover::msg
