#include "rover/deploy/fault_commands.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

namespace rover::deploy {
namespace {

using faults::FaultRecord;

FaultAddArgs Flags(std::map<std::string, std::string> keys, std::string inline_spec = "") {
  FaultAddArgs a;
  a.keys = std::move(keys);
  a.inline_spec = std::move(inline_spec);
  return a;
}

std::string Error(const FaultAddArgs& a) {
  auto s = BuildFaultSpecs(a, {});
  return s.ok() ? "ok" : s.status().message();
}

TEST(FaultAdd, FlagsAndAnInlineSpecMakeOneValidatedFaultFromNow) {
  auto s = BuildFaultSpecs(Flags({{"kind", "drop"},
                                  {"topic", "dl/pose"},
                                  {"probability", "0.5"},
                                  {"seed", "7"},
                                  {"duration_s", "10"}}),
                           {1, 2});
  ASSERT_TRUE(s.ok()) << s.status().message();
  ASSERT_EQ(s->size(), 1u);
  EXPECT_EQ((*s)[0].id, 3u);  // the next id above those the set holds
  EXPECT_EQ((*s)[0].kind, faults::FaultKind::kDrop);
  EXPECT_EQ((*s)[0].probability, 0.5);
  EXPECT_EQ((*s)[0].seed, 7u);
  EXPECT_EQ((*s)[0].duration_s, 10.0);
  EXPECT_EQ((*s)[0].start_mode, faults::StartMode::kOnReceipt);

  // A flag overrides the same key of the inline map; a given id is kept.
  auto o =
      BuildFaultSpecs(Flags({{"probability", "0.25"}, {"topic", "ddl/*"}},
                            "{kind: delay, topic: dl/pose, probability: 0.9, id: 12, delay: 0.2}"),
                      {1});
  ASSERT_TRUE(o.ok()) << o.status().message();
  EXPECT_EQ((*o)[0].id, 12u);
  EXPECT_EQ((*o)[0].probability, 0.25);
  EXPECT_EQ((*o)[0].topic, "ddl/*");
  EXPECT_EQ((*o)[0].delay.a_s, 0.2);

  // --delay takes a distribution map; --from-epoch keeps start_s on the run's epoch.
  FaultAddArgs d = Flags({{"kind", "delay"},
                          {"topic", "ddl/imu"},
                          {"delay", "{distribution: uniform, min: 0.1, max: 0.5}"}});
  d.from_epoch = true;
  auto ds = BuildFaultSpecs(d, {});
  ASSERT_TRUE(ds.ok()) << ds.status().message();
  EXPECT_EQ((*ds)[0].delay.distribution, faults::DelayDistribution::kUniform);
  EXPECT_EQ((*ds)[0].delay.b_s, 0.5);
  EXPECT_EQ((*ds)[0].start_mode, faults::StartMode::kRunEpoch);
}

TEST(FaultAdd, BadSpecsAreOneLineErrorsNamingTheKey) {
  const std::string kind = Error(Flags({{"kind", "dorp"}, {"topic", "dl/pose"}}));
  EXPECT_EQ(
      kind.rfind("fault add: key 'kind': 'dorp' is not a fault kind (did you mean 'drop'?)", 0), 0u)
      << kind;
  const std::string topic = Error(Flags({}, "{kind: drop, topic: dl/poze}"));
  EXPECT_EQ(topic.rfind(
                "fault add: key 'topic': 'dl/poze' matches no catalog topic (nearest: dl/pose", 0),
            0u)
      << topic;
  const std::string field = Error(Flags(
      {{"kind", "corrupt"}, {"topic", "dl/pose"}, {"mode", "nan"}, {"field", "pose.positon.x"}}));
  EXPECT_EQ(field.rfind("fault add: key 'field': rover::dl::PoseEstimate has no field "
                        "'pose.positon.x' (nearest: pose.position.x",
                        0),
            0u)
      << field;
  EXPECT_EQ(Error(Flags({{"kind", "drop"}, {"topic", "dl/pose"}, {"probability", "1.5"}})),
            "fault add: probability = 1.5 is outside [0, 1]");
  EXPECT_EQ(Error(Flags({{"kind", "drop"}, {"topic", "dl/pose"}, {"probabilty", "1"}}))
                .rfind("fault add: key 'probabilty': unknown key (did you mean 'probability'?)", 0),
            0u);
  EXPECT_EQ(Error(Flags({}, "[drop]")),
            "fault add: the spec is a YAML map, e.g. '{kind: drop, topic: dl/pose}'");
  EXPECT_EQ(Error(FaultAddArgs{}).rfind("fault add: give a spec", 0), 0u);
}

TEST(FaultAdd, AFileOfFaultsKeepsItsLinesAndGetsFreeIds) {
  const std::string path =
      ::testing::TempDir() + "/fault-add-" + std::to_string(::getpid()) + ".yaml";
  std::ofstream(path) << "- {kind: drop, topic: dl/pose}\n- {kind: freeze, topic: ddl/imu}\n";
  FaultAddArgs a;
  a.file = path;
  auto s = BuildFaultSpecs(a, {3, 4});
  ASSERT_TRUE(s.ok()) << s.status().message();
  ASSERT_EQ(s->size(), 2u);
  EXPECT_EQ((*s)[0].id, 5u);
  EXPECT_EQ((*s)[1].id, 6u);
  std::ofstream(path) << "- {kind: drop, topic: dl/pose}\n- kind: freeze\n  topic: ddl/imuu\n";
  EXPECT_EQ(Error(a).rfind(path + ":3: key 'topic': 'ddl/imuu' matches no catalog topic", 0), 0u)
      << Error(a);
  a.keys["kind"] = "drop";
  EXPECT_EQ(Error(a), "fault add: give a file (-f) or a spec and flags, not both");
}

FaultRecord Listed(std::uint32_t id, const std::string& service, std::uint64_t seen,
                   std::uint64_t hit, const std::string& detail,
                   faults::FaultKind kind = faults::FaultKind::kDrop) {
  FaultRecord r;
  r.kind = kind;
  r.event = FaultRecord::Event::kListed;
  r.fault_id = id;
  r.service = service;
  r.topic = "ddl/imu";
  r.seen = seen;
  r.hit = hit;
  r.detail = detail;
  return r;
}

TEST(FaultList, OneRowPerFaultAndServiceItActsIn) {
  const std::string table = FormatFaultList(
      {Listed(2, "dl-smoke", 0, 0, "pending: fault 2: freeze ddl/imu ... (not for this service)",
              faults::FaultKind::kFreeze),
       Listed(1, "dl-smoke", 0, 0,
              "active: fault 1: drop 50% of ddl/imu ... (not for this service)"),
       Listed(1, "ddl-smoke", 240, 118, "active: fault 1: drop 50% of ddl/imu at the writers")});
  EXPECT_NE(table.find("1    drop       active   ddl-smoke                     240        118  "
                       "fault 1: drop 50% of ddl/imu at the writers\n"),
            std::string::npos)
      << table;
  EXPECT_EQ(table.find(" dl-smoke "), std::string::npos) << table;  // fault 1 does not act there
  EXPECT_NE(table.find("2    freeze     pending  -"), std::string::npos) << table;
  EXPECT_NE(table.find("(no service of the set matches)"), std::string::npos) << table;
  EXPECT_LT(table.find("1    drop"), table.find("2    freeze"));
  EXPECT_NE(FormatFaultList({}).find("(no faults)"), std::string::npos);
}

}  // namespace
}  // namespace rover::deploy
