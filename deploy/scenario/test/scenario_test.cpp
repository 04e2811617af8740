#include "rover/deploy/scenario.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace rover::deploy {
namespace {

class ScenarioTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "/scenario_test";
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ + "/set.compose.yaml") << "services: {a: {command: x}}\n";
  }
  Result<Scenario> Parse(const std::string& text, const SimSectionValidator& v = nullptr,
                         const TaskValidator& t = nullptr) {
    return ParseScenario(text, dir_ + "/s.yaml", v, t);
  }
  std::string Err(const std::string& text, const TaskValidator& t = nullptr) {
    auto s = Parse(text, nullptr, t);
    EXPECT_FALSE(s.ok());
    const std::string prefix = dir_ + "/s.yaml:";
    const std::string m = s.status().message();
    EXPECT_EQ(m.rfind(prefix, 0), 0u) << m;
    return m.substr(prefix.size());
  }
  std::string dir_;
};

constexpr const char* kGood = R"(name: drive-turns
description: a drive with turns
compose: set.compose.yaml
seed: 7
sim: {real_time_factor: 0, time_budget_s: 200}
rover: {start: {x: 1, y: 2, yaw_deg: 90}}
terrain: {size_x: 30}
task:
  type: directed
  steps:
    - {primitive: straight, distance: 5}
    - {primitive: turn_in_place, angle_deg: -90}
    - {primitive: arc, curvature: 0.5, distance: 3, speed: 0.04}
criteria:
  target: {x: 6, y: 2, tolerance: 0.5}
  heading: {deg: 0, tolerance_deg: 3}
  max_tilt_deg: 25
  max_estimate_error_percent: 2
  max_hazard_contacts: 0
params:
  dl-pose: {ekf: {gyro_noise: 0.001}}
)";

TEST_F(ScenarioTest, ParsesAFullScenario) {
  std::string seen_text;
  std::string seen_task;
  auto s = Parse(
      kGood,
      [&](const std::string& text, const std::string&) {
        seen_text = text;
        return Status::Ok();
      },
      [&](const Scenario& parsed) {
        seen_task = parsed.task.type;
        return Status::Ok();
      });
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->name, "drive-turns");
  EXPECT_EQ(s->compose_path, std::filesystem::path(dir_ + "/set.compose.yaml").lexically_normal().string());
  EXPECT_EQ(s->seed, 7u);
  EXPECT_EQ(s->time_budget_s, 200);
  EXPECT_NEAR(s->start_yaw, M_PI / 2, 1e-12);
  // The task section's keys belong to the task (deploy/runner); the scenario knows where it is.
  EXPECT_EQ(s->task.type, "directed");
  EXPECT_EQ(s->task.line, 9);
  EXPECT_EQ(s->task.type_line, 9);
  EXPECT_EQ(seen_task, "directed");
  ASSERT_TRUE(s->criteria.target_xy.has_value());
  EXPECT_EQ(s->criteria.position_tolerance, 0.5);
  EXPECT_NEAR(*s->criteria.max_estimate_error_fraction, 0.02, 1e-12);
  EXPECT_EQ(s->criteria.max_hazard_contacts, 0);
  EXPECT_EQ(s->params.at("dl-pose").at("ekf.gyro_noise"), "0.001");
  EXPECT_EQ(seen_text, kGood);  // the simulator's sections are validated by the callback
}

TEST_F(ScenarioTest, SimulatorSectionErrorsComeFromTheValidator) {
  auto s = Parse(kGood, [](const std::string&, const std::string& file) {
    return InvalidArgument(file + ":7: key 'terrain.size_x': 30 is too small");
  });
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.status().message().find(":7: key 'terrain.size_x'"), std::string::npos);
}

TEST_F(ScenarioTest, BadInputNamesFileLineAndKey) {
  const std::string base = "name: x\ncompose: set.compose.yaml\n";
  const std::string task = "task: {type: directed, steps: [{primitive: straight, distance: 1}]}\n";
  const std::string crit = "criteria: {max_tilt_deg: 30}\n";
  EXPECT_EQ(Err(base + task + crit + "critera: {}\n"),
            "5: unknown key 'critera' (did you mean 'criteria'?) (known: name, description, "
            "compose, simulator, estimator, seed, sim, rover, task, faults, criteria, params, record, "
            "terrain, terrain_features, lander, science_targets)");
  EXPECT_EQ(Err(base + crit), "1: missing 'task' (what the rover is to do)");
  EXPECT_EQ(Err(base + task), "1: missing 'criteria' (how the run is judged)");
  EXPECT_EQ(Err(base + task + "criteria: {max_tilt_deg: 95}\n"),
            "4: criteria.max_tilt_deg: 95 is out of range [0.1, 89.9]");
  EXPECT_EQ(Err(base + task + "criteria: {target: {x: 1, y: 2, tolerance: -1}}\n"),
            "4: criteria.target.tolerance: -1 is out of range [0.001, 100]");
  EXPECT_EQ(Err(base + task + "criteria: {max_hazard_contacts: 1.5}\n"),
            "4: criteria.max_hazard_contacts: 1.5 is not a whole number");
  EXPECT_EQ(Err(base + task + "criteria: {max_hazard_contacts: -1}\n"),
            "4: criteria.max_hazard_contacts: -1 is out of range [0, 1e+06]");
  EXPECT_EQ(Err(base + task + "criteria: {target: {x: 1}}\n"),
            "4: criteria.target: needs both 'x' and 'y'");
  EXPECT_EQ(Err(base + "task: {steps: []}\n" + crit), "3: task: missing 'type'");
  EXPECT_EQ(Err(base + "task: [directed]\n" + crit), "3: task: expected a map");
  EXPECT_EQ(Err(base + "task: {type: [a]}\n" + crit), "3: task.type: expected the name of a task");
  // The task's own errors come from the task validator, after the scenario's own checks.
  const TaskValidator reject = [](const Scenario& sc) {
    return InvalidArgument(sc.file + ":" + std::to_string(sc.task.type_line) + ": task.type: '" +
                           sc.task.type + "' is not known here");
  };
  EXPECT_EQ(Err(base + "task: {type: fly}\n" + crit, reject),
            "3: task.type: 'fly' is not known here");
  EXPECT_EQ(Err(base + "task: {type: fly}\n" + "criteria: {max_tilt_deg: 95}\n", reject),
            "4: criteria.max_tilt_deg: 95 is out of range [0.1, 89.9]");
  EXPECT_EQ(Err("name: x\ncompose: nope.yaml\n" + task + crit).rfind("2: compose: file '", 0), 0u);
  EXPECT_EQ(Err(base + task + crit + "seed: -3\n"), "5: seed: expected an integer in [0, 2^32)");
  EXPECT_EQ(Err("name: [x\n"), "2: malformed YAML: end of sequence flow not found");
}

TEST_F(ScenarioTest, FaultsAreValidatedWhenTheFileIsRead) {
  auto s = Parse(std::string(kGood) +
                 "faults:\n  - {kind: drop, topic: dl/pose, probability: 0.5, start_s: 20, "
                 "duration_s: 10, seed: 3}\n  - {kind: freeze, topic: ddl/imu, service: dl-pose, "
                 "side: reader}\n");
  ASSERT_TRUE(s.ok()) << s.status().message();
  ASSERT_EQ(s->faults.size(), 2u);
  EXPECT_EQ(s->faults[0].spec.kind, faults::FaultKind::kDrop);
  EXPECT_EQ(s->faults[0].spec.start_s, 20);
  EXPECT_EQ(s->faults[0].spec.seed, 3u);
  EXPECT_EQ(s->faults[0].spec.line, 23);
  EXPECT_EQ(s->faults[1].spec.side, faults::Side::kReader);
  EXPECT_EQ(s->faults[1].spec.id, 2u);
  EXPECT_EQ(Err(std::string(kGood) + "faults:\n  - kind: drop\n    topic: dl/pose\n"
                                     "    probability: -0.1\n"),
            "25: probability = -0.1 is outside [0, 1]");
  const std::string kind = Err(std::string(kGood) + "faults:\n  - {kind: stall, topic: dl/pose}\n");
  EXPECT_EQ(kind.rfind("23: key 'kind': 'stall' is not a fault kind", 0), 0u) << kind;
  EXPECT_EQ(Err(std::string(kGood) + "faults: {kind: drop}\n"), "22: faults: expected a list");
}

TEST_F(ScenarioTest, LockstepIsStrictByDefaultAndChecked) {
  auto s = Parse(kGood);
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->lockstep, "strict");
  EXPECT_DOUBLE_EQ(s->lockstep_quantum_s, 0.04);
  // Raw camera frames, lock-step acknowledgements and the simulator's high-rate hardware streams
  // stay out of the recording unless asked for.
  EXPECT_EQ(s->record.topics.exclude,
            (std::vector<std::string>{"hw/camera_frame", "sim/clock_ack", "hw/imu",
                                      "hw/motor_telemetry", "hw/suspension_pots",
                                      "hw/arm_contact"}));
  std::string text = kGood;
  const std::string sim = "sim: {real_time_factor: 0, time_budget_s: 200}";
  auto with = [&](const std::string& replacement) {
    std::string t = text;
    t.replace(t.find(sim), sim.size(), replacement);
    return t;
  };
  auto lead = Parse(with("sim: {lockstep: lead, lockstep_quantum_s: 0.05}"));
  ASSERT_TRUE(lead.ok()) << lead.status().message();
  EXPECT_EQ(lead->lockstep, "lead");
  EXPECT_DOUBLE_EQ(lead->lockstep_quantum_s, 0.05);
  EXPECT_EQ(Err(with("sim: {lockstep: tight}")),
            "5: sim.lockstep: 'tight' is not one of: strict, lead, off");
  EXPECT_EQ(Err(with("sim: {lockstep_quantum_s: 0.015}")),
            "5: sim.lockstep_quantum_s: 0.015 s is not a whole number of the simulator's 0.01 s "
            "periods");
  EXPECT_NE(Err(with("sim: {real_time_factor: 0}") + "record: {exclude: [hw/camera_frames]}\n")
                .find("record.exclude: 'hw/camera_frames' matches no topic (did you mean "
                      "'hw/camera_frame'?)"),
            std::string::npos);
}

TEST(SeedRange, ParsesAndRejects) {
  auto r = ParseSeedRange("1..4");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(*r, (std::vector<std::uint32_t>{1, 2, 3, 4}));
  EXPECT_EQ(ParseSeedRange("9")->size(), 1u);
  EXPECT_EQ(ParseSeedRange("5..1").status().message(),
            "--seeds: '5..1' is empty: the first seed is greater than the last");
  EXPECT_FALSE(ParseSeedRange("a..b").ok());
  EXPECT_FALSE(ParseSeedRange("1..").ok());
  EXPECT_FALSE(ParseSeedRange("0..20000").ok());
  EXPECT_EQ(*ParseSeedRange("4294967295"), std::vector<std::uint32_t>{4294967295u});
  EXPECT_EQ(ParseSeedRange("4294967296").status().message(),
            "--seeds: '4294967296' is not a seed or a range A..B");
  EXPECT_EQ(ParseSeedRange("-1..3").status().message(),
            "--seeds: '-1..3' is not a range A..B of non-negative integers");
  EXPECT_EQ(ParseSeedRange("1..10000")->size(), 10000u);
  EXPECT_EQ(*ParseSeedRange("3,5..7,3,12"), (std::vector<std::uint32_t>{3, 5, 6, 7, 12}));
  EXPECT_EQ(ParseSeedRange("3,,4").status().message(),
            "--seeds: '' is not a seed or a range A..B");
  EXPECT_EQ(ParseSeedRange("0..10000").status().message(),
            "--seeds: '0..10000' has more than 10000 seeds");
}

}  // namespace
}  // namespace rover::deploy
