#include "rover/apl/sequencer/command_table.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "rover/apl/sequencer/units.hpp"

namespace rover::apl::sequencer {
namespace {

TEST(CommandTable, RowsAreInKindOrderWithUniqueNames) {
  std::set<std::string_view> names;
  for (std::size_t i = 0; i < CommandTable().size(); ++i) {
    const CommandSpec& c = CommandTable()[i];
    EXPECT_EQ(static_cast<std::size_t>(c.kind), i) << c.name;
    EXPECT_TRUE(names.insert(c.name).second) << "duplicate " << c.name;
    EXPECT_EQ(&SpecOf(c.kind), &c);
    EXPECT_EQ(FindCommand(c.name), &c);
  }
  EXPECT_EQ(FindCommand("DRIVE"), nullptr);
  EXPECT_EQ(FindCommand("drive arc"), nullptr);  // the parser upper-cases first
  EXPECT_EQ(MaxCommandWords(), 3);               // VISODOM TURN TO
}

TEST(CommandTable, CoversEveryDrivingModeAndFamily) {
  // Seed 000 Table 2's eight modes, the guarded arc, long traverse, stop and clear-fault; the
  // mast, rendezvous and arm commands.
  for (const char* name :
       {"DRIVE ARC", "DRIVE STRAIGHT", "TURN", "TURN TO", "VISODOM ARC", "VISODOM STRAIGHT",
        "VISODOM TURN", "VISODOM TURN TO", "GOTO", "VISODOM GOTO", "GUARDED", "GUARDED VISODOM",
        "GUARDED ARC", "AUTONAV", "AUTONAV VISODOM", "LONG_TRAVERSE", "STOP", "CLEAR_FAULT",
        "MAST", "MAST LOOK_AT", "RETURN_TO_LANDER", "APPROACH_TARGET", "ARM MOVE", "ARM PLACE",
        "ARM STOW", "ARM UNSTOW", "AUTOFOCUS"}) {
    EXPECT_NE(FindCommand(name), nullptr) << name;
  }
  EXPECT_EQ(FindCommand("MAST")->family, Family::kMast);
  EXPECT_EQ(FindCommand("APPROACH_TARGET")->family, Family::kRendezvous);
  EXPECT_EQ(FindCommand("AUTOFOCUS")->family, Family::kArm);
  EXPECT_EQ(FindCommand("GUARDED ARC")->family, Family::kMobility);
}

TEST(CommandTable, EveryRowIsConsistent) {
  for (const CommandSpec& c : CommandTable()) {
    SCOPED_TRACE(std::string(c.name));
    ASSERT_FALSE(c.args.empty());
    EXPECT_EQ(c.args.back().name, kOnFaultArg);
    if (!c.positional.empty()) {
      EXPECT_NE(c.FindArg(c.positional), nullptr);
    }
    std::map<std::string_view, int> groups;
    for (const ArgSpec& a : c.args) {
      SCOPED_TRACE(std::string(a.name));
      (void)DeclaredUnit(a.unit);  // aborts on a unit the language does not know
      if (!a.one_of.empty()) {
        ++groups[a.one_of];
        EXPECT_FALSE(a.required);
      }
      if (!a.needs.empty()) {
        EXPECT_NE(c.FindArg(a.needs), nullptr);
      }
      if (!a.required && (a.type == ArgType::kNumber || a.type == ArgType::kInteger)) {
        EXPECT_TRUE(a.bounds.Contains(a.default_value)) << a.default_value;
      }
      if (a.type == ArgType::kWord) {
        EXPECT_NE(std::find(a.choices.begin(), a.choices.end(), a.default_word),
                  a.choices.end());
      }
      if (a.type == ArgType::kTuple) {
        EXPECT_GT(a.size, 0);
      }
      for (char ch : a.name) EXPECT_FALSE(std::isupper(static_cast<unsigned char>(ch)));
    }
    for (const auto& [g, n] : groups) EXPECT_GE(n, 2) << "one-of group " << g;
  }
}

TEST(CommandTable, ArgumentsCarryUnitsAndRanges) {
  const CommandSpec& arc = *FindCommand("DRIVE ARC");
  ASSERT_NE(arc.FindArg("curvature"), nullptr);
  EXPECT_EQ(arc.FindArg("curvature")->unit, "1/m");
  EXPECT_TRUE(arc.FindArg("curvature")->required);
  EXPECT_EQ(arc.FindArg("distance")->unit, "m");
  EXPECT_FALSE(arc.FindArg("distance")->bounds.Contains(50.5));
  EXPECT_FALSE(arc.FindArg("speed")->required);
  const CommandSpec& approach = *FindCommand("APPROACH_TARGET");
  EXPECT_DOUBLE_EQ(approach.FindArg("standoff")->default_value, 1.05);
  EXPECT_EQ(approach.FindArg("pixel")->one_of, "designation");
  EXPECT_EQ(approach.FindArg("pixel")->needs, "image");
  EXPECT_EQ(arc.ArgNames(), (std::vector<std::string>{"curvature", "distance", "speed",
                                                      "timeout", "on_fault"}));
}

TEST(CommandTable, DesignPageListsEveryCommand) {
  std::ifstream in(std::string(ROVER_SOURCE_DIR) + "/apl/sequencer/README.md");
  ASSERT_TRUE(in) << "apl/sequencer/README.md";
  std::stringstream text;
  text << in.rdbuf();
  for (const CommandSpec& c : CommandTable()) {
    EXPECT_NE(text.str().find("`" + std::string(c.name)), std::string::npos)
        << c.name << " is missing from the design page's command table";
    for (const ArgSpec& a : c.args) {
      if (a.name == kOnFaultArg) continue;
      EXPECT_NE(text.str().find(std::string(a.name)), std::string::npos) << a.name;
    }
  }
}

}  // namespace
}  // namespace rover::apl::sequencer
