#include "rover/runtime/activity.hpp"

#include "rover/base/cpu_time.hpp"

#include <time.h>

#include <algorithm>

#include "rover/base/clock.hpp"

namespace rover::runtime {

void ActivityLog::Add(std::string_view name, Duration wall) {
  const double s = std::max(0.0, ToSeconds(wall));
  std::string_view key = name.substr(0, kMaxNameLength);
  auto it =
      std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.name == key; });
  if (it == entries_.end()) {
    if (entries_.size() + 1 >= kMaxActivities) {
      key = "other";
      it = std::find_if(entries_.begin(), entries_.end(),
                        [&](const Entry& e) { return e.name == key; });
    }
    if (it == entries_.end()) {
      entries_.push_back(Entry{std::string(key), 0.0, 0});
      it = entries_.end() - 1;
    }
  }
  it->wall_s += s;
  ++it->count;
}

ScopedActivity::ScopedActivity(ActivityLog& log, std::string_view name)
    : log_(log), name_(name), start_(MonotonicNow()) {}

ScopedActivity::~ScopedActivity() { log_.Add(name_, MonotonicNow() - start_); }

double ProcessCpuSeconds() {
  timespec ts{};
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return 0.0;
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

double ThreadCpuSeconds() { return rover::ThreadCpuSeconds(); }

}  // namespace rover::runtime
