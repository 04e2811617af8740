// Steps 5-7: steep regions, discontinuities above the body clearance, missing data, blocked
// cells; the border; the safe rest.
#include <gtest/gtest.h>

#include <cmath>

#include "rover/apl/roaman/traversability.hpp"
#include "scenes.hpp"

namespace rover::apl::roaman {
namespace {

struct Classified {
  ElevationMap elevation;
  Layer<CellClass> cls;
  Layer<float> step;
};

Classified Classify(const sim::terrain::HeightField& f, int w, int h, const RoamanOptions& o,
                    const Layer<std::uint8_t>& blocked = {}) {
  Classified c;
  c.elevation = testing::SampledElevation(f, testing::CellGeometry(w, h));
  const NormalMap n = FitNormals(c.elevation, o);
  const RegionMap r = GrowRegions(c.elevation, n, o);
  MarkHazards(c.elevation, n, r, blocked, o, &c.cls, &c.step);
  return c;
}

int Count(const Layer<CellClass>& cls, CellClass k) {
  int n = 0;
  for (const CellClass c : cls.values()) n += c == k;
  return n;
}

// A ramp of `deg` degrees for 1 m <= x < 2 m, flat elsewhere.
sim::terrain::HeightField Ramp(double deg) {
  const double t = std::tan(deg * kDegree);
  return testing::HeightFieldOf(-0.5, -0.5, 3.5, 2.5, 0.01, [t](double x, double) {
    return t * std::clamp(x - 1.0, 0.0, 1.0);
  });
}

TEST(Hazards, SteepRegionsAreHazardsGentleOnesAreNot) {
  const RoamanOptions o;  // FIDO: 45°
  const Classified steep = Classify(Ramp(50.0), 60, 40, o);
  EXPECT_EQ(steep.cls.at(30, 20), CellClass::kSteep);  // mid-ramp
  EXPECT_EQ(steep.cls.at(5, 20), CellClass::kSafe);
  EXPECT_EQ(steep.cls.at(55, 20), CellClass::kSafe);
  const Classified gentle = Classify(Ramp(30.0), 60, 40, o);
  EXPECT_EQ(Count(gentle.cls, CellClass::kSteep), 0);
  EXPECT_EQ(Count(gentle.cls, CellClass::kStep), 0);
  RoamanOptions strict = o;
  strict.max_slope = 25.0 * kDegree;
  EXPECT_EQ(Classify(Ramp(30.0), 60, 40, strict).cls.at(30, 20), CellClass::kSteep);
}

TEST(Hazards, SmallSteepPatchesAreLeftToTheStepTest) {
  // A wedge: a 50° face 0.25 m long and 0.4 m wide, at most 0.3 m high (below the 0.35 m body
  // clearance). With 15 cm plane fits its face is a region of 3 x 6 cells (0.045 m^2), smaller
  // than min_steep_area.
  const double t = std::tan(50.0 * kDegree);
  const sim::terrain::HeightField f =
      testing::HeightFieldOf(-0.5, -0.5, 3.5, 2.5, 0.01, [t](double x, double y) {
        return (x >= 1.0 && x <= 1.25 && std::abs(y - 1.0) < 0.2) ? t * (x - 1.0) : 0.0;
      });
  RoamanOptions o;
  o.normal_window = 0.15;
  const Classified c = Classify(f, 60, 40, o);
  EXPECT_EQ(c.cls.at(22, 20), CellClass::kSafe);  // (1.125, 1.025): mid-face
  EXPECT_EQ(Count(c.cls, CellClass::kSteep), 0);
  EXPECT_EQ(Count(c.cls, CellClass::kStep), 0);
  RoamanOptions tiny = o;
  tiny.min_steep_area = 0.02;
  EXPECT_EQ(Classify(f, 60, 40, tiny).cls.at(22, 20), CellClass::kSteep);
}

TEST(Hazards, DiscontinuitiesAboveTheBodyClearance) {
  // Rocks on flat ground: 0.5 m tall (> 0.35 m belly clearance) and 0.2 m tall.
  sim::terrain::HeightField f = testing::FlatGround(-0.5, -0.5, 3.5, 2.5, 0.01);
  testing::AddRock(&f, 0.8, 1.0, 0.8, 0.5);
  testing::AddRock(&f, 2.3, 1.0, 0.5, 0.2);
  const RoamanOptions o;
  const Classified c = Classify(f, 60, 40, o);
  int tall = 0, low = 0;
  for (int j = 0; j < 40; ++j) {
    for (int i = 0; i < 60; ++i) {
      const Eigen::Vector2d p = c.elevation.geometry.Center(i, j);
      const bool hazard = c.cls.at(i, j) == CellClass::kStep || c.cls.at(i, j) == CellClass::kSteep;
      if ((p - Eigen::Vector2d(0.8, 1.0)).norm() < 0.45) tall += hazard;
      if ((p - Eigen::Vector2d(2.3, 1.0)).norm() < 0.3) low += hazard;
    }
  }
  EXPECT_GT(tall, 20);
  EXPECT_EQ(low, 0);
  // The step height is the rise within the baseline: above the clearance on the tall rock's
  // flank (0.39 m 15 cm in from its rim), small on its rounded top, 0 on the flat.
  float flank = 0.0f;
  for (std::size_t k = 0; k < c.step.size(); ++k) {
    if (!std::isnan(c.step[k])) flank = std::max(flank, c.step[k]);
  }
  EXPECT_GT(flank, 0.35f);
  int ti = 0, tj = 0;
  c.elevation.geometry.CellOf(0.8, 1.0, &ti, &tj);
  EXPECT_LT(c.step.at(ti, tj), 0.2);
  EXPECT_NEAR(c.step.at(2, 2), 0.0, 1e-6);
  RoamanOptions low_belly = o;
  low_belly.body_clearance = 0.1;
  int now_low = 0;
  const Classified d = Classify(f, 60, 40, low_belly);
  for (int j = 0; j < 40; ++j) {
    for (int i = 0; i < 60; ++i) {
      const Eigen::Vector2d p = d.elevation.geometry.Center(i, j);
      if ((p - Eigen::Vector2d(2.3, 1.0)).norm() < 0.3)
        now_low += d.cls.at(i, j) == CellClass::kStep;
    }
  }
  EXPECT_GT(now_low, 0);
}

TEST(Hazards, MissingDataAndBlockedCells) {
  const sim::terrain::HeightField f = testing::FlatGround(-0.5, -0.5, 2.0, 2.0, 0.01);
  ElevationMap m = testing::SampledElevation(f, testing::CellGeometry(20, 20));
  for (int j = 0; j < 20; ++j) {
    for (int i = 8; i < 12; ++i) m.source.at(i, j) = HeightSource::kNone;
  }
  // A 2 x 2 hole (0.01 m^2 < min_missing_area 0.04 m^2) is too small to be a hazard.
  for (int j = 14; j < 16; ++j) {
    for (int i = 3; i < 5; ++i) m.source.at(i, j) = HeightSource::kNone;
  }
  const RoamanOptions o;
  const NormalMap n = FitNormals(m, o);
  const RegionMap r = GrowRegions(m, n, o);
  Layer<std::uint8_t> blocked(20, 20, 0);
  blocked.at(15, 15) = 1;
  Layer<CellClass> cls;
  Layer<float> step;
  MarkHazards(m, n, r, blocked, o, &cls, &step);
  EXPECT_EQ(cls.at(9, 5), CellClass::kMissing);
  EXPECT_TRUE(std::isnan(step.at(9, 5)));
  EXPECT_EQ(cls.at(15, 15), CellClass::kBlocked);
  EXPECT_EQ(cls.at(3, 3), CellClass::kSafe);
  EXPECT_EQ(cls.at(3, 14), CellClass::kSafe);
  EXPECT_TRUE(std::isnan(step.at(3, 14)));
  EXPECT_TRUE(IsHazard(CellClass::kMissing));
  EXPECT_FALSE(IsHazard(CellClass::kBorder));
  EXPECT_STREQ(CellClassName(CellClass::kSteep), "steep slope");
}

TEST(Hazards, BorderGrowsAroundHazardsOnly) {
  Layer<CellClass> cls(21, 21, CellClass::kSafe);
  cls.at(10, 10) = CellClass::kStep;
  cls.at(0, 0) = CellClass::kBorder;  // a border is no hazard: nothing grows from it
  const int n = GrowBorder(&cls, 3.0);
  // Cells within 3 cells (centre to centre) of (10, 10): 29 in the disc, less the hazard.
  EXPECT_EQ(n, 28);
  EXPECT_EQ(cls.at(10, 10), CellClass::kStep);
  EXPECT_EQ(cls.at(13, 10), CellClass::kBorder);
  EXPECT_EQ(cls.at(12, 12), CellClass::kBorder);  // 2.83 cells away
  EXPECT_EQ(cls.at(13, 11), CellClass::kSafe);    // 3.16 cells away
}

}  // namespace
}  // namespace rover::apl::roaman
