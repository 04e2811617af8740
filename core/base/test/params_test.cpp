#include "rover/base/params.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

namespace rover {
namespace {

ParamSet MakeParams() {
  ParamSet p("drive");
  p.Declare("rate_hz", 8.0, "control rate").Range(0.1, 100.0);
  p.Declare("cycles", 3, "tilt cycles").Min(1);
  p.Declare("enabled", true, "enable checks");
  p.Declare("mode", "arc", "primitive").OneOf({"arc", "turn"});
  p.Declare("gains", std::vector<double>{1, 2, 3}, "PID gains").Size(3).Min(0.0);
  p.Declare("ekf.gyro_noise", 1e-4, "gyro noise").Range(0.0, 1.0);
  return p;
}

TEST(Params, DefaultsAreValid) {
  ParamSet p = MakeParams();
  ASSERT_TRUE(p.Validate().ok());
  EXPECT_EQ(p.GetDouble("rate_hz"), 8.0);
  EXPECT_EQ(p.GetInt("cycles"), 3);
  EXPECT_TRUE(p.GetBool("enabled"));
  EXPECT_EQ(p.GetString("mode"), "arc");
  EXPECT_EQ(p.GetDoubleList("gains").size(), 3u);
  EXPECT_EQ(p.Origin("rate_hz").ToString(), "default");
}

TEST(Params, LoadsYamlWithNestingAndServiceWrapper) {
  ParamSet p = MakeParams();
  ASSERT_TRUE(p.LoadYamlString("drive:\n  rate_hz: 10\n  ekf:\n    gyro_noise: 0.01\n", "f.yaml")
                  .ok());
  ASSERT_TRUE(p.Validate().ok());
  EXPECT_EQ(p.GetDouble("rate_hz"), 10.0);
  EXPECT_EQ(p.GetDouble("ekf.gyro_noise"), 0.01);
  EXPECT_EQ(p.Origin("rate_hz").ToString(), "f.yaml:2");
}

TEST(Params, AtParamKeyRestatesAFieldFailureAtTheKeysLine) {
  ParamSet p = MakeParams();
  ASSERT_TRUE(p.LoadYamlString("drive:\n  cycles: 2\n  rate_hz: 10\n", "f.yaml").ok());
  const Status s = AtParamKey(p, "rate_hz", InvalidArgument("rate: 10 exceeds the motor's 5"));
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message(), "f.yaml:3: key 'rate_hz': 10 exceeds the motor's 5");
  EXPECT_EQ(AtParamKey(p, "no.such", InvalidArgument("x: bad")).message(),
            "parameters: key 'no.such': bad");
  EXPECT_TRUE(AtParamKey(p, "rate_hz", Status::Ok()).ok());
}

TEST(Params, OutOfRangeNamesFileLineAndKey) {
  ParamSet p = MakeParams();
  ASSERT_TRUE(p.LoadYamlString("mode: turn\nrate_hz: 500\n", "params/drive.yaml").ok());
  const Status s = p.Validate();
  EXPECT_EQ(s.code(), StatusCode::kOutOfRange);
  EXPECT_EQ(s.message(), "params/drive.yaml:2: key 'rate_hz': 500 is out of range [0.1, 100]");
}

TEST(Params, UnknownKeySuggestsTheClosest) {
  ParamSet p = MakeParams();
  const Status s = p.LoadYamlString("rate_hx: 5\n", "a.yaml");
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message(), "a.yaml:1: key 'rate_hx': unknown parameter (did you mean 'rate_hz'?)");
}

TEST(Params, WrongTypesAreRejected) {
  ParamSet p = MakeParams();
  EXPECT_NE(p.LoadYamlString("rate_hz: fast\n", "a.yaml").message().find("expected a number"),
            std::string::npos);
  EXPECT_NE(p.LoadYamlString("cycles: 2.5\n", "a.yaml").message().find("expected an integer"),
            std::string::npos);
  EXPECT_NE(p.LoadYamlString("enabled: maybe\n", "a.yaml").message().find("expected a boolean"),
            std::string::npos);
  EXPECT_NE(p.LoadYamlString("gains: 3\n", "a.yaml").message().find("expected a list"),
            std::string::npos);
}

TEST(Params, MalformedYamlNamesTheLine) {
  ParamSet p = MakeParams();
  const Status s = p.LoadYamlString("rate_hz: 5\nmode: [arc\n", "bad.yaml");
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message().rfind("bad.yaml:", 0), 0u) << s.message();
  EXPECT_NE(s.message().find("malformed YAML"), std::string::npos);
}

TEST(Params, ConstraintsOnStringsListsAndNaN) {
  ParamSet p = MakeParams();
  ASSERT_TRUE(p.SetFromString("mode=crab").ok());
  EXPECT_NE(p.Validate().message().find("'crab' is not one of: arc, turn"), std::string::npos);
  ParamSet q = MakeParams();
  ASSERT_TRUE(q.SetFromString("gains=[1, 2]").ok());
  EXPECT_NE(q.Validate().message().find("expected 3 numbers, got 2"), std::string::npos);
  ParamSet r = MakeParams();
  ASSERT_TRUE(r.SetFromString("rate_hz=.nan").ok());
  EXPECT_NE(r.Validate().message().find("not a finite number"), std::string::npos);
  ParamSet t = MakeParams();
  EXPECT_EQ(t.SetFromString("rate_hz").code(), StatusCode::kInvalidArgument);
}

TEST(Params, RequiredMustBeGiven) {
  ParamSet p("svc");
  p.Declare("calibration_file", "", "path").Required();
  EXPECT_NE(p.Validate().message().find("required parameter 'calibration_file'"), std::string::npos);
  ASSERT_TRUE(p.SetFromString("calibration_file=/x.yaml").ok());
  EXPECT_TRUE(p.Validate().ok());
}

TEST(Params, FileErrorsAndDump) {
  ParamSet p = MakeParams();
  EXPECT_EQ(p.LoadYamlFile("/nonexistent/p.yaml").code(), StatusCode::kNotFound);
  const std::string path = ::testing::TempDir() + "/params_test.yaml";
  std::ofstream(path) << "cycles: 7\n";
  ASSERT_TRUE(p.LoadYamlFile(path).ok());
  EXPECT_EQ(p.GetInt("cycles"), 7);
  EXPECT_NE(p.DumpYaml().find("cycles: 7  # " + path + ":1"), std::string::npos);
  EXPECT_NE(p.DescribeAll().find("range [0.1, 100]"), std::string::npos);
  std::remove(path.c_str());
}

TEST(Params, DuplicateDeclarationIsAProgrammingError) {
  ParamSet p("x");
  p.Declare("a", 1.0, "");
  EXPECT_DEATH(p.Declare("a", 2.0, ""), "invariant broken");
}

TEST(Params, LoadsOnlyTheNamedSectionsWithTheirLines) {
  ParamSet p("sim");
  p.Declare("terrain.size_x", 50.0, "size").Range(1, 500);
  p.Declare("terrain.seed", 1, "seed");
  p.Declare("lander.x", 0.0, "x");
  const std::string text = "task: {type: directed}\nterrain:\n  size_x: 20\n  seed: 9\ncriteria: {}\n";
  ASSERT_TRUE(p.LoadYamlSections(text, "scn.yaml", {"terrain", "lander"}).ok());
  EXPECT_EQ(p.GetDouble("terrain.size_x"), 20.0);
  EXPECT_EQ(p.GetInt("terrain.seed"), 9);
  EXPECT_EQ(p.Origin("terrain.seed").ToString(), "scn.yaml:4");
  const Status bad = p.LoadYamlSections("terrain:\n  size: 3\n", "scn.yaml", {"terrain"});
  EXPECT_EQ(bad.message(), "scn.yaml:2: key 'terrain.size': unknown parameter (did you mean 'terrain.size_x'?)");
}

TEST(Params, EditDistance) {
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(EditDistance("", "abc"), 3u);
}

TEST(Params, DidYouMeanNamesTheClosestWithinTwoEdits) {
  EXPECT_EQ(DidYouMean("critera", {"name", "criteria", "seed"}), " (did you mean 'criteria'?)");
  EXPECT_EQ(DidYouMean("ab", {"xb", "ax"}), " (did you mean 'xb'?)");  // the first of equals
  EXPECT_EQ(DidYouMean("kitten", {"sitting"}), "");                    // three edits
  EXPECT_EQ(DidYouMean("x", {}), "");
}

TEST(Params, DidYouMeanSuggestsOnlyCloseNames) {
  const std::vector<std::string> known = {"probability", "duration_s", "start_s"};
  EXPECT_EQ(DidYouMean("probabilty", known), " (did you mean 'probability'?)");
  EXPECT_EQ(DidYouMean("start", known), " (did you mean 'start_s'?)");
  EXPECT_EQ(DidYouMean("colour", known), "");
  EXPECT_EQ(DidYouMean("x", {}), "");
}

}  // namespace
}  // namespace rover
