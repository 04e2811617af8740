#include "rover/deploy/seq_commands.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace rover::deploy {
namespace {

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(SeqRun, BuildsTheTextAndItsOverrides) {
  SeqRunArgs a;
  a.file = WriteFile("approach.seq", "TARGET target = (6, 0, 0)\nVISODOM TURN TO target\n");
  a.sets = {"target=(5.2, 0.4, 0)", "coarse_step= 20 cm"};
  Result<msg::SequenceCommand> c = BuildSequenceCommand(a, 77);
  ASSERT_TRUE(c.ok()) << c.status().message();
  EXPECT_EQ(c->command_id, 77u);
  EXPECT_EQ(c->text, "TARGET target = (6, 0, 0)\nVISODOM TURN TO target\n");
  EXPECT_EQ(c->overrides, "coarse_step = 20 cm\ntarget = (5.2, 0.4, 0)\n");
}

TEST(SeqRun, BadInputIsNamedAndNothingIsBuilt) {
  SeqRunArgs a;
  a.file = "/nonexistent/x.seq";
  EXPECT_EQ(BuildSequenceCommand(a, 1).status().message(), "seq run: cannot read '/nonexistent/x.seq'");
  a.file = WriteFile("ok.seq", "STOP\n");
  a.sets = {"target"};
  EXPECT_EQ(BuildSequenceCommand(a, 1).status().message(), "seq run: --set 'target' is not name=value");
  a.sets = {"a b=1"};
  EXPECT_NE(BuildSequenceCommand(a, 1).status().message().find("'a b' is not a word"), std::string::npos);
  a.sets = {"x=" + std::string(1100, '1')};
  EXPECT_NE(BuildSequenceCommand(a, 1).status().message().find("carries at most 1023"), std::string::npos);
  a.sets.clear();
  a.file = WriteFile("long.seq", std::string(5000, '#'));
  EXPECT_NE(BuildSequenceCommand(a, 1).status().message().find("5000 bytes"), std::string::npos);
}

TEST(SeqRun, NoSequencerOnTheDomainSendsNothing) {
  SeqRunArgs a;
  a.file = WriteFile("stop.seq", "STOP\n");
  a.discovery_s = 0.3;
  std::ostringstream out, err;
  EXPECT_EQ(RunSeqRun(231, a, out, err), 3);
  EXPECT_NE(err.str().find("no apl-sequencer on domain 231"), std::string::npos) << err.str();
  EXPECT_TRUE(out.str().empty());
}

}  // namespace
}  // namespace rover::deploy
