#include "rover/deploy/compose.hpp"

#include <gtest/gtest.h>

namespace rover::deploy {
namespace {

constexpr const char* kGood = R"(version: "3.9"
x-rover:
  project: smoke
  domain: 42
  clock: sim
  qos:
    dl/pose: stream
  sim:
    real_time_factor: 0
    terrain: {seed: 7}
  faults:
    - {topic: ddl/imu, kind: drop, probability: 0.1}
services:
  apl:
    image: rover-stack:latest
    command: apl-smoke --set "report_every=5"
    depends_on:
      dl: {condition: service_healthy}
    restart: on-failure:3
  dl:
    command: [dl-smoke]
    depends_on: [ddl]
    environment: [ROVER_LOG_LEVEL=debug]
    stop_grace_period: 1m30s
  ddl:
    command: ddl-smoke
    environment:
      A: "1"
    restart: always
    x-note: extensions are allowed
)";

TEST(Compose, ParsesTheSupportedSubset) {
  auto p = ParseCompose(kGood, "smoke.yaml");
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(p->rover.project, "smoke");
  EXPECT_EQ(p->rover.domain, 42);
  EXPECT_EQ(p->rover.clock, "sim");
  EXPECT_EQ(p->rover.qos.at("dl/pose"), "stream");
  EXPECT_EQ(p->rover.sim.at("terrain.seed"), "7");
  ASSERT_EQ(p->rover.faults.size(), 1u);
  EXPECT_EQ(p->rover.faults[0].spec.kind, faults::FaultKind::kDrop);
  EXPECT_EQ(p->rover.faults[0].spec.topic, "ddl/imu");
  EXPECT_EQ(p->rover.faults[0].spec.probability, 0.1);
  EXPECT_EQ(p->rover.faults[0].spec.id, 1u);
  ASSERT_EQ(p->services.size(), 3u);
  // Start order: dependencies first.
  EXPECT_EQ(p->services[0].name, "ddl");
  EXPECT_EQ(p->services[1].name, "dl");
  EXPECT_EQ(p->services[2].name, "apl");
  const ServiceSpec* apl = p->Find("apl");
  ASSERT_NE(apl, nullptr);
  EXPECT_EQ(apl->command, (std::vector<std::string>{"apl-smoke", "--set", "report_every=5"}));
  EXPECT_EQ(apl->restart, RestartPolicy::kOnFailure);
  EXPECT_EQ(apl->max_restarts, 3);
  EXPECT_EQ(apl->depends_on[0].condition, DependencyCondition::kHealthy);
  EXPECT_EQ(apl->line, 14);
  EXPECT_EQ(apl->command_line, 16);
  EXPECT_EQ(p->Find("dl")->environment.at("ROVER_LOG_LEVEL"), "debug");
  EXPECT_EQ(p->Find("dl")->stop_grace_s, 90.0);
  EXPECT_EQ(p->Find("ddl")->restart, RestartPolicy::kAlways);
}

TEST(Compose, MergeKeysFillWhatTheServiceDoesNotSet) {
  constexpr const char* kMerged = R"(version: "3.9"
x-rover: {project: merged}
x-service: &service
  image: rover-stack:latest
  restart: on-failure:3
  environment: {A: "1"}
services:
  first:
    <<: *service
    command: ddl-smoke
  second:
    <<: *service
    command: dl-smoke
    restart: "no"
)";
  auto p = ParseCompose(kMerged, "merged.yaml");
  ASSERT_TRUE(p.ok()) << p.status().message();
  const ServiceSpec* first = p->Find("first");
  const ServiceSpec* second = p->Find("second");
  ASSERT_NE(first, nullptr);
  ASSERT_NE(second, nullptr);
  EXPECT_EQ(first->restart, RestartPolicy::kOnFailure);  // from the anchor
  EXPECT_EQ(first->max_restarts, 3);
  EXPECT_EQ(first->environment.at("A"), "1");
  EXPECT_EQ(second->restart, RestartPolicy::kNo);  // its own setting wins
}

TEST(Compose, ProjectNameDefaultsToFileName) {
  auto p = ParseCompose("services: {a: {command: x}}", "deploy/drive.compose.yaml");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->rover.project, "drive");
  EXPECT_FALSE(p->rover.domain.has_value());
}

struct BadCase {
  const char* name;
  const char* text;
  const char* expected;  // the whole one-line message
};

class ComposeBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(ComposeBadInput, OneLineErrorNamingFileLineAndKey) {
  auto p = ParseCompose(GetParam().text, "f.yaml");
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.status().message(), GetParam().expected);
  EXPECT_EQ(p.status().message().find('\n'), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(
    All, ComposeBadInput,
    ::testing::Values(
        BadCase{"malformed", "services:\n  a: {command: [x\n",
                "f.yaml:3: malformed YAML: end of sequence flow not found"},
        BadCase{"unknown_top", "servics: {}\n",
                "f.yaml:1: top level: unknown key 'servics' (did you mean 'services'?) (known: "
                "version, name, services, networks, volumes)"},
        BadCase{"unknown_service_key", "services:\n  a:\n    comand: x\n",
                "f.yaml:3: services.a: unknown key 'comand' (did you mean 'command'?) (known: "
                "command, environment, depends_on, restart, stop_grace_period, image, build, "
                "network_mode, working_dir, volumes, container_name, stop_signal, healthcheck, "
                "init)"},
        BadCase{"missing_command", "services:\n  a:\n    image: x\n",
                "f.yaml:2: services.a: no 'command' (roverctl runs each service's command "
                "natively)"},
        BadCase{"duplicate_service", "services:\n  a: {command: x}\n  a: {command: y}\n",
                "f.yaml:3: services: duplicate service name 'a'"},
        BadCase{"cycle",
                "services:\n  a: {command: x, depends_on: [b]}\n  b: {command: y, depends_on: "
                "[c]}\n  c: {command: z, depends_on: [a]}\n",
                "f.yaml:2: services.a: dependency cycle: a -> b -> c -> a"},
        BadCase{"unknown_dependency", "services:\n  a: {command: x, depends_on: [bb]}\n  b: {command: y}\n",
                "f.yaml:2: services.a.depends_on: unknown service 'bb' (did you mean 'b'?)"},
        BadCase{"bad_condition",
                "services:\n  a: {command: x, depends_on: {b: {condition: up}}}\n  b: {command: y}\n",
                "f.yaml:2: services.a.depends_on.b.condition: 'up' is not one of: "
                "service_started, service_healthy, service_completed_successfully"},
        BadCase{"bad_restart", "services:\n  a: {command: x, restart: sometimes}\n",
                "f.yaml:2: services.a.restart: 'sometimes' is not one of: no, always, "
                "on-failure[:N], unless-stopped"},
        BadCase{"bad_qos", "x-rover:\n  qos:\n    dl/pose: fast\nservices: {a: {command: x}}\n",
                "f.yaml:3: x-rover.qos.dl/pose: unknown QoS profile 'fast' (known: state, "
                "stream, command, latched)"},
        BadCase{"bad_domain", "x-rover: {domain: 300}\nservices: {a: {command: x}}\n",
                "f.yaml:1: x-rover.domain: 300 is not an integer in [0, 232]"},
        BadCase{"bad_clock", "x-rover: {clock: sundial}\nservices: {a: {command: x}}\n",
                "f.yaml:1: x-rover.clock: 'sundial' is not one of: wall, sim"},
        BadCase{"unknown_rover_key", "x-rover: {domian: 3}\nservices: {a: {command: x}}\n",
                "f.yaml:1: x-rover: unknown key 'domian' (did you mean 'domain'?) (known: "
                "project, domain, clock, startup_timeout_s, heartbeat_timeout_s, qos, sim, "
                "faults, scenario, record, security, slurm)"},
        // x-rover.faults is validated when the file is read: nothing starts on a bad fault.
        BadCase{"fault_kind",
                "x-rover:\n  faults:\n    - topic: ddl/imu\n      kind: dorp\n"
                "services: {a: {command: x}}\n",
                "f.yaml:4: key 'kind': 'dorp' is not a fault kind (did you mean 'drop'?); one "
                "of: drop, delay, duplicate, reorder, freeze, corrupt, noise, bias, partition"},
        BadCase{"fault_probability",
                "x-rover:\n  faults:\n    - {kind: drop, topic: ddl/imu, probability: 1.5}\n"
                "services: {a: {command: x}}\n",
                "f.yaml:3: probability = 1.5 is outside [0, 1]"},
        BadCase{"fault_not_a_list", "x-rover:\n  faults: {kind: drop}\nservices: {a: {command: x}}\n",
                "f.yaml:2: x-rover.faults: expected a list"},
        BadCase{"env_overrides_faults",
                "services:\n  a:\n    command: x\n    environment: {ROVER_FAULTS: f.yaml}\n",
                "f.yaml:4: services.a.environment.ROVER_FAULTS: roverctl sets ROVER_FAULTS for "
                "every service (the set's faults: give them under x-rover.faults (with "
                "`service:`)); a service may not override it"},
        BadCase{"unbalanced_quote", "services:\n  a: {command: \"x 'y\"}\n",
                "f.yaml:2: services.a.command: unbalanced ' quote"},
        BadCase{"empty_services", "services: {}\n", "f.yaml:1: 'services' must be a non-empty map"},
        BadCase{"bad_grace", "services:\n  a: {command: x, stop_grace_period: soon}\n",
                "f.yaml:2: services.a.stop_grace_period: 'soon' is not a duration like 10s, "
                "1m30s, 500ms"},
        // What roverctl sets for the whole set cannot be moved for one service.
        BadCase{"env_overrides_domain",
                "services:\n  a:\n    command: x\n    environment: {A: \"1\", ROVER_DOMAIN: \"7\"}\n",
                "f.yaml:4: services.a.environment.ROVER_DOMAIN: roverctl sets ROVER_DOMAIN for "
                "every service (the set's DDS domain: choose it with x-rover.domain or --domain); "
                "a service may not override it"},
        BadCase{"env_overrides_clock_in_a_list",
                "services:\n  a:\n    command: x\n    environment:\n      - A=1\n"
                "      - ROVER_CLOCK=wall\n",
                "f.yaml:6: services.a.environment.ROVER_CLOCK: roverctl sets ROVER_CLOCK for "
                "every service (the set's run clock: choose it with x-rover.clock); a service "
                "may not override it"},
        BadCase{"env_overrides_sim_setting",
                "services:\n  a:\n    command: x\n    environment: {ROVER_SIM_SEED: \"3\"}\n",
                "f.yaml:4: services.a.environment.ROVER_SIM_SEED: roverctl sets ROVER_SIM_* for "
                "every service (simulator settings: give them under x-rover.sim); a service may "
                "not override it"},
        BadCase{"env_overrides_dds_config",
                "services:\n  a:\n    command: x\n    environment: {CYCLONEDDS_URI: x.xml}\n",
                "f.yaml:4: services.a.environment.CYCLONEDDS_URI: roverctl sets CYCLONEDDS_URI "
                "for every service (the set's Cyclone DDS configuration: give roverctl "
                "ROVER_DDS_CONFIG); a service may not override it"}),
    [](const ::testing::TestParamInfo<BadCase>& p) { return std::string(p.param.name); });

TEST(Compose, MissingFileIsNotFound) {
  auto p = LoadComposeFile("/nonexistent/x.yaml");
  EXPECT_EQ(p.status().code(), StatusCode::kNotFound);
}

TEST(Compose, SplitCommandLikeAShell) {
  auto w = SplitCommand(R"(svc --set 'a=b c' --x "q\"uote" back\ slash)");
  ASSERT_TRUE(w.ok());
  EXPECT_EQ(*w, (std::vector<std::string>{"svc", "--set", "a=b c", "--x", "q\"uote", "back slash"}));
  EXPECT_FALSE(SplitCommand("a \"b").ok());
}

TEST(Compose, Durations) {
  EXPECT_EQ(*ParseDuration("10s"), 10.0);
  EXPECT_EQ(*ParseDuration("1m30s"), 90.0);
  EXPECT_EQ(*ParseDuration("500ms"), 0.5);
  EXPECT_EQ(*ParseDuration("2"), 2.0);
  EXPECT_FALSE(ParseDuration("2 days").ok());
}

}  // namespace
}  // namespace rover::deploy
