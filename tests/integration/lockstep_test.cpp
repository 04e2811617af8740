// rover-sim's lock-step (sim.lockstep_lead_s): the simulator must not run further ahead of a
// service's sim/clock_ack than the lead, must follow the acknowledgements as they advance, and
// must stop waiting for a service that goes silent (sim.lockstep_stall_s, 2 s here) instead of
// hanging.
#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

#include "rover/base/process.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {

TEST(LockstepTest, SimulatorWaitsForTheSlowestServiceAndNotForASilentOne) {
  auto lease = testing::IsolatedDomain();
  const std::string dir = testing::MakeTempDir("lockstep");
  SpawnOptions o;
  o.argv = {testing::BinDir() + "/rover-sim",   "--domain",
            std::to_string(lease.domain()),     "--clock",
            "sim",                              "--set",
            "sim.real_time_factor=0",           "--set",
            "sim.lockstep_lead_s=0.1",          "--set",
            "sim.lockstep_stall_s=2",           "--set",
            "terrain.size_x=10",                "--set",
            "terrain.size_y=10",                "--set",
            "sim.start_paused=true"};
  o.stdout_path = dir + "/rover-sim.log";
  o.stderr_path = dir + "/rover-sim.log";
  auto sim = Process::Spawn(o);
  ASSERT_TRUE(sim.ok()) << sim.status().message();

  auto p = dds::Participant::Create(lease.domain());
  ASSERT_TRUE(p.ok());
  auto clock_r = dds::Reader<rover_sim_Clock>::Create(*p, "sim/clock");
  auto ack_w = dds::Writer<rover_sim_ClockAck>::Create(*p, "sim/clock_ack");
  auto control_w = dds::Writer<rover_sim_Control>::Create(*p, "sim/control");
  ASSERT_TRUE(clock_r.ok() && ack_w.ok() && control_w.ok());
  double sim_now = -1;
  auto pump = [&] {
    for (auto& c : clock_r->Take()) sim_now = std::max(sim_now, Time{c->sim_time_ns}.seconds());
  };
  auto ack = [&](double t) {
    rover_sim_ClockAck a{};
    dds::CopyString(a.service, "slow-service");
    a.sim_time_ns = Time::FromSeconds(t).ns;
    a.header.stamp_ns = a.sim_time_ns;
    ASSERT_TRUE(ack_w->Write(a).ok());
  };
  ASSERT_TRUE(testing::WaitFor([&] {
    pump();
    return ack_w->MatchedReaders() >= 1 && control_w->MatchedReaders() >= 1 && sim_now >= 0;
  }, std::chrono::seconds(60))) << testing::ReadFile(dir + "/rover-sim.log");

  // Paused at 0: acknowledge 0.5 s, then let it run. It must stop within the lead of the
  // acknowledged time, and follow when the acknowledgement moves on.
  const double held = 0.5;
  ack(held);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the ack arrives first
  rover_sim_Control resume{};
  resume.command_id = 1;
  resume.command = rover_sim_SIM_RESUME;
  ASSERT_TRUE(control_w->Write(resume).ok());
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  pump();
  EXPECT_LE(sim_now, held + 0.1 + 0.011) << "ran ahead of the acknowledged time";
  EXPECT_GE(sim_now, held + 0.1 - 0.011) << "did not run up to the lead";
  ack(held + 1.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  pump();
  EXPECT_NEAR(sim_now, held + 1.1, 0.011);
  // Silent for more than 2 s: no longer waited for.
  EXPECT_TRUE(testing::WaitFor([&] {
    pump();
    return sim_now > held + 3.0;
  }, std::chrono::seconds(10)));
  (void)sim->Terminate(std::chrono::seconds(10));
  EXPECT_NE(testing::ReadFile(dir + "/rover-sim.log").find("stopped acknowledging"),
            std::string::npos);
}

}  // namespace
}  // namespace rover
