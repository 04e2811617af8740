#pragma once
// Shared by dl_pose's tests.

#include "rover/base/time.hpp"

namespace rover::dl::pose::testing {

/// A run-clock time from seconds.
inline Time T(double s) { return Time::FromSeconds(s); }

}  // namespace rover::dl::pose::testing
