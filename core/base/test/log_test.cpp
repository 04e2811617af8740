#include "rover/base/log.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace rover::log {
namespace {

TEST(Log, SinkReceivesFormattedFieldsAtOrAboveItsLevel) {
  Init("log-test", Level::kDebug);
  std::vector<std::string> got;
  SetSink([&](Level, std::string_view m, std::string_view f) { got.push_back(std::string(m) + "|" + std::string(f)); },
          Level::kWarning);
  Info("not for the sink");
  Warn("tilt over limit", {{"tilt_deg", 31.25}, {"limit_deg", 30}, {"who", "drive loco"}, {"ok", false}});
  SetSink(nullptr, Level::kError);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0], "tilt over limit| tilt_deg=31.25 limit_deg=30 who=\"drive loco\" ok=false");
}

TEST(Log, LevelsParseAndFilter) {
  Level l{};
  EXPECT_TRUE(ParseLevel("warn", &l));
  EXPECT_EQ(l, Level::kWarning);
  EXPECT_FALSE(ParseLevel("loud", &l));
  SetLevel(Level::kError);
  EXPECT_EQ(GetLevel(), Level::kError);
  int calls = 0;
  SetSink([&](Level, std::string_view, std::string_view) { ++calls; }, Level::kDebug);
  Warn("filtered out by the level");
  SetSink(nullptr, Level::kError);
  EXPECT_EQ(calls, 0);
  SetLevel(Level::kInfo);
}

}  // namespace
}  // namespace rover::log
