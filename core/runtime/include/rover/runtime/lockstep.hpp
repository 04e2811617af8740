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
///   frontier     every acknowledgement carries how many samples its participant has written
///                per topic; the simulator sends their sum (and its own) with the next tick,
///                and a gated reader first waits until it has received that many (bounded by
///                kFrontierWaitS of wall time).
///
/// So an output written while serving tick T is seen by everyone at T + Q, never at T, however
/// fast its writer was; and at T + Q it has arrived: its writer acknowledged T only after
/// writing it, the simulator published T + Q only after that acknowledgement, and the frontier
/// makes the reader wait for it if it travelled slower than the clock (which happens on one
/// host: samples of two senders are not delivered in the order they were sent). A sample that
/// nevertheless arrives a tick late is still delivered, and counted (LateSamples), and one that
/// never arrives within kFrontierWaitS is counted missing, so a run that may not be
/// reproducible says so.
///
///   idle         the simulator sends each participant only the ticks on which something is
///                due for it, on the participant's own partition of sim/clock
///                (ClockPartition): MustServe of the tick's frontier, the frontier of the
///                tick it last served, and the next run-clock deadline and the catalog topics
///                it reads, both carried by its last acknowledgement. Serving a tick on which
///                nothing is due hands out no sample and fires no timer, so leaving it out
///                changes nothing in the run; it saves the participant two thread wake-ups
///                and the simulator an acknowledgement. The default partition still carries
///                every tick (the recorder, the runner, services outside strict lock-step); a
///                tick the simulator repeats while it waits goes to every participant.
///
/// Source timestamps below kWallStampFloor are ticks (simulated ns); a sample stamped with wall
/// time (a writer that is not in lock-step) is not held back by a gate.
///
/// Both settings are per thread: a service's executor thread, each scenario run's thread in
/// the runner. kOff (the default) means wall-time stamps and no gate.

#include <dds/dds.h>

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "rover/base/lockstep_rule.hpp"

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

/// A process in strict lock-step (a service with ROVER_LOCKSTEP=strict, the scenario runner of
/// a strict scenario): its readers and writers created from then on are reliable (stream topics
/// too) and keep kStrictReaderDepth / kStrictWriterDepth samples per instance instead of their
/// profile's last one or eight. A keep-last-1 reader loses a sample when the next one arrives
/// before it was taken, a best-effort one loses what the network drops, and a keep-last-1
/// writer cannot resend what it has replaced: each makes a run depend on scheduling. Readers
/// outside lock-step (roverctl, the recorder) still match: a reliable writer serves best-effort
/// readers.
void SetStrictProcess(bool strict);
bool StrictProcess();
inline constexpr int kStrictReaderDepth = 256;
inline constexpr int kStrictWriterDepth = 64;

/// Per topic of the catalog (TopicCatalog() order): samples written, or to be received.
using TopicCounts = std::vector<std::uint64_t>;
/// The catalog index of `topic`, or -1 for a topic outside the catalog.
int CatalogIndex(std::string_view topic);
/// Registers a writer (Writer<T>::Create does): its writes through Write() count for `topic`
/// and for `participant`.
void RegisterWriter(dds_entity_t writer, dds_entity_t participant, std::string_view topic);
/// The samples the registered writers of `participant` have written, per catalog topic.
TopicCounts WrittenBy(dds_entity_t participant);
/// The frontier of the tick this thread serves: a gated reader of catalog topic i first waits
/// until it has received frontier[i] samples (counting from when it first read). Empty: no
/// waiting.
void SetFrontier(TopicCounts frontier);
const TopicCounts& Frontier();
// The idle-tick rule (TopicMask, TopicBit, MustServe) is DDS-free, shared with the simulator's
// pacer: rover/base/lockstep_rule.hpp.
using ::rover::lockstep::MustServe;
using ::rover::lockstep::TopicBit;
using ::rover::lockstep::TopicMask;

/// Wall time a reader waits for its frontier before it counts the rest missing and goes on.
inline constexpr double kFrontierWaitS = 2.0;
/// Samples a reader of this process gave up waiting for (see kFrontierWaitS).
std::uint64_t MissingSamples();
void CountMissingSamples(std::string_view topic, std::uint64_t n);

/// The DDS partition on which the simulator sends strict lock-step participant `service` (its
/// --name) the ticks it must serve: "rover.clock.<service>".
std::string ClockPartition(std::string_view service);

/// The lock-step machinery's own topics (sim/clock, sim/clock_ack, sim/control): never held
/// back by a gate, whatever thread reads them.
bool Ungated(std::string_view topic);

/// True when a sample with this source timestamp is visible under the gate `before_ns`.
inline bool Visible(dds_time_t source_timestamp, std::int64_t before_ns) {
  return before_ns == kOff || source_timestamp >= kWallStampFloor || source_timestamp < before_ns;
}

/// Samples of this process delivered later than the tick after the one they were written at
/// (they arrived late; the run may not be reproducible).
std::uint64_t LateSamples();
/// Counts a late sample of `topic` written at tick `written_ns`, handed out under gate `gate_ns`.
void CountLateSample(std::string_view topic, std::int64_t written_ns, std::int64_t gate_ns);
/// The last late sample counted: "<topic> written at <t> s, handed out at <t> s" ("" if none).
std::string LastLateSample();

}  // namespace rover::dds::lockstep
