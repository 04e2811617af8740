#pragma once
/// @file
/// ROVER_DEMAND: aborts the process on a broken invariant, i.e. a programming error that no
/// input may cause. Never use it on user input, sample contents or hardware readings; those are
/// reported with Status (status.hpp) or a typed status on a topic. See docs/error-policy.md.

namespace rover::internal {
[[noreturn]] void DemandFailed(const char* condition, const char* file, int line,
                               const char* message);
}  // namespace rover::internal

#define ROVER_DEMAND(condition)                                                     \
  do {                                                                              \
    if (!(condition)) ::rover::internal::DemandFailed(#condition, __FILE__, __LINE__, ""); \
  } while (false)

#define ROVER_DEMAND_MSG(condition, message)                                        \
  do {                                                                              \
    if (!(condition))                                                               \
      ::rover::internal::DemandFailed(#condition, __FILE__, __LINE__, (message));   \
  } while (false)

#define ROVER_UNREACHABLE() \
  ::rover::internal::DemandFailed("unreachable", __FILE__, __LINE__, "")
