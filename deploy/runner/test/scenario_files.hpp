#pragma once
// A small scenario and service set on disk for the runner's process-free tests: the "services"
// are `true` (found on PATH, not in the bin folder), so preflight checks them without running
// them.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "rover/deploy/runner.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::deploy::runner::testing {

inline constexpr const char* kSmallScenario = R"(name: tiny
compose: set.compose.yaml
seed: 3
rover: {start: {x: 1.5, y: -0.5, yaw_deg: 90}}
terrain:
  size_x: 6
  size_y: 6
  resolution: 0.05
  hills: {amplitude: 0.03}
  craters: {count: 0}
  rocks: {preset: none}
task:
  type: directed
  steps:
    - {primitive: straight, distance: 2}
criteria: {max_tilt_deg: 20}
params:
  dl-pose: {ekf: {gyro_noise: 0.001}}
)";

class ScenarioFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = rover::testing::MakeTempDir("runner-test");
    bin_ = dir_ + "/bin";
    std::filesystem::create_directories(bin_);
    Compose("services:\n  rover-sim: {command: \"true\"}\n  dl-pose: {command: \"true\"}\n");
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  void Compose(const std::string& text) { std::ofstream(dir_ + "/set.compose.yaml") << text; }
  // Parses `text` as <dir>/s.yaml with the full validation of `roverctl run`.
  Result<Scenario> Load(const std::string& text) {
    std::ofstream(dir_ + "/s.yaml") << text;
    return LoadScenario(dir_ + "/s.yaml");
  }
  RunOptions Options() const {
    RunOptions o;
    o.out_dir = dir_ + "/out";
    o.bin_dir = bin_;
    o.dds_config_uri = dds::LoopbackConfigUri(rover::testing::SourceDir());
    return o;
  }
  std::string dir_, bin_;
};

}  // namespace rover::deploy::runner::testing
