#include "rover/base/clock.hpp"

#include <ctime>

namespace rover {
namespace {
Time Read(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return Time{static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec};
}
}  // namespace

Time WallClock::Now() const { return Read(CLOCK_REALTIME); }
Time WallNow() { return Read(CLOCK_REALTIME); }
Time MonotonicNow() { return Read(CLOCK_MONOTONIC); }

}  // namespace rover
