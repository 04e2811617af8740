// Strict lock-step stamping (lockstep.hpp): writes carry the thread's tick, a gated reader hands
// out only what was written at earlier ticks, and an executor in strict mode serves each tick in
// one go, in the same order whatever order the samples arrived in.
#include "rover/runtime/lockstep.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rover/runtime/dds.hpp"
#include "rover/runtime/executor.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::dds {
namespace {

class LockstepTest : public ::testing::Test {
 protected:
  void SetUp() override {
    lease_ = testing::IsolatedDomain();
    auto p = Participant::Create(lease_.domain());
    ASSERT_TRUE(p.ok());
    participant_ = std::move(*p);
  }
  void TearDown() override {
    lockstep::SetWriteTick(lockstep::kOff);
    lockstep::SetReadGate(lockstep::kOff);
    lockstep::SetFrontier({});
  }
  static rover_dl_DriveCommand Command(std::uint32_t id) {
    rover_dl_DriveCommand c{};
    c.command_id = id;
    c.header.stamp_ns = id;
    return c;
  }
  DomainLease lease_;
  Participant participant_;
};

TEST_F(LockstepTest, WritesCarryTheThreadsTick) {
  auto w = Writer<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  auto r = Reader<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  ASSERT_TRUE(w.ok() && r.ok());
  lockstep::SetWriteTick(120'000'000);
  ASSERT_TRUE(w->Write(Command(1)).ok());
  lockstep::SetWriteTick(lockstep::kOff);
  ASSERT_TRUE(w->Write(Command(2)).ok());
  std::vector<OwnedSample<rover_dl_DriveCommand>> got;
  ASSERT_TRUE(testing::WaitFor([&] {
    for (auto& s : r->Take()) got.push_back(std::move(s));
    return got.size() == 2;
  }));
  EXPECT_EQ(got[0].info().source_timestamp, 120'000'000);
  EXPECT_GE(got[1].info().source_timestamp, lockstep::kWallStampFloor);  // wall time
}

TEST_F(LockstepTest, AGatedReaderHandsOutOnlyEarlierTicksOldestFirst) {
  auto w = Writer<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  auto r = Reader<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  ASSERT_TRUE(w.ok() && r.ok());
  // A command reader (fresh only) counts what was written before the first tick it was read at
  // as history, not for it: read it first at tick 0, as a service does.
  lockstep::SetReadGate(0);
  EXPECT_TRUE(r->Take().empty());
  lockstep::SetReadGate(lockstep::kOff);
  for (std::int64_t tick : {30, 10, 20}) {  // written out of tick order
    lockstep::SetWriteTick(tick);
    ASSERT_TRUE(w->Write(Command(static_cast<std::uint32_t>(tick))).ok());
  }
  lockstep::SetWriteTick(lockstep::kOff);
  ASSERT_TRUE(testing::WaitFor([&] {
    r->Stash();
    return r->held() == 3;
  }));
  lockstep::SetReadGate(25);  // serving tick 25: ticks 10 and 20 are visible, 30 is not
  auto first = r->Take();
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[0]->command_id, 10u);
  EXPECT_EQ(first[1]->command_id, 20u);
  EXPECT_TRUE(r->Take().empty());
  lockstep::SetReadGate(30);  // written at the tick being served: not yet
  EXPECT_TRUE(r->Take().empty());
  lockstep::SetReadGate(40);
  auto second = r->Take();
  ASSERT_EQ(second.size(), 1u);
  EXPECT_EQ(second[0]->command_id, 30u);
}

TEST_F(LockstepTest, CommandsWrittenBeforeTheFirstTickReadAreHistory) {
  auto w = Writer<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  auto r = Reader<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  ASSERT_TRUE(w.ok() && r.ok());
  lockstep::SetWriteTick(10);
  ASSERT_TRUE(w->Write(Command(1)).ok());  // before this reader's service joined at tick 50
  lockstep::SetWriteTick(50);
  ASSERT_TRUE(w->Write(Command(2)).ok());
  lockstep::SetWriteTick(lockstep::kOff);
  ASSERT_TRUE(testing::WaitFor([&] {
    r->Stash();
    return r->held() == 2;
  }));
  lockstep::SetReadGate(50);  // the first tick it serves (a restarted service)
  EXPECT_TRUE(r->Take().empty());
  lockstep::SetReadGate(60);
  auto got = r->Take();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0]->command_id, 2u);
}

TEST_F(LockstepTest, WallStampedSamplesAreNotHeldBack) {
  auto w = Writer<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  auto r = Reader<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  ASSERT_TRUE(w.ok() && r.ok());
  ASSERT_TRUE(w->Write(Command(5)).ok());  // no write tick: a writer outside lock-step
  lockstep::SetReadGate(0);
  std::vector<OwnedSample<rover_dl_DriveCommand>> got;
  ASSERT_TRUE(testing::WaitFor([&] {
    for (auto& s : r->Take()) got.push_back(std::move(s));
    return !got.empty();
  }));
  EXPECT_EQ(got[0]->command_id, 5u);
}

// The frontier: a reader serving a tick first waits until it has received what the tick says
// was written on its topic since it started counting (its second tick); what never comes is
// counted missing after kFrontierWaitS, and the reader goes on.
TEST_F(LockstepTest, AGatedReaderWaitsForTheFrontierAndCountsWhatNeverCame) {
  auto w = Writer<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  auto r = Reader<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  ASSERT_TRUE(w.ok() && r.ok());
  const int index = lockstep::CatalogIndex("dl/drive_command");
  ASSERT_GE(index, 0);
  auto frontier = [&](std::uint64_t n) {
    lockstep::TopicCounts f(TopicCatalog().size(), 0);
    f[static_cast<std::size_t>(index)] = n;
    lockstep::SetFrontier(f);
  };
  frontier(5);  // written before this reader counts: never waited for
  lockstep::SetReadGate(10);
  EXPECT_TRUE(r->Take().empty());  // first tick served
  lockstep::SetReadGate(20);
  EXPECT_TRUE(r->Take().empty());  // second: counting starts (base 5)
  lockstep::SetReadGate(lockstep::kOff);
  lockstep::SetWriteTick(20);
  ASSERT_TRUE(w->Write(Command(1)).ok());
  ASSERT_TRUE(w->Write(Command(2)).ok());
  lockstep::SetWriteTick(lockstep::kOff);
  EXPECT_EQ(lockstep::WrittenBy(participant_.handle())[static_cast<std::size_t>(index)], 2u);
  frontier(7);  // two more written before tick 30: Take waits until both are here
  lockstep::SetReadGate(30);
  auto got = r->Take();
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[1]->command_id, 2u);
  const std::uint64_t missing = lockstep::MissingSamples();
  frontier(8);  // one more that nobody sends
  lockstep::SetReadGate(40);
  EXPECT_TRUE(r->Take().empty());
  EXPECT_EQ(lockstep::MissingSamples(), missing + 1);
  EXPECT_NE(lockstep::LastLateSample().find("1 sample(s) of dl/drive_command never arrived"),
            std::string::npos);
  lockstep::SetFrontier({});
}

TEST(LockstepVisibleTest, Rule) {
  EXPECT_TRUE(lockstep::Visible(99, lockstep::kOff));
  EXPECT_TRUE(lockstep::Visible(10, 11));
  EXPECT_FALSE(lockstep::Visible(11, 11));
  EXPECT_FALSE(lockstep::Visible(12, 11));
  EXPECT_TRUE(lockstep::Visible(lockstep::kWallStampFloor + 5, 11));
}

// The executor serves a tick in one go: samples stashed while the clock stood still are handed
// out at the next tick, in subscription order, before that tick's timers, and a sample written
// at the tick being served waits for the next one.
TEST_F(LockstepTest, StrictExecutorServesEachTickInOneGo) {
  ManualClock clock(Time{0}, /*valid=*/false);
  auto exec = Executor::Create(participant_, clock);
  ASSERT_TRUE(exec.ok());
  (*exec)->SetStrictTicks(true);
  auto w_cmd = Writer<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  auto w_range = Writer<rover_dl_RangeRequest>::Create(participant_, "dl/range_request");
  auto r_cmd = Reader<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  auto r_range = Reader<rover_dl_RangeRequest>::Create(participant_, "dl/range_request");
  ASSERT_TRUE(w_cmd.ok() && w_range.ok() && r_cmd.ok() && r_range.ok());
  std::vector<std::string> events;
  ASSERT_TRUE((*exec)
                  ->Subscribe<rover_dl_DriveCommand>(*r_cmd,
                                                     [&](const Sample<rover_dl_DriveCommand>& s) {
                                                       events.push_back(
                                                           "cmd" + std::to_string(s->command_id) +
                                                           "@" + std::to_string(clock.Now().ns));
                                                     })
                  .ok());
  ASSERT_TRUE((*exec)
                  ->Subscribe<rover_dl_RangeRequest>(*r_range,
                                                     [&](const Sample<rover_dl_RangeRequest>& s) {
                                                       events.push_back(
                                                           "range" + std::to_string(s->request_id) +
                                                           "@" + std::to_string(clock.Now().ns));
                                                     })
                  .ok());
  (*exec)->AddTimer(std::chrono::nanoseconds(100),
                    [&] { events.push_back("timer@" + std::to_string(clock.Now().ns)); });
  ASSERT_TRUE((*exec)->SetActive(true).ok());
  clock.Set(Time{0});
  (*exec)->SpinOnce(Duration::zero());  // tick 0: arms the timer, nothing to hand out
  ASSERT_EQ((*exec)->last_tick(), Time{0});
  // Written at tick 0 by "another service", range request first, then the command.
  rover_dl_RangeRequest rr{};
  rr.request_id = 7;
  const std::int64_t saved = lockstep::WriteTick();
  lockstep::SetWriteTick(0);
  ASSERT_TRUE(w_range->Write(rr).ok());
  ASSERT_TRUE(w_cmd->Write(Command(1)).ok());
  lockstep::SetWriteTick(saved);
  // They arrive while the clock stands still: they wait in DDS (a gated reader does not wake
  // the thread), nothing is handed out.
  for (int i = 0; i < 5; ++i) (*exec)->SpinOnce(std::chrono::milliseconds(5));
  EXPECT_TRUE(events.empty());
  EXPECT_EQ(r_cmd->held(), 0u);
  clock.Set(Time{100});
  (*exec)->SpinOnce(Duration::zero());
  // Subscription order (command first), then the timer due at 100.
  EXPECT_EQ(events, (std::vector<std::string>{"cmd1@100", "range7@100", "timer@100"}));
  EXPECT_EQ(lockstep::WriteTick(), 100);  // what this thread writes now belongs to tick 100
}

// What an acknowledgement carries for the simulator's idle-tick rule (lockstep::MustServe): the
// next run-clock deadline and the catalog topics read; with them the simulator leaves out the
// ticks on which serving would hand out nothing and fire nothing.
TEST_F(LockstepTest, StrictExecutorReportsItsNextDeadlineAndTheTopicsItReads) {
  ManualClock clock(Time{0}, /*valid=*/false);
  auto exec = Executor::Create(participant_, clock);
  ASSERT_TRUE(exec.ok());
  (*exec)->SetStrictTicks(true);
  auto w_cmd = Writer<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  auto r_cmd = Reader<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command");
  ASSERT_TRUE(w_cmd.ok() && r_cmd.ok());
  std::vector<std::string> events;
  ASSERT_TRUE((*exec)
                  ->Subscribe<rover_dl_DriveCommand>(
                      *r_cmd,
                      [&](const Sample<rover_dl_DriveCommand>& s) {
                        events.push_back("cmd" + std::to_string(s->command_id) + "@" +
                                         std::to_string(clock.Now().ns));
                      })
                  .ok());
  (*exec)->AddTimer(std::chrono::nanoseconds(1000),
                    [&] { events.push_back("timer@" + std::to_string(clock.Now().ns)); });
  ASSERT_TRUE((*exec)->SetActive(true).ok());
  const int cmd_topic = lockstep::CatalogIndex("dl/drive_command");
  const int other_topic = lockstep::CatalogIndex("dl/range_request");
  ASSERT_GE(cmd_topic, 0);
  ASSERT_GE(other_topic, 0);
  lockstep::TopicCounts frontier(TopicCatalog().size(), 0);
  auto tick = [&](std::int64_t t) {
    lockstep::SetFrontier(frontier);
    clock.Set(Time{t});
    (*exec)->SpinOnce(Duration::zero());
  };
  tick(0);  // arms the timer: due at 1000
  ASSERT_EQ((*exec)->last_tick(), Time{0});
  EXPECT_EQ((*exec)->next_due_ns(), 1000);
  EXPECT_EQ((*exec)->reads(), lockstep::TopicBit(cmd_topic));
  const lockstep::TopicCounts served_at_0 = frontier;
  // The simulator's rule on what this executor said: another topic moving is nothing for it.
  frontier[static_cast<std::size_t>(other_topic)] = 3;
  EXPECT_FALSE(lockstep::MustServe(100, frontier, (*exec)->reads(), served_at_0,
                                   (*exec)->next_due_ns()));
  // A command written at tick 100 counts in the frontier of 200: due there, and handed out.
  const std::int64_t saved = lockstep::WriteTick();
  lockstep::SetWriteTick(100);
  ASSERT_TRUE(w_cmd->Write(Command(4)).ok());
  lockstep::SetWriteTick(saved);
  frontier[static_cast<std::size_t>(cmd_topic)] = 1;
  EXPECT_TRUE(lockstep::MustServe(200, frontier, (*exec)->reads(), served_at_0,
                                  (*exec)->next_due_ns()));
  tick(200);
  EXPECT_EQ(events, (std::vector<std::string>{"cmd4@200"}));
  // Served at 200, nothing new: due again only at the timer's 1000.
  const lockstep::TopicCounts served_at_200 = frontier;
  EXPECT_EQ((*exec)->next_due_ns(), 1000);
  EXPECT_FALSE(lockstep::MustServe(900, frontier, (*exec)->reads(), served_at_200, 1000));
  EXPECT_TRUE(lockstep::MustServe(1000, frontier, (*exec)->reads(), served_at_200, 1000));
  // Ticks 300..900 left out (the simulator did not send them): the timer still fires at 1000.
  tick(1000);
  EXPECT_EQ(events, (std::vector<std::string>{"cmd4@200", "timer@1000"}));
  EXPECT_EQ((*exec)->next_due_ns(), 2000);
  lockstep::SetFrontier({});
}

}  // namespace
}  // namespace rover::dds
