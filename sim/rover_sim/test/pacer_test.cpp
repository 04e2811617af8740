#include "rover/sim/rover_sim/pacer.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rover/base/param_binder.hpp"

namespace rover::sim::rover_sim {
namespace {

Time Wall(double s) { return Time::FromSeconds(100.0 + s); }

TEST(PacerOptionsTest, DefaultsAreValid) { EXPECT_TRUE(PacerOptions{}.Validate().ok()); }

TEST(PacerOptionsTest, RejectsALeadBelowTheAcknowledgementGranularity) {
  PacerOptions o;
  o.lockstep_lead_s = 0.01;
  const Status s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("lockstep_lead_s = 0.01 s is below"), std::string::npos)
      << s.message();
  o.lockstep_lead_s = kMinLockstepLeadS;
  EXPECT_TRUE(o.Validate().ok());
}

TEST(PacerOptionsTest, RejectsANegativeOrNanRealTimeFactor) {
  PacerOptions o;
  o.real_time_factor = -1.0;
  EXPECT_FALSE(o.Validate().ok());
  o.real_time_factor = std::nan("");
  EXPECT_NE(o.Validate().message().find("real_time_factor is nan"), std::string::npos);
}

TEST(PacerOptionsTest, ReadsItsKeysUnderSim) {
  ParamSet p;
  DeclareParams<PacerOptions>(p, "sim.");
  ASSERT_TRUE(p.SetFromString("sim.real_time_factor=0").ok());
  ASSERT_TRUE(p.SetFromString("sim.lockstep_lead_s=0.5").ok());
  auto o = ReadParams<PacerOptions>(p, "sim.");
  ASSERT_TRUE(o.ok()) << o.status().message();
  EXPECT_EQ(o->real_time_factor, 0.0);
  EXPECT_EQ(o->lockstep_lead_s, 0.5);
  EXPECT_EQ(o->lockstep_stall_s, 30.0);
}

TEST(PacerTest, RealTimeStepsAreDueAtTheAnchoredWallTime) {
  PacerOptions o;
  o.real_time_factor = 2.0;
  Pacer p(o);
  p.Anchor(Wall(0), 10.0);
  EXPECT_EQ(p.UntilNextStep(Wall(0), 10.0), Duration::zero());
  // Simulated 11 s is due 0.5 s of wall time after the anchor.
  EXPECT_NEAR(ToSeconds(p.UntilNextStep(Wall(0.2), 11.0)), 0.3, 1e-9);
  EXPECT_EQ(p.UntilNextStep(Wall(0.5), 11.0), Duration::zero());
  EXPECT_NEAR(p.MeasuredRealTimeFactor(Wall(0.5), 11.0), 2.0, 1e-9);
}

TEST(PacerTest, ZeroRealTimeFactorNeverWaits) {
  PacerOptions o;
  o.real_time_factor = 0.0;
  Pacer p(o);
  p.Anchor(Wall(0), 0.0);
  EXPECT_EQ(p.UntilNextStep(Wall(0), 1e6), Duration::zero());
}

TEST(PacerTest, ASpeedChangeReanchorsInsteadOfRacing) {
  PacerOptions o;
  o.real_time_factor = 0.5;
  Pacer p(o);
  p.Anchor(Wall(0), 0.0);
  ASSERT_TRUE(p.SetRealTimeFactor(1.0, Wall(10), 1.0).ok());
  EXPECT_EQ(p.UntilNextStep(Wall(10), 1.0), Duration::zero());
  EXPECT_NEAR(ToSeconds(p.UntilNextStep(Wall(10), 2.0)), 1.0, 1e-9);
  const Status bad = p.SetRealTimeFactor(-3.0, Wall(11), 2.0);
  EXPECT_FALSE(bad.ok());
  EXPECT_EQ(p.real_time_factor(), 1.0);
}

TEST(PacerTest, PausedPollsAndResumeReanchors) {
  PacerOptions o;
  o.start_paused = true;
  Pacer p(o);
  EXPECT_TRUE(p.paused());
  EXPECT_EQ(p.UntilNextStep(Wall(0), 0.0), Pacer::kPausedPoll);
  p.Resume(Wall(50), 0.0);
  EXPECT_EQ(p.UntilNextStep(Wall(50), 0.0), Duration::zero());
  p.Pause();
  EXPECT_EQ(p.UntilNextStep(Wall(60), 0.0), Pacer::kPausedPoll);
}

TEST(PacerTest, LockstepWaitsForTheSlowestService) {
  PacerOptions o;
  o.real_time_factor = 0.0;
  o.lockstep_lead_s = 0.1;
  Pacer p(o);
  p.set_self("rover-sim");
  p.Anchor(Wall(0), 0.0);
  p.OnAck("dl-pose", Time::FromSeconds(1.0).ns, Wall(0));
  p.OnAck("ddl-camera", Time::FromSeconds(0.5).ns, Wall(0));
  p.OnAck("rover-sim", 0, Wall(0));  // its own acknowledgement is not waited on
  EXPECT_EQ(p.UntilNextStep(Wall(0), 0.6), Duration::zero());
  EXPECT_EQ(p.UntilNextStep(Wall(0), 0.7), Pacer::kLockstepPoll);
  p.OnAck("ddl-camera", Time::FromSeconds(0.6).ns, Wall(0.1));
  EXPECT_EQ(p.UntilNextStep(Wall(0.1), 0.7), Duration::zero());
  EXPECT_EQ(p.services_waited_on(), (std::vector<std::string>{"ddl-camera", "dl-pose"}));
}

TEST(PacerTest, LockstepDropsASilentServiceAndTakesItBackWhenItAcknowledges) {
  PacerOptions o;
  o.real_time_factor = 0.0;
  o.lockstep_lead_s = 0.1;
  o.lockstep_stall_s = 2.0;
  Pacer p(o);
  p.OnAck("dl-vo", Time::FromSeconds(1.0).ns, Wall(0));
  std::vector<std::string> dropped;
  EXPECT_EQ(p.UntilNextStep(Wall(1.9), 2.0, &dropped), Pacer::kLockstepPoll);
  EXPECT_TRUE(dropped.empty());
  // A repeated acknowledgement of the same time is not progress.
  p.OnAck("dl-vo", Time::FromSeconds(1.0).ns, Wall(1.95));
  EXPECT_EQ(p.UntilNextStep(Wall(2.1), 2.0, &dropped), Duration::zero());
  EXPECT_EQ(dropped, (std::vector<std::string>{"dl-vo"}));
  EXPECT_TRUE(p.services_waited_on().empty());
  EXPECT_EQ(p.OnAck("dl-vo", Time::FromSeconds(1.5).ns, Wall(3.0)), "dl-vo");
  EXPECT_EQ(p.UntilNextStep(Wall(3.0), 2.0), Pacer::kLockstepPoll);
}

TEST(PacerTest, StrictOptionsNeedTheServicesAndSaneNames) {
  PacerOptions o;
  o.lockstep_strict = true;
  Status s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("lockstep_services: empty"), std::string::npos) << s.message();
  o.lockstep_services = "dl-pose, ddl-imu";
  s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("lockstep_services: 'dl-pose, ddl-imu' has a space"),
            std::string::npos)
      << s.message();
  o.lockstep_services = "dl-pose,ddl-imu";
  EXPECT_TRUE(o.Validate().ok());
  o.lockstep_quantum_s = 0.0;
  EXPECT_FALSE(o.Validate().ok());
  EXPECT_EQ(Pacer::ParseServices("a,,b,"), (std::vector<std::string>{"a", "b"}));
}

TEST(PacerTest, StrictWaitsForEveryNamedServiceFromTheStart) {
  PacerOptions o;
  o.real_time_factor = 0.0;
  o.lockstep_strict = true;
  o.lockstep_services = "dl-pose,scenario-runner";
  o.lockstep_pipelined = false;
  Pacer p(o);
  p.set_self("rover-sim");
  p.Anchor(Wall(0), 0.0);
  p.SetBarrier(0, Wall(0));
  // Nobody has acknowledged tick 0 yet: a service that starts late cannot miss the start.
  EXPECT_EQ(p.UntilNextStep(Wall(0), 0.0), Pacer::kStrictWait);
  EXPECT_EQ(p.Missing(), (std::vector<std::string>{"dl-pose", "scenario-runner"}));
  p.OnAck("dl-pose", 0, Wall(0.01));
  p.OnAck("ddl-extra", 0, Wall(0.01));  // not named: heard, not waited for
  EXPECT_EQ(p.UntilNextStep(Wall(0.01), 0.0), Pacer::kStrictWait);
  p.OnAck("scenario-runner", 0, Wall(0.02));
  EXPECT_EQ(p.UntilNextStep(Wall(0.02), 0.0), Duration::zero());
  // Mid-quantum steps run on; the next barrier waits again.
  EXPECT_EQ(p.UntilNextStep(Wall(0.02), 0.01), Duration::zero());
  p.SetBarrier(Time::FromSeconds(0.02).ns, Wall(0.03));
  EXPECT_EQ(p.UntilNextStep(Wall(0.03), 0.02), Pacer::kStrictWait);
  p.OnAck("dl-pose", Time::FromSeconds(0.02).ns, Wall(0.04));
  p.OnAck("scenario-runner", Time::FromSeconds(0.02).ns, Wall(0.04));
  EXPECT_EQ(p.UntilNextStep(Wall(0.04), 0.02), Duration::zero());
  EXPECT_TRUE(p.stalled().empty());
}

TEST(PacerTest, StrictStallsOnAServiceThatNeverAnswersAndNamesIt) {
  PacerOptions o;
  o.real_time_factor = 0.0;
  o.lockstep_strict = true;
  o.lockstep_services = "dl-pose,dl-vo";
  o.lockstep_stall_s = 2.0;
  o.lockstep_pipelined = false;
  Pacer p(o);
  p.SetBarrier(Time::FromSeconds(5.0).ns, Wall(10.0));
  p.OnAck("dl-pose", Time::FromSeconds(5.0).ns, Wall(10.1));
  p.OnAck("dl-vo", Time::FromSeconds(4.99).ns, Wall(9.0));
  EXPECT_EQ(p.UntilNextStep(Wall(11.9), 5.0), Pacer::kStrictWait);
  EXPECT_TRUE(p.stalled().empty());
  EXPECT_EQ(p.UntilNextStep(Wall(12.1), 5.0), Pacer::kPausedPoll);
  EXPECT_EQ(p.stalled(), "dl-vo");
  // A stalled run stays stopped (it is no longer reproducible).
  p.OnAck("dl-vo", Time::FromSeconds(5.0).ns, Wall(12.2));
  EXPECT_EQ(p.UntilNextStep(Wall(12.3), 5.0), Pacer::kPausedPoll);
}

// Pipelined: a quantum steps at once; the clock at its end waits until the barrier that began
// it has been served.
TEST(PacerTest, PipelinedStrictStepsAtOnceAndHoldsTheClockUntilTheBarrierIsServed) {
  PacerOptions o;
  o.real_time_factor = 0.0;
  o.lockstep_strict = true;
  o.lockstep_services = "dl-pose";
  o.lockstep_stall_s = 2.0;
  o.lockstep_pipelined = true;
  Pacer p(o);
  p.SetBarrier(0, Wall(0));
  EXPECT_EQ(p.UntilNextStep(Wall(0), 0.0), Duration::zero());  // physics of (0, Q] at once
  EXPECT_EQ(p.UntilBarrierServed(Wall(0)), Pacer::kStrictWait);  // the clock at Q waits
  p.OnAck("dl-pose", 0, Wall(0.01));
  EXPECT_EQ(p.UntilBarrierServed(Wall(0.01)), Duration::zero());
  const std::int64_t q = Time::FromSeconds(0.02).ns;
  p.SetBarrier(q, Wall(0.02));
  EXPECT_EQ(p.UntilNextStep(Wall(0.02), 0.02), Duration::zero());
  EXPECT_EQ(p.UntilBarrierServed(Wall(0.03)), Pacer::kStrictWait);
  EXPECT_EQ(p.UntilBarrierServed(Wall(2.1)), Pacer::kPausedPoll);  // stalled
  EXPECT_EQ(p.stalled(), "dl-pose");
  EXPECT_EQ(p.UntilNextStep(Wall(2.1), 0.02), Pacer::kPausedPoll);
}

TEST(PacerTest, TheFrontierSumsTheLatestCountsAndIsFrozenPerTick) {
  PacerOptions o;
  o.lockstep_strict = true;
  o.lockstep_services = "a,b";
  Pacer p(o);
  p.OnWritten("a", {1, 2, 0});
  p.OnWritten("b", {0, 3, 4});
  bool fresh = false;
  EXPECT_EQ(p.FrontierFor(100, {10, 0, 0}, &fresh), (std::vector<std::uint64_t>{11, 5, 4}));
  EXPECT_TRUE(fresh);
  p.OnWritten("a", {9, 9, 9});  // an acknowledgement of the tick being served: not counted
  EXPECT_EQ(p.FrontierFor(100, {10, 0, 0}, &fresh), (std::vector<std::uint64_t>{11, 5, 4}));
  EXPECT_FALSE(fresh);
  EXPECT_EQ(p.FrontierFor(200, {10, 0, 0}, &fresh), (std::vector<std::uint64_t>{19, 12, 13}));
  EXPECT_TRUE(fresh);
}

// Idle ticks: a service whose acknowledgement says nothing is due before its next deadline and
// whose topics got no sample is not waited for at that tick; it is again when a topic it reads
// moves, when its deadline comes, or when its state is unknown (an acknowledgement of a tick
// whose frontier is gone).
TEST(PacerTest, ABarrierDoesNotWaitForAServiceWithNothingDue) {
  PacerOptions o;
  o.real_time_factor = 0.0;
  o.lockstep_strict = true;
  o.lockstep_services = "imu,camera";
  Pacer p(o);
  const std::int64_t q = Time::FromSeconds(0.01).ns;
  // Tick 0: nobody has said anything: both are waited for.
  p.FrontierFor(0, {0, 0});
  p.SetBarrier(0, Wall(0));
  EXPECT_EQ(p.Missing(), (std::vector<std::string>{"imu", "camera"}));
  p.OnAck("imu", 0, Wall(0.001));
  p.OnIdleState("imu", 0, /*next_due_ns=*/0, /*reads=*/0b01);  // every tick
  p.OnAck("camera", 0, Wall(0.001));
  p.OnIdleState("camera", 0, /*next_due_ns=*/10 * q, /*reads=*/0b10);
  EXPECT_TRUE(p.Missing().empty());
  // Tick Q: topic 0 moved (the camera does not read it), its deadline is 10 Q: idle.
  p.FrontierFor(q, {5, 0});
  p.SetBarrier(q, Wall(0.01));
  EXPECT_EQ(p.idle(), (std::vector<std::string>{"camera"}));
  EXPECT_EQ(p.Missing(), (std::vector<std::string>{"imu"}));
  EXPECT_TRUE(p.SendsTickTo("imu", /*repeat=*/false));
  EXPECT_FALSE(p.SendsTickTo("camera", /*repeat=*/false));
  EXPECT_TRUE(p.SendsTickTo("camera", /*repeat=*/true));  // a repeat goes to everyone
  p.OnAck("imu", q, Wall(0.011));
  p.OnIdleState("imu", q, 0, 0b01);
  EXPECT_EQ(p.UntilBarrierServed(Wall(0.011)), Duration::zero());
  // Tick 2Q: topic 1 moved: the camera serves.
  p.FrontierFor(2 * q, {9, 1});
  p.SetBarrier(2 * q, Wall(0.02));
  EXPECT_TRUE(p.idle().empty());
  EXPECT_EQ(p.Missing(), (std::vector<std::string>{"imu", "camera"}));
  p.OnAck("imu", 2 * q, Wall(0.021));
  p.OnIdleState("imu", 2 * q, 0, 0b01);
  p.OnAck("camera", 2 * q, Wall(0.021));
  p.OnIdleState("camera", 2 * q, 10 * q, 0b10);
  // Its deadline comes at 10 Q whatever its topics do.
  p.FrontierFor(3 * q, {12, 1});
  EXPECT_EQ(p.idle(), (std::vector<std::string>{"camera"}));
  p.FrontierFor(10 * q, {40, 1});
  EXPECT_TRUE(p.idle().empty());
  // An acknowledgement of a tick whose frontier is no longer kept: due every tick.
  p.OnIdleState("camera", 77, 100 * q, 0b10);
  p.FrontierFor(11 * q, {41, 1});
  EXPECT_TRUE(p.idle().empty());
}

}  // namespace
}  // namespace rover::sim::rover_sim
