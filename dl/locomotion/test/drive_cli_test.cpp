// rover-drive's command line without DDS: subcommands, units, environment, clear errors.
#include "tools/drive_cli.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace rover::dl::locomotion::tools {
namespace {

ParseOutcome Parse(std::vector<std::string> args, const char* env_domain = nullptr,
                   const char* env_clock = nullptr) {
  args.insert(args.begin(), "rover-drive");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  return ParseDriveCli(static_cast<int>(argv.size()), argv.data(), env_domain, env_clock);
}

TEST(DriveCli, ArcWithGlobalOptionsAfterTheSubcommand) {
  const ParseOutcome p =
      Parse({"arc", "--curvature", "0.5", "--distance", "2", "--domain", "17", "--timeout", "30"});
  ASSERT_TRUE(p.options.has_value()) << p.output;
  EXPECT_EQ(p.options->primitive, DrivePrimitive::kArc);
  EXPECT_EQ(p.options->curvature, 0.5);
  EXPECT_EQ(p.options->distance, 2.0);
  EXPECT_EQ(p.options->domain, 17);
  EXPECT_EQ(p.options->timeout_s, 30.0);
  EXPECT_EQ(p.options->clock, "wall");
  const rover_dl_DriveCommand c = MakeDriveCommand(*p.options, 9, 123);
  EXPECT_EQ(c.primitive, rover_dl_PRIMITIVE_ARC);
  EXPECT_EQ(c.command_id, 9u);
  EXPECT_EQ(c.header.stamp_ns, 123);
  EXPECT_EQ(c.curvature, 0.5);
  EXPECT_EQ(c.distance, 2.0);
}

TEST(DriveCli, TurnTakesDegreesOrRadiansAndOtherPrimitivesParse) {
  ParseOutcome p = Parse({"turn", "--angle-deg", "90"});
  ASSERT_TRUE(p.options.has_value()) << p.output;
  EXPECT_EQ(p.options->primitive, DrivePrimitive::kTurnInPlace);
  EXPECT_NEAR(p.options->angle, std::numbers::pi / 2, 1e-15);
  p = Parse({"turn", "--angle", "-0.5"});
  ASSERT_TRUE(p.options.has_value()) << p.output;
  EXPECT_EQ(p.options->angle, -0.5);
  p = Parse({"straight", "--distance", "-1", "--speed", "0.03", "--drive-timeout", "90"});
  ASSERT_TRUE(p.options.has_value()) << p.output;
  EXPECT_EQ(p.options->primitive, DrivePrimitive::kStraight);
  EXPECT_EQ(p.options->distance, -1.0);
  EXPECT_EQ(p.options->speed, 0.03);
  EXPECT_EQ(p.options->drive_timeout_s, 90.0);
  p = Parse({"steer", "--curvature", "0.3"});
  ASSERT_TRUE(p.options.has_value()) << p.output;
  EXPECT_EQ(p.options->primitive, DrivePrimitive::kSteer);
  p = Parse({"stop", "--id", "77"});
  ASSERT_TRUE(p.options.has_value()) << p.output;
  EXPECT_EQ(p.options->primitive, DrivePrimitive::kStop);
  EXPECT_EQ(p.options->command_id, 77u);
}

TEST(DriveCli, DomainAndClockComeFromTheEnvironmentUnlessGiven) {
  ParseOutcome p = Parse({"stop"}, "42", "sim");
  ASSERT_TRUE(p.options.has_value()) << p.output;
  EXPECT_EQ(p.options->domain, 42);
  EXPECT_EQ(p.options->clock, "sim");
  p = Parse({"stop", "--domain", "3", "--clock", "wall"}, "42", "sim");
  ASSERT_TRUE(p.options.has_value()) << p.output;
  EXPECT_EQ(p.options->domain, 3);
  EXPECT_EQ(p.options->clock, "wall");
  p = Parse({"stop"}, "forty-two");
  EXPECT_EQ(p.exit_code, kExitBadArguments);
  EXPECT_NE(p.output.find("ROVER_DOMAIN 'forty-two' is not a domain id"), std::string::npos)
      << p.output;
}

TEST(DriveCli, BadArgumentsGiveOneClearErrorAndExitCode2) {
  struct Case {
    std::vector<std::string> args;
    std::string expected;
  };
  const Case cases[] = {
      {{}, "a primitive is required: one of arc, straight, turn, steer, stop"},
      {{"fly"}, "unknown primitive 'fly' (expected one of: arc, straight, turn, steer, stop)"},
      {{"--domain", "3", "fly"}, "unknown primitive 'fly'"},
      {{"arc", "--distance", "1"}, "--curvature is required"},
      {{"arc", "--curvature", "abc", "--distance", "1"}, "abc"},
      {{"arc", "--curvature", "nan", "--distance", "1"}, "--curvature nan must be a finite number"},
      {{"straight", "--distance", "inf"}, "--distance inf must be a finite number"},
      {{"turn"}, "turn needs --angle-deg A [deg] or --angle A [rad]"},
      {{"turn", "--angle-deg", "10", "--angle", "1"}, "excludes"},
      {{"straight", "--distance", "1", "--speed", "-0.1"}, "--speed -0.1 m/s must be >= 0"},
      {{"stop", "--timeout", "0"}, "--timeout 0 must be > 0"},
      {{"stop", "--domain", "300"}, "--domain 300 is out of range [0, 232]"},
      {{"stop", "--clock", "sundial"}, "--clock 'sundial' is not one of: wall, sim"},
  };
  for (const Case& c : cases) {
    const ParseOutcome p = Parse(c.args);
    EXPECT_FALSE(p.options.has_value());
    EXPECT_EQ(p.exit_code, kExitBadArguments);
    EXPECT_TRUE(p.output_is_error);
    EXPECT_EQ(p.output.rfind("rover-drive: error: ", 0), 0u) << p.output;
    EXPECT_NE(p.output.find(c.expected), std::string::npos) << p.output;
  }
}

TEST(DriveCli, RawSkipsTheLocalChecksSoTheServiceCanBeTested) {
  const ParseOutcome p = Parse({"--raw", "arc", "--curvature", "nan", "--distance", "1"});
  ASSERT_TRUE(p.options.has_value()) << p.output;
  EXPECT_TRUE(std::isnan(MakeDriveCommand(*p.options, 1, 0).curvature));
}

TEST(DriveCli, HelpExitsZeroAndListsThePrimitives) {
  const ParseOutcome p = Parse({"--help"});
  EXPECT_FALSE(p.options.has_value());
  EXPECT_EQ(p.exit_code, 0);
  EXPECT_FALSE(p.output_is_error);
  for (const char* word : {"arc", "straight", "turn", "steer", "stop", "--domain", "--timeout"}) {
    EXPECT_NE(p.output.find(word), std::string::npos) << word;
  }
}

TEST(DriveCli, StatusLinesAndTerminalStates) {
  rover_dl_DriveStatus s{};
  s.header.stamp_ns = 12'500'000'000;
  s.command_id = 42;
  s.primitive = rover_dl_PRIMITIVE_ARC;
  s.state = rover_dl_DRIVE_DRIVING;
  s.distance_done = 0.5121;
  s.heading_change = 0.2566;
  std::snprintf(s.message, sizeof(s.message), "driving");
  EXPECT_EQ(FormatDriveStatus(s),
            "t=12.500 s  #42 ARC DRIVING  distance 0.512 m  heading 14.7 deg  driving");
  EXPECT_FALSE(IsTerminal(s));
  s.state = rover_dl_DRIVE_FAILED;
  s.termination = rover_dl_TERMINATION_TILT;
  EXPECT_NE(FormatDriveStatus(s).find("ARC FAILED (TILT)"), std::string::npos);
  EXPECT_TRUE(IsTerminal(s));
  s.state = rover_dl_DRIVE_REJECTED;
  EXPECT_TRUE(IsTerminal(s));
  s.state = rover_dl_DRIVE_DONE;
  EXPECT_TRUE(IsTerminal(s));
}

}  // namespace
}  // namespace rover::dl::locomotion::tools
