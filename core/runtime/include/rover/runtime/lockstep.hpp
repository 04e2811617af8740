#pragma once
/// @file
/// Strict lock-step stamping (docs/scenarios.md, "Reproducible runs"): how a run on a simulated
/// clock becomes independent of wall-clock scheduling.
///
/// The simulator advances in quanta of Q seconds and publishes sim/clock only at their ends,
/// the ticks T = Q, 2Q, ...; it starts a quantum only when every lock-step participant has
/// acknowledged the last tick. Each participant serves a tick T in one go: it delivers its
/// inputs, fires its run-clock timers, writes its outputs and then acknowledges T. Two rules
/// make what a participant sees at T independent of when the samples happened to arrive:
///
///   write tick   every sample a thread writes carries, as its DDS source timestamp, the tick
///                the thread is serving (SetWriteTick); the simulator stamps the samples of the
///                quantum (T - Q, T] with T - Q;
///   read gate    a reader on a gated thread (SetReadGate(T)) hands out only samples whose
///                source timestamp is < T, oldest tick first, and keeps the others for a later
///                tick.
///
/// So an output written while serving tick T is seen by everyone at T + Q, never at T, however
/// fast its writer was; and at T + Q it has arrived, because its writer acknowledged T only
/// after writing it and the simulator published T + Q only after that acknowledgement (causal
/// order on one host: the sample precedes the acknowledgement on the wire). A sample that
/// nevertheless arrives a tick late (a lost fragment resent) is still delivered, and counted
/// (LateSamples), so a run that may not be reproducible says so.
///
/// Source timestamps below kWallStampFloor are ticks (simulated ns); a sample stamped with wall
/// time (a writer that is not in lock-step) is not held back by a gate.
///
/// Both settings are per thread: a service's executor thread, each scenario run's thread in
/// the runner. kOff (the default) means wall-time stamps and no gate.

#include <dds/dds.h>

#include <cstdint>
#include <limits>

namespace rover::dds::lockstep {

inline constexpr std::int64_t kOff = std::numeric_limits<std::int64_t>::min();
/// Source timestamps at or above this are wall time (2001-09-09), below it ticks.
inline constexpr std::int64_t kWallStampFloor = 1'000'000'000'000'000'000;

/// The tick this thread's writes carry (kOff: the wall time, as DDS does by default).
void SetWriteTick(std::int64_t tick_ns);
std::int64_t WriteTick();
/// Readers taken from on this thread hand out only samples stamped before `before_ns`
/// (kOff: every sample).
void SetReadGate(std::int64_t before_ns);
std::int64_t ReadGate();

/// dds_write, stamped with this thread's write tick when one is set (every write of the
/// typed writers and of the fault seams goes through here).
dds_return_t Write(dds_entity_t writer, const void* sample);

/// True when a sample with this source timestamp is visible under the gate `before_ns`.
inline bool Visible(dds_time_t source_timestamp, std::int64_t before_ns) {
  return before_ns == kOff || source_timestamp >= kWallStampFloor || source_timestamp < before_ns;
}

/// Samples of this process delivered later than the tick after the one they were written at
/// (they arrived late; the run may not be reproducible).
std::uint64_t LateSamples();
void CountLateSample();

}  // namespace rover::dds::lockstep
