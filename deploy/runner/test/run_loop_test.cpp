#include "rover/deploy/runner/run_loop.hpp"

#include <gtest/gtest.h>

#include "run_fixture.hpp"

namespace rover::deploy::runner {
namespace {
using testing::RunFixture;
using testing::ScriptedClock;

TEST(RunLoop, WaitsOnSimulatedTimeAndRunsPumpsEveryPass) {
  RunFixture run;
  ScriptedClock clock(run.participant(), 0.25);
  int pumps = 0;
  run.loop().AddPump([&] { ++pumps; });
  run.loop().AddCheck([&] {
    clock.Tick();
    return std::string();
  });
  EXPECT_EQ(run.loop().now(), 0);
  EXPECT_EQ(run.loop().WaitUntil([&] { return run.loop().now() >= 2.0; }), "");
  EXPECT_GE(run.loop().now(), 2.0);
  EXPECT_LE(run.loop().now(), clock.now());
  EXPECT_GE(pumps, 8);  // at least one pass per clock step heard
  // A condition that holds at once returns after one pass, without running the checks.
  const double before = clock.now();
  EXPECT_EQ(run.loop().WaitUntil([] { return true; }), "");
  EXPECT_EQ(clock.now(), before);
}

TEST(RunLoop, TheFirstFailingCheckEndsTheWait) {
  RunFixture run;
  int first = 0, second = 0;
  run.loop().AddCheck([&] { return ++first < 3 ? std::string() : "service 'x' crashed (exit 1)"; });
  run.loop().AddCheck([&] { return ++second < 10 ? std::string() : "cross-talk"; });
  EXPECT_EQ(run.loop().WaitUntil([] { return false; }), "service 'x' crashed (exit 1)");
  EXPECT_EQ(first, 3);
  EXPECT_EQ(second, 2);  // not run on the pass where the first one failed
}

TEST(RunLoop, CrashesComeBeforeTheBuiltInChecks) {
  std::atomic<bool> abort{true};
  RunFixture run(testing::Limits(100, &abort));
  run.loop().AddCheck([] { return std::string("service 'x' crashed (exit 1)"); });
  EXPECT_EQ(run.loop().Check(), "service 'x' crashed (exit 1)");
}

TEST(RunLoop, InterruptedByAbort) {
  std::atomic<bool> abort{false};
  RunFixture run(testing::Limits(100, &abort));
  EXPECT_EQ(run.loop().Check(), "");
  abort = true;
  EXPECT_EQ(run.loop().WaitUntil([] { return false; }).rfind(
                "interrupted: roverctl was stopped (Ctrl-C or a termination signal) at ", 0),
            0u);
}

TEST(RunLoop, TimeBudgetIsSimulated) {
  RunFixture run(testing::Limits(1));
  ScriptedClock clock(run.participant(), 0.5);
  run.loop().AddCheck([&] {
    clock.Tick();
    return std::string();
  });
  EXPECT_EQ(run.loop().WaitUntil([] { return false; }), "time budget of 1 simulated s exceeded");
  EXPECT_GT(run.loop().now(), 1.0);
}

TEST(RunLoop, WallBudgetCatchesAHungRun) {
  // The run "began" an hour ago; its wall budget is a minute; simulated time never moved.
  auto lease = rover::testing::IsolatedDomain();
  auto p = dds::Participant::Create(lease.domain());
  ASSERT_TRUE(p.ok());
  LoopLimits limits = testing::Limits(100);
  limits.wall_budget_s = 60;
  limits.wall_start = MonotonicNow() - Seconds(3600);
  auto loop = RunLoop::Create(*p, limits);
  ASSERT_TRUE(loop.ok());
  EXPECT_EQ((*loop)->WaitUntil([] { return false; }),
            "hung: wall budget of 60 s exceeded at 0.0 simulated s");
}

}  // namespace
}  // namespace rover::deploy::runner
