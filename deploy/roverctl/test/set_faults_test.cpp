#include "rover/deploy/set_faults.hpp"

#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>

#include "rover/runtime/fault_spec.hpp"

namespace rover::deploy {
namespace {

Result<std::vector<SetFault>> Parse(const std::string& text, const std::string& file = "f.yaml") {
  const YAML::Node doc = YAML::Load(text);
  return ParseSetFaults(doc["faults"], file);
}

TEST(SetFaults, FlowYamlIsOneLine) {
  const YAML::Node n = YAML::Load("kind: drop\ntopic: dl/pose\nlist: [1, 2]\n");
  EXPECT_EQ(FlowYaml(n), "{kind: drop, topic: dl/pose, list: [1, 2]}");
}

TEST(SetFaults, ParsesValidatesAndKeepsTheDocumentsLines) {
  auto f = Parse(
      "name: x\nfaults:\n  - {kind: drop, topic: dl/pose, probability: 0.5, seed: 3}\n"
      "  - kind: delay\n    topic: ddl/imu\n    delay: {distribution: uniform, min: 0.1, max: "
      "0.2}\n");
  ASSERT_TRUE(f.ok()) << f.status().message();
  ASSERT_EQ(f->size(), 2u);
  EXPECT_EQ((*f)[0].spec.id, 1u);
  EXPECT_EQ((*f)[0].spec.line, 3);
  EXPECT_EQ((*f)[0].spec.seed, 3u);
  EXPECT_EQ((*f)[1].spec.id, 2u);
  EXPECT_EQ((*f)[1].spec.line, 4);
  EXPECT_EQ((*f)[1].spec.delay.distribution, faults::DelayDistribution::kUniform);
}

TEST(SetFaults, ErrorsNameFileLineAndKey) {
  EXPECT_EQ(Parse("faults:\n  - {kind: drop, topic: dl/pose}\n  - kind: drop\n    topic: dl/pose\n"
                  "    probability: 1.5\n")
                .status()
                .message(),
            "f.yaml:5: probability = 1.5 is outside [0, 1]");
  const std::string kind = Parse("faults:\n  - {kind: dorp, topic: dl/pose}\n").status().message();
  EXPECT_EQ(
      kind.rfind("f.yaml:2: key 'kind': 'dorp' is not a fault kind (did you mean 'drop'?)", 0), 0u)
      << kind;
  const std::string topic =
      Parse("faults:\n  - kind: drop\n    topic: dl/poze\n").status().message();
  EXPECT_EQ(
      topic.rfind("f.yaml:3: key 'topic': 'dl/poze' matches no catalog topic (nearest: dl/pose", 0),
      0u)
      << topic;
  const std::string field = Parse(
                                "faults:\n  - kind: corrupt\n    topic: dl/pose\n    mode: nan\n   "
                                " field: pose.positon.x\n")
                                .status()
                                .message();
  EXPECT_EQ(field.rfind("f.yaml:5: key 'field': rover::dl::PoseEstimate has no field "
                        "'pose.positon.x' (nearest: pose.position.x",
                        0),
            0u)
      << field;
  EXPECT_EQ(Parse("faults: {kind: drop}\n").status().message(),
            "f.yaml:1: expected a list of faults");
}

TEST(SetFaults, AppendRenumbersAfterTheSetsFaultsAndRefusesATakenId) {
  auto compose = Parse(
      "faults:\n  - {kind: drop, topic: dl/pose}\n  - {kind: freeze, topic: ddl/imu, id: 4}\n",
      "c.yaml");
  auto scenario = Parse(
      "faults:\n  - {kind: drop, topic: ddl/imu}\n  - {kind: drop, topic: dl/pose, id: 9}\n"
      "  - {kind: bias, topic: ddl/imu, field: angular_velocity.z, value: 0.01}\n",
      "s.yaml");
  ASSERT_TRUE(compose.ok() && scenario.ok());
  std::vector<SetFault> set = *compose;
  ASSERT_TRUE(AppendSetFaults(*scenario, &set).ok());
  ASSERT_EQ(set.size(), 5u);
  EXPECT_EQ(set[0].spec.id, 1u);
  EXPECT_EQ(set[1].spec.id, 4u);
  EXPECT_EQ(set[2].spec.id, 10u);  // above every id in use, the scenario's own 9 included
  EXPECT_EQ(set[3].spec.id, 9u);
  EXPECT_EQ(set[4].spec.id, 11u);

  auto clash = Parse("faults:\n  - {kind: drop, topic: ddl/imu, id: 4}\n", "s.yaml");
  ASSERT_TRUE(clash.ok());
  std::vector<SetFault> set2 = *compose;
  EXPECT_EQ(AppendSetFaults(*clash, &set2).message(),
            "s.yaml:2: key 'id': fault id 4 is already used by the fault of c.yaml:3");
}

// What the services read back (ROVER_FAULTS) is what was written, with the set's ids.
TEST(SetFaults, TheServicesFileParsesBackToTheSameFaults) {
  auto compose = Parse(
      "faults:\n  - {kind: partition, service: dl-stereo, start_s: 60}\n"
      "  - kind: corrupt\n    topic: \"dl/pose,!dl/pose_odometry\"\n    mode: value\n"
      "    value: -3.5\n    field: pose.position.x\n    name: \"a: label\"\n",
      "c.yaml");
  auto scenario = Parse(
      "faults:\n  - {kind: delay, topic: \"ddl/*\", delay: {distribution: normal, "
      "mean: 0.3, sigma: 0.1}, probability: 0.25, seed: 8, duration_s: 5}\n",
      "s.yaml");
  ASSERT_TRUE(compose.ok() && scenario.ok())
      << compose.status().message() << scenario.status().message();
  std::vector<SetFault> set = *compose;
  ASSERT_TRUE(AppendSetFaults(*scenario, &set).ok());
  auto back = faults::ParseFaults(SetFaultsFileText(set), "faults.yaml");
  ASSERT_TRUE(back.ok()) << back.status().message() << "\n" << SetFaultsFileText(set);
  ASSERT_EQ(back->size(), set.size());
  for (std::size_t i = 0; i < set.size(); ++i) {
    EXPECT_EQ((*back)[i].Describe(), set[i].spec.Describe()) << SetFaultsFileText(set);
    EXPECT_EQ((*back)[i].id, set[i].spec.id);
  }
  EXPECT_EQ((*back)[2].id, 3u);
  EXPECT_EQ((*back)[1].name, "a: label");
}

TEST(SetFaults, WritesTheFileIntoTheStateFolder) {
  const std::string dir = ::testing::TempDir() + "/set-faults-" + std::to_string(::getpid());
  auto f = Parse("faults:\n  - {kind: drop, topic: dl/pose}\n");
  ASSERT_TRUE(f.ok());
  ASSERT_TRUE(WriteSetFaults(*f, dir).ok());
  EXPECT_EQ(SetFaultsPath(dir), dir + "/faults.yaml");
  auto back = faults::LoadFaultsFile(SetFaultsPath(dir));
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->size(), 1u);
}

TEST(SetFaults, RecordsSayWhereAFaultActs) {
  faults::FaultRecord r;
  r.detail = "active: fault 1: drop every sample of dl/pose at the writers of dl-pose";
  EXPECT_TRUE(AppliesInService(r));
  r.detail += " (not for this service)";
  EXPECT_FALSE(AppliesInService(r));
  r.detail = "";
  EXPECT_TRUE(AppliesInService(r));
}

}  // namespace
}  // namespace rover::deploy
