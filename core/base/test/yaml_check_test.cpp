#include "rover/base/yaml_check.hpp"

#include <gtest/gtest.h>

namespace rover::yaml {
namespace {

const FileErrors kErr("f.yaml");

YAML::Node Parse(const std::string& text) {
  auto n = Load(text, kErr);
  EXPECT_TRUE(n.ok()) << n.status().message();
  return n.ok() ? *n : YAML::Node();
}

TEST(YamlCheck, MalformedTextNamesItsLine) {
  auto n = Load("a: 1\nb: [x\n", kErr);
  ASSERT_FALSE(n.ok());
  EXPECT_EQ(n.status().message(), "f.yaml:3: malformed YAML: end of sequence flow not found");
}

TEST(YamlCheck, UnknownKeysGetAHintAndTheList) {
  const YAML::Node n = Parse("a: 1\ncritera: 2\n");
  EXPECT_EQ(CheckKeys(n, "", {"a", "criteria"}, kErr).message(),
            "f.yaml:2: unknown key 'critera' (did you mean 'criteria'?) (known: a, criteria)");
  EXPECT_EQ(CheckKeys(n, "top level", {"a"}, kErr).message(),
            "f.yaml:2: top level: unknown key 'critera' (known: a)");
  EXPECT_TRUE(CheckKeys(n, "", {"a", "critera"}, kErr).ok());
}

TEST(YamlCheck, ExtensionKeysAndNonMaps) {
  const YAML::Node n = Parse("a: 1\nx-note: hi\n");
  EXPECT_FALSE(CheckKeys(n, "s", {"a"}, kErr).ok());
  KeyRules extensions;
  extensions.allow_extensions = true;
  EXPECT_TRUE(CheckKeys(n, "s", {"a"}, kErr, extensions).ok());
  const YAML::Node list = Parse("- 1\n- 2\n");
  EXPECT_EQ(CheckKeys(list, "sim", {"a"}, kErr).message(), "f.yaml:1: sim: expected a map");
  KeyRules any_node;
  any_node.require_map = false;
  EXPECT_TRUE(CheckKeys(list, "sim", {"a"}, kErr, any_node).ok());
}

TEST(YamlCheck, RequiredKeys) {
  const YAML::Node n = Parse("x: 1\nstep: {distance: 2}\n");
  EXPECT_TRUE(RequireKey(n, "", "x", kErr).ok());
  EXPECT_EQ(RequireKey(n["step"], "task.steps[]", "primitive", kErr).message(),
            "f.yaml:2: task.steps[]: missing 'primitive'");
}

TEST(YamlCheck, NumbersAreFiniteAndInRange) {
  const YAML::Node n = Parse("a: 95\nb: .inf\nc: fast\nd: [1]\ne: 0\n");
  EXPECT_EQ(*Number(n["a"], "a", kErr), 95.0);
  EXPECT_EQ(Number(n["b"], "s.b", kErr).status().message(),
            "f.yaml:2: s.b: expected a finite number, got '.inf'");
  EXPECT_EQ(Number(n["c"], "c", kErr).status().message(),
            "f.yaml:3: c: expected a finite number, got 'fast'");
  EXPECT_FALSE(Number(n["d"], "d", kErr).ok());

  double v = 7;
  bool present = true;
  EXPECT_TRUE(OptionalNumber(n, "missing", "s", 0, 1, kErr, &v, &present).ok());
  EXPECT_FALSE(present);
  EXPECT_EQ(v, 7);  // untouched
  EXPECT_EQ(OptionalNumber(n, "a", "criteria", 0.1, 89.9, kErr, &v).message(),
            "f.yaml:1: criteria.a: 95 is out of range [0.1, 89.9]");
  EXPECT_EQ(OptionalNumber(n, "e", "x-rover", Bounds::OpenLow(0, 3600), kErr, &v).message(),
            "f.yaml:5: x-rover.e: 0 is out of range (0, 3600]");
  EXPECT_TRUE(OptionalNumber(n, "a", "", 0, 100, kErr, &v, &present).ok());
  EXPECT_TRUE(present);
  EXPECT_EQ(v, 95);
}

TEST(YamlCheck, OneOfListsTheChoices) {
  const YAML::Node n = Parse("clock: sim\nexpect: tilted\nlist: [a]\n");
  EXPECT_EQ(*OneOf(n["clock"], "clock", {"wall", "sim"}, kErr), "sim");
  EXPECT_EQ(
      OneOf(n["expect"], "steps[].expect", {"nominal", "tilt"}, kErr).status().message(),
      "f.yaml:2: steps[].expect: 'tilted' is not one of: nominal, tilt (did you mean 'tilt'?)");
  EXPECT_EQ(OneOf(n["list"], "list", {"no", "always"}, kErr).status().message(),
            "f.yaml:3: list: '' is not one of: no, always");
}

TEST(YamlCheck, FlattenWritesOneLineValues) {
  const YAML::Node n = Parse("ekf: {gyro_noise: 0.001, gates: [1, 2]}\nname: x\nnothing: ~\n");
  std::map<std::string, std::string> flat;
  Flatten(n, "", &flat);
  EXPECT_EQ(flat.at("ekf.gyro_noise"), "0.001");
  EXPECT_EQ(flat.at("ekf.gates"), "[1, 2]");
  EXPECT_EQ(flat.at("name"), "x");
  EXPECT_EQ(flat.at("nothing"), "~");
  std::map<std::string, std::string> prefixed;
  Flatten(n["ekf"], "dl-pose", &prefixed);
  EXPECT_EQ(prefixed.at("dl-pose.gyro_noise"), "0.001");
}

TEST(YamlCheck, JoinNames) {
  EXPECT_EQ(JoinNames({"a", "b", "c"}), "a, b, c");
  EXPECT_EQ(JoinNames({"a", "b"}, " -> "), "a -> b");
  EXPECT_EQ(JoinNames({}), "");
}

}  // namespace
}  // namespace rover::yaml
