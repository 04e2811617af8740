#include "rover/apl/gestalt/fov_edge.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rover::apl::gestalt {
namespace {

// Masks drawn as strings, one per row: '#' used, '.' not.
std::vector<std::uint8_t> Mask(const std::vector<std::string>& rows) {
  std::vector<std::uint8_t> m;
  for (const auto& r : rows) {
    for (char c : r) m.push_back(c == '#' ? 1 : 0);
  }
  return m;
}
std::vector<std::string> Draw(int w, const std::vector<std::uint8_t>& edge,
                              const std::vector<std::uint8_t>& used) {
  std::vector<std::string> rows;
  for (std::size_t k = 0; k < edge.size(); ++k) {
    if (k % static_cast<std::size_t>(w) == 0) rows.emplace_back();
    rows.back() += edge[k] ? 'E' : (used[k] ? '#' : '.');
  }
  return rows;
}

TEST(FovEdge, OutlineOfAFootprintWithAHole) {
  // A trapezoid footprint (far edge at the top, as a downward-looking camera sees the ground)
  // with a hole (a rock's shadow) inside it.
  const std::vector<std::string> in = {
      "..........", "...####...", "..######..", ".###..###.", ".########.", "##########",
  };
  const auto used = Mask(in);
  std::vector<std::uint8_t> edge;
  FindFovEdgePixels(10, 6, used, 1, &edge);
  const std::vector<std::string> want = {
      "..........", "...EEEE...", "..E####E..", ".E##..##E.", ".E######E.", "EEEEEEEEEE",
  };
  EXPECT_EQ(Draw(10, edge, used), want);
}

TEST(FovEdge, BandWidensTheEdgeInward) {
  std::vector<std::uint8_t> used(8 * 6, 1);
  std::vector<std::uint8_t> edge;
  FindFovEdgePixels(8, 6, used, 2, &edge);
  const std::vector<std::string> want = {
      "EEEEEEEE", "EEEEEEEE", "EE####EE", "EE####EE", "EEEEEEEE", "EEEEEEEE",
  };
  EXPECT_EQ(Draw(8, edge, used), want);
}

TEST(FovEdge, NoBandNoEdgeAndEmptyMasks) {
  std::vector<std::uint8_t> used(4 * 4, 1), edge;
  FindFovEdgePixels(4, 4, used, 0, &edge);
  for (auto e : edge) EXPECT_EQ(e, 0);
  std::vector<std::uint8_t> none(4 * 4, 0);
  FindFovEdgePixels(4, 4, none, 3, &edge);
  for (auto e : edge) EXPECT_EQ(e, 0);
}

}  // namespace
}  // namespace rover::apl::gestalt
