#pragma once
/// @file
/// Strict lock-step's idle-tick rule (core/runtime lockstep.hpp has the protocol): DDS-free, so
/// that the simulator's pacer and every participant apply the very same function.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rover::lockstep {

/// Catalog topics as bits (bit i: the i-th topic of the topic catalog); at most 64 topics.
using TopicMask = std::uint64_t;

/// The bit of catalog topic `index` (none for an index outside [0, 64), e.g. -1).
inline TopicMask TopicBit(int index) {
  return index < 0 || index >= 64 ? TopicMask{0} : TopicMask{1} << index;
}

/// Must a lock-step participant serve the tick `tick_ns` [ns of run clock] whose frontier (per
/// catalog topic, samples written before it) is `frontier`? Yes when its next run-clock
/// deadline `next_due_ns` has come (0: every tick), or when a topic in `reads` counts more
/// samples in `frontier` than in `served`, the frontier of the tick it last served. Otherwise
/// serving it would hand out no sample and fire no timer. Missing entries count 0.
inline bool MustServe(std::int64_t tick_ns, const std::vector<std::uint64_t>& frontier,
                      TopicMask reads, const std::vector<std::uint64_t>& served,
                      std::int64_t next_due_ns) {
  if (next_due_ns <= tick_ns) return true;
  for (std::size_t i = 0; i < frontier.size() && i < 64; ++i) {
    if ((reads & (TopicMask{1} << i)) == 0) continue;
    const std::uint64_t before = i < served.size() ? served[i] : 0;
    if (frontier[i] > before) return true;
  }
  return false;
}

}  // namespace rover::lockstep
