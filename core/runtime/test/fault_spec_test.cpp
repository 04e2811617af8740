#include "rover/runtime/fault_spec.hpp"

#include <gtest/gtest.h>

#include "rover/runtime/fault_yaml.hpp"

namespace rover::faults {
namespace {

std::string ErrorOf(std::string_view yaml) {
  auto r = ParseFaults(yaml, "faults.yaml");
  EXPECT_FALSE(r.ok()) << "parsed: " << yaml;
  const std::string m = r.ok() ? "" : r.status().message();
  EXPECT_EQ(m.find('\n'), std::string::npos) << "not one line: " << m;
  return m;
}

TEST(FaultSpec, ParsesEveryKindWithItsKeys) {
  auto r = ParseFaults(R"(
- kind: drop
  topic: dl/pose
  probability: 0.5
  start_s: 10
  duration_s: 5
  seed: 7
- kind: delay
  topic: dl/range_image
  delay: 3
- kind: delay
  topic: ddl/imu
  side: reader
  service: dl-pose
  delay: {distribution: uniform, min: 0.1, max: 0.3}
- kind: duplicate
  topic: "dl/*"
  copies: 2
- kind: reorder
  topic: ddl/joint_state
- kind: freeze
  topic: ddl/imu
  name: stuck imu
- kind: corrupt
  topic: dl/pose
  field: pose.position.x
  mode: nan
- kind: corrupt
  topic: ddl/joint_state
  field: wheel_angle[2]
  mode: bitflip
  bits: 3
- kind: noise
  topic: ddl/imu
  field: angular_velocity
  sigma: 0.01
- kind: bias
  topic: ddl/imu
  field: angular_velocity.z
  value: 0.002
- kind: partition
  service: dl-pose
  id: 42
)", "faults.yaml");
  ASSERT_TRUE(r.ok()) << r.status().message();
  ASSERT_EQ(r->size(), 11u);
  const auto& f = *r;
  EXPECT_EQ(f[0].id, 1u);
  EXPECT_EQ(f[0].kind, FaultKind::kDrop);
  EXPECT_EQ(f[0].probability, 0.5);
  EXPECT_EQ(f[0].start_s, 10.0);
  EXPECT_EQ(f[0].duration_s, 5.0);
  EXPECT_EQ(f[0].seed, 7u);
  EXPECT_EQ(f[0].service, "*");
  EXPECT_EQ(f[0].side, Side::kWriter);
  EXPECT_EQ(f[0].line, 2);
  EXPECT_EQ(f[1].delay.a_s, 3.0);
  EXPECT_EQ(f[1].delay.distribution, DelayDistribution::kFixed);
  EXPECT_EQ(f[2].delay.distribution, DelayDistribution::kUniform);
  EXPECT_EQ(f[2].delay.b_s, 0.3);
  EXPECT_EQ(f[2].side, Side::kReader);
  EXPECT_EQ(f[3].copies, 2u);
  EXPECT_EQ(f[4].delay.a_s, 1.0);  // reorder's default longest hold
  EXPECT_FALSE(f[4].delay.given);
  EXPECT_EQ(f[5].name, "stuck imu");
  EXPECT_EQ(f[6].corruption, Corruption::kNan);
  EXPECT_EQ(f[7].bits, 3u);
  EXPECT_EQ(f[8].sigma, 0.01);
  EXPECT_EQ(f[9].value, 0.002);
  EXPECT_EQ(f[10].id, 42u);
  EXPECT_EQ(f[10].topic, "*,!sim/*");  // partition: every topic but the simulator's time
  EXPECT_EQ(f[10].side, Side::kBoth);
}

TEST(FaultSpec, AcceptsAMapWithAFaultsListAndTopicLists) {
  auto r = ParseFaults("faults:\n  - {kind: drop, topic: [dl/pose, dl/pose_odometry]}\n", "f.yaml");
  ASSERT_TRUE(r.ok()) << r.status().message();
  ASSERT_EQ(r->size(), 1u);
  EXPECT_EQ((*r)[0].topic, "dl/pose,dl/pose_odometry");
  EXPECT_TRUE(ParseFaults("faults: []\n", "f.yaml").ok());
  EXPECT_NE(ErrorOf("fault:\n  - {kind: drop, topic: dl/pose}\n")
                .find("faults.yaml:1: key 'fault': unknown key (expected 'faults')"),
            std::string::npos);
}

TEST(FaultSpec, ErrorsNameFileLineAndKey) {
  EXPECT_EQ(ErrorOf("- kind: drop\n  topic: dl/pose\n- kind: dorp\n  topic: dl/pose\n"),
            "faults.yaml:3: key 'kind': 'dorp' is not a fault kind (did you mean 'drop'?); one of: "
            "drop, delay, duplicate, reorder, freeze, corrupt, noise, bias, partition");
  EXPECT_EQ(ErrorOf("- kind: drop\n  topic: dl/pose\n  probabilty: 0.5\n"),
            "faults.yaml:3: key 'probabilty': unknown key (did you mean 'probability'?)");
  EXPECT_EQ(ErrorOf("- kind: drop\n  topic: dl/poze\n").rfind(
                "faults.yaml:2: key 'topic': 'dl/poze' matches no catalog topic (nearest: dl/pose", 0),
            0u);
  EXPECT_EQ(ErrorOf("- kind: drop\n  topic: dl/pose\n  probability: 1.5\n"),
            "faults.yaml:3: probability = 1.5 is outside [0, 1]");
  const std::string field =
      ErrorOf("- kind: corrupt\n  topic: dl/pose\n  mode: nan\n  field: pose.positon.x\n");
  EXPECT_EQ(field.rfind("faults.yaml:4: key 'field': rover::dl::PoseEstimate has no field "
                        "'pose.positon.x' (nearest: pose.position.x",
                        0),
            0u)
      << field;
  EXPECT_NE(field.find("(topic dl/pose)"), std::string::npos);
  EXPECT_EQ(ErrorOf("- kind: corrupt\n  topic: dl/pose\n  mode: nan\n  field: header.seq\n"),
            "faults.yaml:3: key 'mode': rover::dl::PoseEstimate 'header.seq': member 'seq' is an "
            "unsigned integer (4 bytes); nan needs floating-point fields");
  EXPECT_NE(ErrorOf("- kind: drop\n  topic: dl/pose\n  sigma: 1\n")
                .find("faults.yaml:3: key 'sigma': does not apply to drop"),
            std::string::npos);
  EXPECT_NE(ErrorOf("- kind: partition\n").find("key 'service': partition needs the service"),
            std::string::npos);
  EXPECT_NE(ErrorOf("- {kind: drop, topic: dl/pose, id: 3}\n- {kind: drop, topic: dl/pose, id: 3}\n")
                .find("faults.yaml:2: key 'id': fault id 3 is used twice"),
            std::string::npos);
  EXPECT_NE(ErrorOf("- kind: corrupt\n  topic: dl/pose\n  field: odometer\n").find("missing key 'mode'"),
            std::string::npos);
  EXPECT_NE(ErrorOf("- kind: delay\n  topic: dl/pose\n").find("key 'delay': is required"),
            std::string::npos);
  EXPECT_NE(ErrorOf("- kind: delay\n  topic: dl/pose\n  delay: {distribution: uniform, min: 2, max: 1}\n")
                .find("delay.max = 1 s is outside [2, inf)"),
            std::string::npos);
  EXPECT_NE(ErrorOf("- kind: delay\n  topic: dl/pose\n  delay: {distribution: normal, mean: 1}\n")
                .find("'sigma' is required"),
            std::string::npos);
  EXPECT_NE(ErrorOf("- kind: corrupt\n  topic: dl/pose\n  field: header.seq\n  mode: value\n  value: -1\n")
                .find("does not fit [0, 4294967295]"),
            std::string::npos);
  EXPECT_NE(ErrorOf("- kind: corrupt\n  topic: dl/drive_command\n  field: primitive\n  mode: out_of_range\n")
                .find("member 'primitive' is an enum (4 bytes) with literals 0..4; DDS refuses to send "
                      "an enum value outside them, so corrupt it with side: reader"),
            std::string::npos);
  EXPECT_TRUE(ParseFaults("- {kind: corrupt, topic: dl/drive_command, field: primitive, mode: value, value: 2}\n"
                          "- {kind: corrupt, topic: dl/drive_command, field: primitive, mode: bitflip, side: reader}\n",
                          "f.yaml")
                  .ok());
  EXPECT_NE(ErrorOf("- kind: noise\n  topic: dl/pose\n  field: header.frame_id\n  sigma: 1\n")
                .find("noise needs numbers"),
            std::string::npos);
  EXPECT_NE(ErrorOf("- kind: drop\n  topic: dl/pose\n  probability: high\n")
                .find("key 'probability': 'high' is not a number"),
            std::string::npos);
  EXPECT_NE(ErrorOf("- kind: drop\n  topic: dl/pose\n  seed: -3\n").find("key 'seed'"), std::string::npos);
  const std::string malformed = ErrorOf("- kind: drop\n  topic: [dl/pose\n");
  EXPECT_EQ(malformed.rfind("faults.yaml:", 0), 0u) << malformed;
  EXPECT_NE(malformed.find(": malformed YAML: "), std::string::npos) << malformed;
  EXPECT_NE(ErrorOf("- drop\n").find("faults.yaml:1: fault 1: expected a map"), std::string::npos);
}

TEST(FaultSpec, NothingIsReturnedWhenOneFaultIsBad) {
  auto r = ParseFaults("- {kind: drop, topic: dl/pose}\n- {kind: drop, topic: nowhere}\n", "f.yaml");
  EXPECT_FALSE(r.ok());
}

TEST(FaultSpec, GlobsAndTopicPatterns) {
  EXPECT_TRUE(GlobMatch("*", "dl/pose"));
  EXPECT_TRUE(GlobMatch("dl/*", "dl/pose"));
  EXPECT_TRUE(GlobMatch("dl/pose*", "dl/pose_odometry"));
  EXPECT_TRUE(GlobMatch("?dl/*", "ddl/imu"));
  EXPECT_FALSE(GlobMatch("dl/*", "ddl/imu"));
  EXPECT_TRUE(GlobMatch("*/imu", "hw/imu"));
  EXPECT_FALSE(GlobMatch("dl-pose", "dl-pose2"));
  EXPECT_TRUE(TopicMatches("*,!sim/*", "dl/pose"));
  EXPECT_FALSE(TopicMatches("*,!sim/*", "sim/clock"));
  EXPECT_TRUE(TopicMatches("dl/pose, ddl/imu", "ddl/imu"));
  const auto ddl = MatchingCatalogTopics("ddl/*");
  EXPECT_NE(std::find(ddl.begin(), ddl.end(), "ddl/imu"), ddl.end());
  for (const auto& t : MatchingCatalogTopics("sys/*")) EXPECT_FALSE(IsFaultInfrastructure(t)) << t;
  EXPECT_TRUE(MatchingCatalogTopics("sys/fault_*").empty());
}

TEST(FaultSpec, ControlMessagesCarryTheWholeSpec) {
  auto r = ParseFaults(R"(
- {kind: delay, topic: ddl/imu, service: "dl-*", side: reader, probability: 0.25,
   delay: {distribution: normal, mean: 0.2, sigma: 0.05}, start_s: 1.5, duration_s: 2, seed: 99,
   name: slow imu}
- {kind: corrupt, topic: dl/pose, field: "covariance[*]", mode: value, value: -4}
- {kind: reorder, topic: ddl/joint_state}
- {kind: partition, service: dl-pose, topic: "dl/*"}
)", "f.yaml");
  ASSERT_TRUE(r.ok()) << r.status().message();
  for (const FaultSpec& s : *r) {
    rover_sys_FaultControl m{};
    ToControl(s, &m);
    EXPECT_EQ(m.action, rover_sys_FAULT_ACTION_ADD);
    auto back = FromControl(m);
    ASSERT_TRUE(back.ok()) << back.status().message();
    EXPECT_EQ(back->id, s.id);
    EXPECT_EQ(back->kind, s.kind);
    EXPECT_EQ(back->name, s.name);
    EXPECT_EQ(back->topic, s.topic);
    EXPECT_EQ(back->service, s.service);
    EXPECT_EQ(back->side, s.side);
    EXPECT_EQ(back->field, s.field);
    EXPECT_EQ(back->corruption, s.corruption);
    EXPECT_EQ(back->value, s.value);
    EXPECT_EQ(back->probability, s.probability);
    EXPECT_EQ(back->delay.distribution, s.delay.distribution);
    EXPECT_EQ(back->delay.a_s, s.delay.a_s);
    EXPECT_EQ(back->delay.b_s, s.delay.b_s);
    EXPECT_EQ(back->delay.given, s.delay.given);
    EXPECT_DOUBLE_EQ(back->start_s, s.start_s);
    EXPECT_DOUBLE_EQ(back->duration_s, s.duration_s);
    EXPECT_EQ(back->seed, s.seed);
    EXPECT_EQ(back->Describe(), s.Describe());
  }
}

TEST(FaultSpec, BadControlMessagesAreRejectedWithTheFaultId) {
  rover_sys_FaultControl m{};
  auto ok = ParseFault("{kind: drop, topic: dl/pose, id: 5}", "cli");
  ASSERT_TRUE(ok.ok()) << ok.status().message();
  ToControl(*ok, &m);
  m.probability = 2.0;
  auto bad = FromControl(m);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "sys/fault_control: fault 5: probability = 2 is outside [0, 1]");
  ToControl(*ok, &m);
  m.kind = static_cast<rover_sys_FaultKind>(77);
  EXPECT_EQ(FromControl(m).status().message(),
            "sys/fault_control: fault 5: key 'kind': value 77 is not a valid enumerator");
  ToControl(*ok, &m);
  m.fault_id = 0;
  EXPECT_FALSE(FromControl(m).ok());
}

TEST(FaultSpec, DescribeSaysWhatWhereAndWhen) {
  auto r = ParseFault("{kind: drop, topic: dl/pose, probability: 0.5, start_s: 10, duration_s: 5, seed: 3, id: 2}",
                      "cli");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->Describe(),
            "fault 2: drop 50% of dl/pose at the writers of every service, from 10 s for 5 s, seed 3");
  auto p = ParseFault("{kind: partition, service: dl-pose, id: 1}", "cli");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->Describe(), "fault 1: cut dl-pose off *,!sim/*, from 0 s until removed, seed 1");
}

TEST(FaultSpec, FilesAndYamlNodes) {
  auto missing = LoadFaultsFile("/nonexistent/faults.yaml");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().code(), StatusCode::kNotFound);
  // A section of a larger document (roverctl: x-rover.faults) keeps the document's lines.
  const YAML::Node doc = YAML::Load(
      "services: {}\nx-rover:\n  faults:\n    - kind: drop\n      topic: dl/pose\n"
      "    - kind: drop\n      topic: dl/nope\n");
  auto r = ParseFaults(doc["x-rover"]["faults"], "drive.compose.yaml");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message().rfind("drive.compose.yaml:7: key 'topic': 'dl/nope'", 0), 0u)
      << r.status().message();
}

}  // namespace
}  // namespace rover::faults
