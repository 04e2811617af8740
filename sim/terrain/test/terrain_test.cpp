#include "rover/sim/terrain/terrain.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "rover/base/units.hpp"
#include "rover/sim/terrain/rock_model.hpp"

namespace rover::sim::terrain {
namespace {

using ::testing::HasSubstr;
TerrainParams Small(std::uint64_t seed) {
  TerrainParams p;
  p.size_x = 20;
  p.size_y = 16;
  p.seed = seed;
  return p;
}

void ExpectSameRocks(const std::vector<Rock>& a, const std::vector<Rock>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].id, b[i].id);
    EXPECT_EQ(a[i].position, b[i].position);  // bit-identical
    EXPECT_EQ(a[i].diameter, b[i].diameter);
    EXPECT_EQ(a[i].height, b[i].height);
    EXPECT_EQ(a[i].texture_id, b[i].texture_id);
    EXPECT_EQ(a[i].yaw, b[i].yaw);
    EXPECT_EQ(a[i].elongation, b[i].elongation);
    EXPECT_EQ(a[i].bluntness, b[i].bluntness);
    EXPECT_EQ(a[i].lobe_amplitude, b[i].lobe_amplitude);
  }
}

TEST(GenerateTerrain, SameSeedIsBitIdenticalDifferentSeedDiffers) {
  auto a = GenerateTerrain(Small(5));
  auto b = GenerateTerrain(Small(5));
  auto c = GenerateTerrain(Small(6));
  ASSERT_TRUE(a.ok() && b.ok() && c.ok()) << a.status().ToString();
  EXPECT_EQ(a->ground.nx(), 501);
  EXPECT_EQ(a->ground.ny(), 401);
  EXPECT_EQ(a->ground.heights(), b->ground.heights());
  EXPECT_EQ(a->ground.soils(), b->ground.soils());
  ExpectSameRocks(a->rocks, b->rocks);
  EXPECT_GT(a->rocks.size(), 100u);

  EXPECT_NE(a->ground.heights(), c->ground.heights());
  std::size_t same_height = 0;
  for (std::size_t i = 0; i < a->bare.heights().size(); ++i) {
    same_height += a->bare.heights()[i] == c->bare.heights()[i];
  }
  EXPECT_LT(same_height, a->bare.heights().size() / 100);  // a few coincidences at most
  std::size_t same_rock = 0;
  for (std::size_t i = 0; i < std::min(a->rocks.size(), c->rocks.size()); ++i) {
    same_rock += a->rocks[i].position == c->rocks[i].position;
  }
  EXPECT_EQ(same_rock, 0u);
}

TEST(GenerateTerrain, FeatureStreamsAreIndependent) {
  // Changing the rock preset must not move hills, craters or soil.
  TerrainParams p = Small(9);
  auto vl1 = GenerateTerrain(p);
  p.rocks.preset = RockPreset::kVl2;
  auto vl2 = GenerateTerrain(p);
  ASSERT_TRUE(vl1.ok() && vl2.ok());
  EXPECT_EQ(vl1->bare.heights(), vl2->bare.heights());
  EXPECT_EQ(vl1->bare.soils(), vl2->bare.soils());
  EXPECT_GT(vl2->rocks.size(), vl1->rocks.size());
}

// Least-squares plane z = a x + b y + c over the grid; returns (a, b).
Eigen::Vector2d FitPlaneGradient(const HeightField& h) {
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  for (int j = 0; j < h.ny(); j += 2) {
    for (int i = 0; i < h.nx(); i += 2) {
      const Eigen::Vector3d row(h.min_x() + i * h.resolution(), h.min_y() + j * h.resolution(), 1);
      ata += row * row.transpose();
      atb += row * h.at(i, j);
    }
  }
  const Eigen::Vector3d sol = ata.ldlt().solve(atb);
  return sol.head<2>();
}

TEST(GenerateTerrain, BaseSlopeHasTheRequestedAngleAndDirection) {
  TerrainParams p = Small(3);
  p.hills.amplitude = 0;
  p.craters.count = 0;
  p.rocks.preset = RockPreset::kNone;
  p.slope.angle_deg = 12.0;
  p.slope.uphill_direction_deg = 120.0;
  auto t = GenerateTerrain(p);
  ASSERT_TRUE(t.ok());
  Eigen::Vector2d g = FitPlaneGradient(t->ground);
  // A pure plane: exact up to float rounding of the heights.
  EXPECT_NEAR(std::atan(g.norm()) / kDegree, 12.0, 1e-3);
  EXPECT_NEAR(std::atan2(g.y(), g.x()) / kDegree, 120.0, 1e-3);

  // With the default hills and craters the fitted slope stays close. Tolerance: the hills'
  // largest octave (amplitude 0.35 m, wavelength 16 m) over a 20 m x 16 m map can tilt a
  // fitted plane by at most about 2 * 0.35 m / 16 m ~ 2.5 deg; we allow 2 deg around 8 deg and
  // 15 deg of direction (the tilt is a vector added to an 8 deg one).
  p = Small(3);
  p.slope.angle_deg = 8.0;
  p.slope.uphill_direction_deg = -45.0;
  t = GenerateTerrain(p);
  ASSERT_TRUE(t.ok());
  g = FitPlaneGradient(t->bare);
  EXPECT_NEAR(std::atan(g.norm()) / kDegree, 8.0, 2.0);
  EXPECT_NEAR(std::atan2(g.y(), g.x()) / kDegree, -45.0, 15.0);
}

TEST(GenerateTerrain, BadParamsAreErrors) {
  TerrainParams p = Small(1);
  p.size_x = -3;
  auto t = GenerateTerrain(p);
  ASSERT_FALSE(t.ok());
  EXPECT_THAT(t.status().message(), HasSubstr("size_x"));
  p = Small(1);
  p.rocks.preset = RockPreset::kCustom;
  p.rocks.k = 0.8;
  t = GenerateTerrain(p);
  ASSERT_FALSE(t.ok());
  EXPECT_THAT(t.status().message(), HasSubstr("rocks.k"));
}

TEST(GenerateTerrain, KeepOutDiscIsRockFreeAndFlat) {
  TerrainParams p = Small(17);
  p.rocks.preset = RockPreset::kImpassable;
  p.slope.angle_deg = 5;
  p.slope.uphill_direction_deg = 60;
  p.start.x = 4.0;
  p.start.y = -2.5;
  p.start.keep_out_radius = 2.5;
  auto t = GenerateTerrain(p);
  ASSERT_TRUE(t.ok()) << t.status().ToString();
  const Eigen::Vector2d s(p.start.x, p.start.y);
  for (const Rock& r : t->rocks) {
    EXPECT_GE((r.position.head<2>() - s).norm(), p.start.keep_out_radius + 0.5 * r.diameter)
        << "rock " << r.id;
  }
  // Inside the disc the ground is the base plane through the start point.
  const double g = std::tan(5 * kDegree);
  const Eigen::Vector2d up(std::cos(60 * kDegree), std::sin(60 * kDegree));
  const double z0 = t->ground.Height(s.x(), s.y());
  double worst = 0;
  int samples = 0;
  const HeightField& h = t->ground;
  for (int j = 0; j < h.ny(); ++j) {
    for (int i = 0; i < h.nx(); ++i) {
      const Eigen::Vector2d q(h.min_x() + i * h.resolution(), h.min_y() + j * h.resolution());
      if ((q - s).norm() > p.start.keep_out_radius) continue;
      worst = std::max(worst, std::abs(h.at(i, j) - (z0 + g * (q - s).dot(up))));
      ++samples;
    }
  }
  EXPECT_GT(samples, 10000);
  EXPECT_LT(worst, 1e-4);  // float rounding only
  // And the field is dense around it: the disc is the only empty place.
  EXPECT_GT(t->rocks.size(), 1500u);
}

// Cumulative fractional area of a generated field vs the Golombek-Rapp model.
void CheckSizeFrequency(RockPreset preset, std::uint64_t seed) {
  TerrainParams p;
  p.seed = seed;
  p.rocks.preset = preset;
  p.start.keep_out_radius = 0;  // measure over the whole map
  auto t = GenerateTerrain(p);
  ASSERT_TRUE(t.ok()) << t.status().ToString();
  const double area = (t->bare.max_x() - t->bare.min_x()) * (t->bare.max_y() - t->bare.min_y());
  const double k = p.rocks.EffectiveK(), d_max = p.rocks.diameter_max;
  for (double d0 : {0.1, 0.15, 0.2, 0.3, 0.5, 0.8, 1.2}) {
    double covered = 0;
    for (const Rock& r : t->rocks) {
      if (r.diameter >= d0) covered += std::numbers::pi / 4 * r.diameter * r.diameter;
    }
    const double measured = covered / area;
    const double model = RockAreaFraction(k, d0, d_max);
    // Tolerance: 3.5 standard deviations of the area fraction of a Poisson rock field of this
    // size (rock_model.hpp). Our count is fixed to the expectation, so the real spread is
    // smaller; a generator with the wrong k or q is far outside (checked below).
    const double sigma = std::sqrt(RockAreaFractionVariance(k, d0, d_max, area));
    EXPECT_NEAR(measured, model, 3.5 * sigma)
        << RockPresetName(preset) << " D >= " << d0 << " m: measured " << measured << " model "
        << model << " sigma " << sigma;
  }
}

TEST(GenerateTerrain, Vl1SizeFrequencyMatchesGolombekRapp) {
  CheckSizeFrequency(RockPreset::kVl1, 42);
}
TEST(GenerateTerrain, Vl2SizeFrequencyMatchesGolombekRapp) {
  CheckSizeFrequency(RockPreset::kVl2, 42);
}

TEST(GenerateTerrain, StatisticalToleranceHasPower) {
  // The VL-1 field must be rejected by the VL-2 model at the same tolerance.
  TerrainParams p;
  p.seed = 42;
  p.start.keep_out_radius = 0;
  auto t = GenerateTerrain(p);
  ASSERT_TRUE(t.ok());
  const double area = 50.0 * 50.0, k2 = RockPresetK(RockPreset::kVl2);
  double covered = 0;
  for (const Rock& r : t->rocks) covered += std::numbers::pi / 4 * r.diameter * r.diameter;
  const double sigma = std::sqrt(RockAreaFractionVariance(k2, 0.1, 2.0, area));
  EXPECT_GT(std::abs(covered / area - RockAreaFraction(k2, 0.1, 2.0)), 10 * sigma);
}

TEST(GenerateTerrain, RocksAreInTheHeightfieldAtTheirPositionAndHeight) {
  auto t = GenerateTerrain(Small(21));
  ASSERT_TRUE(t.ok());
  const HeightField& h = t->ground;
  int checked = 0;
  for (const Rock& r : t->rocks) {
    if (r.diameter < 0.4) continue;
    const double br = RockBoundingRadius(r);
    if (!h.Contains(r.position.x() - br, r.position.y() - br) ||
        !h.Contains(r.position.x() + br, r.position.y() + br)) {
      continue;
    }
    ++checked;
    EXPECT_EQ(r.position.z(), t->bare.Height(r.position.x(), r.position.y()));
    // At the centre the profile is within (1 - rho^2)^bluntness of its top, rho <= one cell
    // diagonal over the short semi-axis (>= 0.4 m / 2 / sqrt(1.6)): >= 0.98 H.
    const double top = h.Height(r.position.x(), r.position.y()) - r.position.z();
    EXPECT_NEAR(top, r.height, 0.03 * r.height) << "rock " << r.id;
    // Outside the footprint the rock leaves no trace (unless a neighbour is there).
    const double out_x = r.position.x() + br + 2 * h.resolution();
    if (h.Contains(out_x, r.position.y())) {
      bool neighbour = false;
      for (const Rock& o : t->rocks) {
        neighbour |= o.id != r.id && RockRelief(o, out_x, r.position.y()) > 0;
      }
      if (!neighbour) {
        EXPECT_NEAR(t->natural.Height(out_x, r.position.y()), t->bare.Height(out_x, r.position.y()),
                    1e-6);
      }
    }
  }
  EXPECT_GT(checked, 10);
  // Cells raised by rocks cover about the summed footprint area (rocks do not overlap).
  double footprint = 0;
  for (const Rock& r : t->rocks) footprint += std::numbers::pi / 4 * r.diameter * r.diameter;
  std::size_t raised = 0;
  for (std::size_t i = 0; i < h.heights().size(); ++i) {
    raised += t->natural.heights()[i] > t->bare.heights()[i] + 1e-6f;
  }
  const double raised_area = raised * h.resolution() * h.resolution();
  // Sampling a footprint on a 4 cm grid and the clipped footprints at the map edge: within 5 %.
  EXPECT_NEAR(raised_area, footprint, 0.05 * footprint);
}

TEST(GenerateTerrain, SoilFractionsAreExact) {
  TerrainParams p = Small(4);
  p.soil.sand_fraction = 0.2;
  p.soil.bedrock_fraction = 0.1;
  auto t = GenerateTerrain(p);
  ASSERT_TRUE(t.ok());
  std::size_t sand = 0, bed = 0;
  for (Soil s : t->bare.soils()) {
    sand += s == Soil::kLooseSand;
    bed += s == Soil::kBedrock;
  }
  const double n = static_cast<double>(t->bare.soils().size());
  EXPECT_NEAR(sand / n, 0.2, 1e-4);
  EXPECT_NEAR(bed / n, 0.1, 1e-4);
  // Patches, not salt and pepper: most sand cells have a sand neighbour on the right.
  std::size_t pairs = 0;
  for (int j = 0; j < t->bare.ny(); ++j) {
    for (int i = 0; i + 1 < t->bare.nx(); ++i) {
      pairs += t->bare.soil(i, j) == Soil::kLooseSand && t->bare.soil(i + 1, j) == Soil::kLooseSand;
    }
  }
  EXPECT_GT(pairs, 0.95 * sand);
}

TEST(GenerateTerrain, CratersAreDepressionsWithRims) {
  TerrainParams p = Small(8);
  p.hills.amplitude = 0;
  p.rocks.preset = RockPreset::kNone;
  p.craters.count = 1;
  p.craters.diameter_min = 6;
  p.craters.diameter_max = 6;
  p.start.keep_out_radius = 0;
  p.start.blend_width = 0;
  auto t = GenerateTerrain(p);
  ASSERT_TRUE(t.ok());
  ASSERT_EQ(t->craters.size(), 1u);
  const Crater& c = t->craters[0];
  EXPECT_DOUBLE_EQ(c.diameter, 6.0);
  EXPECT_NEAR(CraterRelief(c, c.center.x(), c.center.y()), -c.depth, 1e-12);
  EXPECT_NEAR(CraterRelief(c, c.center.x() + 3.0, c.center.y()), c.rim_height, 1e-12);
  EXPECT_EQ(CraterRelief(c, c.center.x() + 9.5, c.center.y()), 0.0);
  if (t->bare.Contains(c.center.x(), c.center.y())) {
    EXPECT_NEAR(t->bare.Height(c.center.x(), c.center.y()), -c.depth, 1e-3);
  }
  EXPECT_GT(c.depth, 0.6 * 0.15 * 6 - 1e-9);
}

TEST(RockShape, OutlineBoundsAndArea) {
  Rock r;
  r.position = Eigen::Vector3d(1, 2, 0.5);
  r.diameter = 0.8;
  r.height = 0.4;
  r.elongation = 1.4;
  r.yaw = 0.7;
  r.lobe_amplitude = 0.1;
  r.lobe_phase = 1.0;
  EXPECT_DOUBLE_EQ(RockRelief(r, 1, 2), 0.4);
  double area = 0;
  const double step = 0.002, br = RockBoundingRadius(r);
  for (double x = 1 - br; x <= 1 + br; x += step) {
    for (double y = 2 - br; y <= 2 + br; y += step) {
      if (RockRelief(r, x, y) > 0) area += step * step;
    }
  }
  EXPECT_NEAR(area, std::numbers::pi / 4 * 0.64, 0.005);  // footprint area is pi D^2 / 4
  for (const auto& q : RockOutline(r, 36)) {
    EXPECT_LE((q - Eigen::Vector2d(1, 2)).norm(), br + 1e-12);
    EXPECT_NEAR(RockRelief(r, q.x(), q.y()), 0.0, 1e-6);
  }
}

}  // namespace
}  // namespace rover::sim::terrain
