#include "rover/runtime/executor.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "rover/testing/test_support.hpp"

namespace rover {
namespace {

class ExecutorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    lease_ = testing::IsolatedDomain();
    auto p = dds::Participant::Create(lease_.domain());
    ASSERT_TRUE(p.ok());
    participant_ = std::move(*p);
  }
  std::unique_ptr<Executor> Make(const Clock& c) {
    auto e = Executor::Create(participant_, c);
    EXPECT_TRUE(e.ok());
    return std::move(*e);
  }
  dds::DomainLease lease_;
  dds::Participant participant_;
};

TEST_F(ExecutorTest, RunClockTimersFollowSimulatedTime) {
  ManualClock clock(Time{0}, /*valid=*/false);
  auto exec = Make(clock);
  ASSERT_TRUE(exec->SetActive(true).ok());
  int fired = 0;
  exec->AddTimer(Seconds(0.125), [&] { ++fired; });  // 8 Hz on the run clock
  exec->SpinOnce(Duration::zero());
  EXPECT_EQ(fired, 0);  // no time yet: the clock has not been heard from
  clock.Set(Time::FromSeconds(1.0));
  exec->SpinOnce(Duration::zero());  // arms at t = 1.0
  for (int i = 1; i <= 80; ++i) {
    clock.Set(Time::FromSeconds(1.0 + i * 0.0125));  // 10 simulated seconds in 80 ticks
    exec->SpinOnce(Duration::zero());
  }
  EXPECT_EQ(fired, 8);  // 1 s of simulated time at 8 Hz, regardless of wall time
}

TEST_F(ExecutorTest, ClockGoingBackRearmsTimers) {
  ManualClock clock(Time::FromSeconds(100));
  auto exec = Make(clock);
  ASSERT_TRUE(exec->SetActive(true).ok());
  int fired = 0;
  exec->AddTimer(Seconds(1.0), [&] { ++fired; });
  exec->SpinOnce(Duration::zero());
  clock.Set(Time::FromSeconds(0));  // simulator reset
  exec->SpinOnce(Duration::zero());
  clock.Set(Time::FromSeconds(0.5));
  exec->SpinOnce(Duration::zero());
  EXPECT_EQ(fired, 0);
  clock.Set(Time::FromSeconds(1.01));
  exec->SpinOnce(Duration::zero());
  EXPECT_EQ(fired, 1);
}

TEST_F(ExecutorTest, InactiveExecutorServesOnlyAlwaysTimers) {
  ManualClock clock(Time::FromSeconds(1));
  auto exec = Make(clock);
  int normal = 0, always = 0;
  exec->AddTimer(Seconds(0.1), [&] { ++normal; });
  exec->AddTimer(Seconds(0.1), [&] { ++always; }, Executor::TimerBase::kRunClock, true);
  for (int i = 0; i < 5; ++i) {
    clock.Advance(Seconds(0.11));
    exec->SpinOnce(Duration::zero());
  }
  EXPECT_EQ(normal, 0);
  EXPECT_GE(always, 3);
}

TEST_F(ExecutorTest, CallbackExceptionsAreContained) {
  ManualClock clock(Time::FromSeconds(1));
  auto exec = Make(clock);
  ASSERT_TRUE(exec->SetActive(true).ok());
  auto w = dds::Writer<rover_ddl_Imu>::Create(participant_, "ddl/imu");
  auto r = dds::Reader<rover_ddl_Imu>::Create(participant_, "ddl/imu");
  ASSERT_TRUE(w.ok() && r.ok());
  int good = 0;
  ASSERT_TRUE(exec->Subscribe<rover_ddl_Imu>(*r, [&](const dds::Sample<rover_ddl_Imu>& s) {
    if (s->angular_velocity.z < 0) throw std::runtime_error("bad sample");
    ++good;
  }).ok());
  ASSERT_TRUE(testing::WaitFor([&] { return w->MatchedReaders() == 1; }));
  for (double z : {1.0, -1.0, 2.0}) {
    rover_ddl_Imu m{};
    m.angular_velocity.z = z;
    ASSERT_TRUE(w->Write(m).ok());
  }
  ASSERT_TRUE(testing::WaitFor([&] {
    exec->SpinOnce(std::chrono::milliseconds(10));
    return good == 2;
  }));
  EXPECT_EQ(exec->callback_errors(), 1u);
}

TEST_F(ExecutorTest, WorkRunsBetweenPollsOnlyWhileActive) {
  WallClock clock;
  auto exec = Make(clock);
  int calls = 0;
  exec->SetWork([&]() -> Duration {
    if (++calls == 50) exec->Stop();
    return Duration::zero();
  });
  ASSERT_TRUE(exec->SetActive(true).ok());
  exec->Spin();  // returns because the work function stops it after 50 calls
  EXPECT_EQ(calls, 50);
}

TEST_F(ExecutorTest, StopWakesSpinFromAnotherThread) {
  WallClock clock;
  auto exec = Make(clock);
  std::thread t([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    exec->Stop();
  });
  exec->Spin();  // returns only because of Stop()
  t.join();
  EXPECT_TRUE(exec->stopped());
}

}  // namespace
}  // namespace rover
