#include "rover/deploy/runner/fault_log.hpp"

#include <gtest/gtest.h>

namespace rover::deploy::runner {
namespace {

using faults::FaultRecord;
using Event = faults::FaultRecord::Event;

faults::FaultSpec Spec(const std::string& yaml) {
  auto s = faults::ParseFault(yaml, "s.yaml");
  EXPECT_TRUE(s.ok()) << s.status().message();
  return *s;
}

FaultRecord Rec(Event e, std::uint32_t id, const std::string& service, std::uint64_t seen,
                std::uint64_t hit, double at_s, const std::string& detail = "") {
  FaultRecord r;
  r.event = e;
  r.fault_id = id;
  r.service = service;
  r.seen = seen;
  r.hit = hit;
  r.start = Time::FromSeconds(20);
  r.end = Time::FromSeconds(30);
  r.at = Time::FromSeconds(at_s);
  r.detail = detail;
  return r;
}

TEST(FaultLog, StartCountsAndEndPerFaultSummedOverServices) {
  FaultLog log(
      {Spec("{kind: drop, topic: dl/pose, id: 1, start_s: 20, duration_s: 10, probability: 0.5}"),
       Spec("{kind: freeze, topic: ddl/imu, id: 2, service: nobody}")});
  log.Add(Rec(Event::kAdded, 1, "dl-pose", 0, 0, 0.5));
  log.Add(Rec(Event::kAdded, 1, "apl-x", 0, 0, 0.5));
  log.Add(Rec(Event::kStarted, 1, "dl-pose", 0, 0, 20.1));
  log.Add(Rec(Event::kCount, 1, "dl-pose", 40, 19, 21.1));
  log.Add(Rec(Event::kStarted, 1, "apl-x", 0, 0, 20.2));
  log.Add(Rec(Event::kCount, 1, "apl-x", 10, 6, 21.2));
  log.Add(Rec(Event::kCount, 1, "dl-pose", 30, 15, 20.9));  // late and older: counts only grow
  log.Add(Rec(Event::kEnded, 1, "dl-pose", 100, 52, 30.05));
  log.Add(Rec(Event::kRejected, 1, "apl-x", 0, 0, 30.0));
  log.Add(Rec(Event::kListed, 1, "apl-x", 25, 12, 40, "ended: fault 1: ..."));
  // Held by the simulator too, where it does not act: its answers do not make it a place where
  // the fault started (seen in a scenario run: "active: ... (not for this service)").
  log.Add(
      Rec(Event::kListed, 1, "rover-sim", 0, 0, 25, "active: fault 1: ... (not for this service)"));
  const auto s = log.Summary();
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].id, 1u);
  EXPECT_EQ(s[0].kind, "drop");
  EXPECT_EQ(s[0].topic, "dl/pose");
  EXPECT_EQ(s[0].side, "writer");
  EXPECT_EQ(s[0].service, "*");
  EXPECT_DOUBLE_EQ(s[0].start_s, 20);
  EXPECT_DOUBLE_EQ(s[0].end_s, 30);  // the LISTED window end is before the ENDED report
  EXPECT_EQ(s[0].samples_seen, 125u);
  EXPECT_EQ(s[0].samples_hit, 64u);
  EXPECT_EQ(s[0].services, (std::vector<std::string>{"apl-x", "dl-pose"}));
  EXPECT_NE(s[0].description.find("drop 50% of dl/pose"), std::string::npos);
  // Held by every service, started in none.
  EXPECT_EQ(s[1].kind, "freeze");
  EXPECT_LT(s[1].start_s, 0);
  EXPECT_LT(s[1].end_s, 0);
  EXPECT_TRUE(s[1].services.empty());
}

TEST(FaultLog, AFaultStillActiveAtTheEndHasNoEnd) {
  FaultLog log({Spec("{kind: drop, topic: dl/pose, id: 1}")});
  log.Add(Rec(Event::kStarted, 1, "dl-pose", 0, 0, 0.1));
  log.Add(Rec(Event::kListed, 1, "dl-pose", 80, 80, 12, "active: fault 1: ..."));
  const auto s = log.Summary();
  ASSERT_EQ(s.size(), 1u);
  EXPECT_DOUBLE_EQ(s[0].start_s, 20);
  EXPECT_LT(s[0].end_s, 0);
  EXPECT_EQ(s[0].samples_hit, 80u);
}

TEST(FaultLog, FaultsNotInTheSpecsAreTakenFromTheirRecords) {
  FaultLog log({});
  FaultRecord r = Rec(Event::kStarted, 7, "dl-pose", 0, 0, 1);
  r.kind = faults::FaultKind::kDelay;
  r.topic = "ddl/*";
  r.detail = "fault 7: delay ...";
  log.Add(r);
  const auto s = log.Summary();
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].id, 7u);
  EXPECT_EQ(s[0].kind, "delay");
  EXPECT_EQ(s[0].topic, "ddl/*");
}

}  // namespace
}  // namespace rover::deploy::runner
