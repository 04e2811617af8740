#include "rover/sim/terrain/lander.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"
#include "rover/base/units.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace rover::sim::terrain {
namespace {

constexpr double kRampThickness = 0.04;    // [m]
constexpr double kLegWidth = 0.06;         // [m]
constexpr double kBraceWidth = 0.025;      // [m]
constexpr double kLegSplay = 0.15;         // [m] footpads this far outside the deck vertices
constexpr double kStripeLift = 0.003;      // [m] stripes float above the ramp (no z-fighting)
constexpr double kTargetClearance = 0.05;  // [m] gap kept between a target and other rocks

const Eigen::Vector3d kDeckAlbedo(0.62, 0.62, 0.64);
const Eigen::Vector3d kLegAlbedo(0.45, 0.45, 0.47);
const Eigen::Vector3d kRampAlbedo(0.85, 0.85, 0.82);
const Eigen::Vector3d kStripeAlbedo(0.05, 0.05, 0.05);

double Apothem(const LanderParams& p) { return p.deck_radius * std::cos(30.0 * kDegree); }

void AddQuad(std::vector<LanderQuad>* out, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
             const Eigen::Vector3d& c, const Eigen::Vector3d& d, const Eigen::Vector3d& albedo,
             LanderPart part, int ramp = -1, int stripe = -1) {
  LanderQuad q;
  q.corners = {a, b, c, d};
  q.albedo = albedo;
  q.part = part;
  q.ramp = ramp;
  q.stripe = stripe;
  out->push_back(q);
}

// Oriented box: centre, right-handed unit axes ex, ey, ez (ex x ey = ez), half extents.
void AddBox(std::vector<LanderQuad>* out, const Eigen::Vector3d& c, const Eigen::Vector3d& ex,
            const Eigen::Vector3d& ey, const Eigen::Vector3d& ez, const Eigen::Vector3d& half,
            const Eigen::Vector3d& albedo, LanderPart part, int ramp = -1) {
  auto p = [&](double sx, double sy, double sz) {
    return Eigen::Vector3d(c + sx * half.x() * ex + sy * half.y() * ey + sz * half.z() * ez);
  };
  AddQuad(out, p(-1, -1, 1), p(1, -1, 1), p(1, 1, 1), p(-1, 1, 1), albedo, part, ramp);
  AddQuad(out, p(-1, -1, -1), p(-1, 1, -1), p(1, 1, -1), p(1, -1, -1), albedo, part, ramp);
  AddQuad(out, p(1, -1, -1), p(1, 1, -1), p(1, 1, 1), p(1, -1, 1), albedo, part, ramp);
  AddQuad(out, p(-1, -1, -1), p(-1, -1, 1), p(-1, 1, 1), p(-1, 1, -1), albedo, part, ramp);
  AddQuad(out, p(-1, 1, -1), p(-1, 1, 1), p(1, 1, 1), p(1, 1, -1), albedo, part, ramp);
  AddQuad(out, p(-1, -1, -1), p(1, -1, -1), p(1, -1, 1), p(-1, -1, 1), albedo, part, ramp);
}

// A square beam of width w from p0 to p1.
void AddBeam(std::vector<LanderQuad>* out, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
             double w, const Eigen::Vector3d& albedo, LanderPart part) {
  const Eigen::Vector3d ez = (p1 - p0).normalized();
  const Eigen::Vector3d ref =
      std::abs(ez.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d ex = ref.cross(ez).normalized();
  const Eigen::Vector3d ey = ez.cross(ex);
  AddBox(out, 0.5 * (p0 + p1), ex, ey, ez,
         Eigen::Vector3d(0.5 * w, 0.5 * w, 0.5 * (p1 - p0).norm()), albedo, part);
}

double Cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double SegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// Horizontal ramp-local coordinates of (x, y): along (from the deck centre) and across.
void RampLocal(const Lander& l, int r, double x, double y, double* along, double* across) {
  const Eigen::Vector2d d = l.ramps[static_cast<std::size_t>(r)].direction;
  const Eigen::Vector2d rel(x - l.params.x, y - l.params.y);
  *along = rel.dot(d);
  *across = Cross2(d, rel);
}

}  // namespace

const char* LanderPartName(LanderPart p) {
  switch (p) {
    case LanderPart::kDeck:
      return "deck";
    case LanderPart::kLeg:
      return "leg";
    case LanderPart::kBrace:
      return "brace";
    case LanderPart::kRamp:
      return "ramp";
    case LanderPart::kStripe:
      return "stripe";
  }
  return "?";
}

Eigen::Vector3d LanderQuad::Normal() const {
  return (corners[1] - corners[0]).cross(corners[2] - corners[0]).normalized();
}

double LanderRamp::SlopeDeg() const {
  const double run = (bottom_center.head<2>() - top_center.head<2>()).norm();
  return std::atan2(top_center.z() - bottom_center.z(), run) / kDegree;
}

Status LanderParams::Validate() const {
  for (auto [name, v] : {std::pair<const char*, double>{"lander.x", x}, {"lander.y", y},
                         {"lander.yaw_deg", yaw_deg}}) {
    ROVER_RETURN_IF_ERROR(CheckFinite(name, v));
  }
  ROVER_RETURN_IF_ERROR(Description().Validate("lander."));
  return CheckNonNegative("lander.rock_clearance", rock_clearance, "m");
}

hwconfig::LanderDescription LanderParams::Description() const {
  hwconfig::LanderDescription d;
  d.deck_height = deck_height;
  d.deck_thickness = deck_thickness;
  d.deck_radius = deck_radius;
  d.ramp_length = ramp_length;
  d.ramp_width = ramp_width;
  d.stripe_unit = stripe_unit;
  d.stripe_gap = stripe_gap;
  return d;
}

bool Lander::InDeck(double x, double y) const {
  const Eigen::Vector2d p(x, y);
  for (std::size_t m = 0; m < 6; ++m) {
    const Eigen::Vector2d& a = deck_vertices[m];
    const Eigen::Vector2d& b = deck_vertices[(m + 1) % 6];
    if (Cross2(b - a, p - a) < 0.0) return false;
  }
  return true;
}

int Lander::RampAt(double x, double y, double* z) const {
  const double a = Apothem(params);
  for (int r = 0; r < 2; ++r) {
    double along, across;
    RampLocal(*this, r, x, y, &along, &across);
    if (along >= a && along <= a + params.ramp_length &&
        std::abs(across) <= 0.5 * params.ramp_width) {
      const LanderRamp& ramp = ramps[static_cast<std::size_t>(r)];
      if (z != nullptr) {
        *z = deck_z + (along - a) / params.ramp_length * (ramp.bottom_center.z() - deck_z);
      }
      return r;
    }
  }
  return -1;
}

double Lander::DistanceToFootprint(double x, double y) const {
  if (InDeck(x, y) || RampAt(x, y, nullptr) >= 0) return 0.0;
  const Eigen::Vector2d p(x, y);
  double best = 1e300;
  for (std::size_t m = 0; m < 6; ++m) {
    best = std::min(best, SegmentDistance(p, deck_vertices[m], deck_vertices[(m + 1) % 6]));
  }
  const double a = Apothem(params);
  for (int r = 0; r < 2; ++r) {
    double along, across;
    RampLocal(*this, r, x, y, &along, &across);
    const double dx = std::max({a - along, 0.0, along - (a + params.ramp_length)});
    const double dy = std::max(std::abs(across) - 0.5 * params.ramp_width, 0.0);
    best = std::min(best, std::hypot(dx, dy));
  }
  return best;
}

void StampLander(const Lander& l, HeightField* ground) {
  ROVER_DEMAND(ground != nullptr);
  const double reach = Apothem(l.params) + l.params.ramp_length + l.params.deck_radius;
  const double res = ground->resolution();
  const int i0 =
      std::max(0, static_cast<int>(std::floor((l.params.x - reach - ground->min_x()) / res)));
  const int i1 = std::min(
      ground->nx() - 1, static_cast<int>(std::ceil((l.params.x + reach - ground->min_x()) / res)));
  const int j0 =
      std::max(0, static_cast<int>(std::floor((l.params.y - reach - ground->min_y()) / res)));
  const int j1 = std::min(
      ground->ny() - 1, static_cast<int>(std::ceil((l.params.y + reach - ground->min_y()) / res)));
  for (int j = j0; j <= j1; ++j) {
    const double y = ground->min_y() + j * res;
    for (int i = i0; i <= i1; ++i) {
      const double x = ground->min_x() + i * res;
      double z = 0.0;
      if (l.InDeck(x, y)) {
        ground->at(i, j) = static_cast<float>(l.deck_z);
        ground->soil(i, j) = Soil::kBedrock;
      } else if (l.RampAt(x, y, &z) >= 0) {
        ground->at(i, j) = std::max(ground->at(i, j), static_cast<float>(z));
        ground->soil(i, j) = Soil::kBedrock;
      }
    }
  }
}

Status PlaceLander(Terrain* terrain, const LanderParams& p) {
  ROVER_DEMAND(terrain != nullptr);
  ROVER_RETURN_IF_ERROR(p.Validate());
  if (terrain->lander) {
    return FailedPrecondition("lander: the terrain already has a lander at (" +
                              FormatNumber(terrain->lander->params.x) + ", " +
                              FormatNumber(terrain->lander->params.y) + ")");
  }
  const HeightField& bare = terrain->bare;
  Lander l;
  l.params = p;
  const double yaw = p.yaw_deg * kDegree, a = Apothem(p);
  const Eigen::Vector2d c(p.x, p.y);
  for (int m = 0; m < 6; ++m) {
    const double ang = yaw + (30.0 + 60.0 * m) * kDegree;
    l.deck_vertices[static_cast<std::size_t>(m)] =
        c + p.deck_radius * Eigen::Vector2d(std::cos(ang), std::sin(ang));
  }
  // Footprint extent: deck vertices and ramp corners must lie on the map.
  std::vector<Eigen::Vector2d> outline(l.deck_vertices.begin(), l.deck_vertices.end());
  for (int r = 0; r < 2; ++r) {
    const Eigen::Vector2d d = (r == 0 ? 1.0 : -1.0) * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
    const Eigen::Vector2d side(-d.y(), d.x());
    l.ramps[static_cast<std::size_t>(r)].direction = d;
    for (double s : {-0.5, 0.5})
      outline.push_back(c + (a + p.ramp_length) * d + s * p.ramp_width * side);
  }
  Eigen::Vector2d lo = outline[0], hi = outline[0];
  for (const auto& q : outline) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  if (lo.x() < bare.min_x() || hi.x() > bare.max_x()) {
    return InvalidArgument(
        "lander.x: " + FormatNumber(p.x) + " puts the lander footprint (deck and ramps, x in [" +
        FormatNumber(lo.x()) + ", " + FormatNumber(hi.x()) + "]) off the map (x in [" +
        FormatNumber(bare.min_x()) + ", " + FormatNumber(bare.max_x()) + "])");
  }
  if (lo.y() < bare.min_y() || hi.y() > bare.max_y()) {
    return InvalidArgument(
        "lander.y: " + FormatNumber(p.y) + " puts the lander footprint (deck and ramps, y in [" +
        FormatNumber(lo.y()) + ", " + FormatNumber(hi.y()) + "]) off the map (y in [" +
        FormatNumber(bare.min_y()) + ", " + FormatNumber(bare.max_y()) + "])");
  }

  l.deck_z = bare.Height(p.x, p.y) + p.deck_height;
  const double deck_bottom = l.deck_z - p.deck_thickness;
  for (int r = 0; r < 2; ++r) {
    LanderRamp& ramp = l.ramps[static_cast<std::size_t>(r)];
    const Eigen::Vector2d top = c + a * ramp.direction;
    const Eigen::Vector2d foot = c + (a + p.ramp_length) * ramp.direction;
    ramp.width = p.ramp_width;
    ramp.top_center = Eigen::Vector3d(top.x(), top.y(), l.deck_z);
    ramp.bottom_center = Eigen::Vector3d(foot.x(), foot.y(), bare.Height(foot.x(), foot.y()));
    if (ramp.bottom_center.z() > l.deck_z - 0.1) {
      return InvalidArgument("lander.deck_height: " + FormatNumber(p.deck_height) +
                             " m is too low here: the ground at the foot of ramp " +
                             std::to_string(r) + " (z " + FormatNumber(ramp.bottom_center.z()) +
                             ") is not below the deck (z " + FormatNumber(l.deck_z) +
                             "); raise it or turn the lander (yaw_deg)");
    }
  }
  for (const Rock& rock : terrain->rocks) {
    if (rock.science_target &&
        l.DistanceToFootprint(rock.position.x(), rock.position.y()) < RockBoundingRadius(rock)) {
      return InvalidArgument("lander.x: the lander footprint at (" + FormatNumber(p.x) + ", " +
                             FormatNumber(p.y) + ") covers science target " +
                             std::to_string(rock.id) + " at (" + FormatNumber(rock.position.x()) +
                             ", " + FormatNumber(rock.position.y()) + ")");
    }
  }

  // Geometry for the renderer.
  std::vector<LanderQuad>& q = l.quads;
  const auto& v = l.deck_vertices;
  auto at = [](const Eigen::Vector2d& xy, double z) { return Eigen::Vector3d(xy.x(), xy.y(), z); };
  AddQuad(&q, at(v[0], l.deck_z), at(v[1], l.deck_z), at(v[2], l.deck_z), at(v[3], l.deck_z),
          kDeckAlbedo, LanderPart::kDeck);
  AddQuad(&q, at(v[3], l.deck_z), at(v[4], l.deck_z), at(v[5], l.deck_z), at(v[0], l.deck_z),
          kDeckAlbedo, LanderPart::kDeck);
  AddQuad(&q, at(v[3], deck_bottom), at(v[2], deck_bottom), at(v[1], deck_bottom),
          at(v[0], deck_bottom), kDeckAlbedo, LanderPart::kDeck);
  AddQuad(&q, at(v[0], deck_bottom), at(v[5], deck_bottom), at(v[4], deck_bottom),
          at(v[3], deck_bottom), kDeckAlbedo, LanderPart::kDeck);
  for (std::size_t m = 0; m < 6; ++m) {
    const auto& a0 = v[m];
    const auto& a1 = v[(m + 1) % 6];
    AddQuad(&q, at(a0, deck_bottom), at(a1, deck_bottom), at(a1, l.deck_z), at(a0, l.deck_z),
            kDeckAlbedo, LanderPart::kDeck);
  }
  // Truss: a leg under every vertex, splayed outwards, and X braces on every face.
  std::array<Eigen::Vector3d, 6> leg_top, leg_foot;
  for (std::size_t m = 0; m < 6; ++m) {
    const Eigen::Vector2d out = (v[m] - c).normalized();
    const Eigen::Vector2d top = v[m] - 0.5 * kLegWidth * out;
    const Eigen::Vector2d foot = v[m] + kLegSplay * out;
    leg_top[m] = at(top, deck_bottom);
    leg_foot[m] = at(foot, bare.Height(foot.x(), foot.y()));
    AddBeam(&q, leg_foot[m], leg_top[m], kLegWidth, kLegAlbedo, LanderPart::kLeg);
  }
  for (std::size_t m = 0; m < 6; ++m) {
    const std::size_t n = (m + 1) % 6;
    const Eigen::Vector3d low_m = leg_foot[m] + 0.25 * (leg_top[m] - leg_foot[m]);
    const Eigen::Vector3d low_n = leg_foot[n] + 0.25 * (leg_top[n] - leg_foot[n]);
    AddBeam(&q, low_m, leg_top[n], kBraceWidth, kLegAlbedo, LanderPart::kBrace);
    AddBeam(&q, low_n, leg_top[m], kBraceWidth, kLegAlbedo, LanderPart::kBrace);
  }
  // Ramps with their stripes.
  for (int r = 0; r < 2; ++r) {
    LanderRamp& ramp = l.ramps[static_cast<std::size_t>(r)];
    const Eigen::Vector3d side(-ramp.direction.y(), ramp.direction.x(), 0.0);
    const Eigen::Vector3d down_vec = ramp.bottom_center - ramp.top_center;
    const double slope_len = down_vec.norm();
    const Eigen::Vector3d down = down_vec / slope_len;
    const Eigen::Vector3d normal = down.cross(side).normalized();  // points up
    AddBox(&q, 0.5 * (ramp.top_center + ramp.bottom_center) - 0.5 * kRampThickness * normal, down,
           side, normal, Eigen::Vector3d(0.5 * slope_len, 0.5 * p.ramp_width, 0.5 * kRampThickness),
           kRampAlbedo, LanderPart::kRamp, r);
    const hwconfig::LanderDescription desc = p.Description();
    for (int s = 0; s < hwconfig::kStripesPerRamp; ++s) {
      const hwconfig::StripeLayout layout = desc.Stripe(r, s);
      LanderStripe& st = ramp.stripes[static_cast<std::size_t>(s)];
      st.ramp = r;
      st.index = s;
      st.code = layout.code;
      st.width = layout.width;
      st.length = layout.length;
      st.center = ramp.bottom_center - (0.5 * slope_len + layout.u) * down;
      const Eigen::Vector3d cc = st.center + kStripeLift * normal;
      const Eigen::Vector3d hw = 0.5 * st.width * down, hl = 0.5 * st.length * side;
      AddQuad(&q, cc - hw - hl, cc + hw - hl, cc + hw + hl, cc - hw + hl, kStripeAlbedo,
              LanderPart::kStripe, r, s);
    }
  }

  // Clear rocks off the footprint, then stamp.
  std::erase_if(terrain->rocks, [&](const Rock& rock) {
    return !rock.science_target && l.DistanceToFootprint(rock.position.x(), rock.position.y()) <
                                       RockBoundingRadius(rock) + p.rock_clearance;
  });
  terrain->lander = std::move(l);
  RebuildHeights(terrain);
  return Status::Ok();
}

Result<int> AddScienceTarget(Terrain* terrain, const ScienceTargetParams& t) {
  ROVER_DEMAND(terrain != nullptr);
  const HeightField& bare = terrain->bare;
  auto bad = [](const std::string& field, const std::string& what) {
    return InvalidArgument("science_target." + field + ": " + what);
  };
  if (!std::isfinite(t.x)) return bad("x", FormatNumber(t.x) + " is not a finite number");
  if (!std::isfinite(t.y)) return bad("y", FormatNumber(t.y) + " is not a finite number");
  if (!(t.diameter >= 2.0 * bare.resolution() && t.diameter <= 20.0)) {
    return bad("diameter", FormatNumber(t.diameter) + " is out of range [" +
                               FormatNumber(2.0 * bare.resolution()) +
                               ", 20] (at least two grid cells)");
  }
  if (t.texture_id < 0) return bad("texture_id", std::to_string(t.texture_id) + " must be >= 0");
  if (!(t.height >= 0.0 && t.height <= 10.0))
    return bad("height", FormatNumber(t.height) + " is out of range [0, 10]");
  if (!(t.elongation >= 1.0 && t.elongation <= 5.0)) {
    return bad("elongation", FormatNumber(t.elongation) + " is out of range [1, 5]");
  }
  if (!std::isfinite(t.yaw_deg))
    return bad("yaw_deg", FormatNumber(t.yaw_deg) + " is not a finite number");

  Rock rock;
  rock.position = Eigen::Vector3d(t.x, t.y, 0.0);
  rock.diameter = t.diameter;
  rock.height = t.height > 0.0 ? t.height : terrain->params.rocks.height_ratio * t.diameter;
  rock.science_target = true;
  rock.texture_id = t.texture_id;
  rock.yaw = t.yaw_deg * kDegree;
  rock.elongation = t.elongation;
  rock.bluntness = 0.5;
  const double br = RockBoundingRadius(rock);
  if (t.x - br < bare.min_x() || t.x + br > bare.max_x()) {
    return bad("x", FormatNumber(t.x) + ": the target (radius " + FormatNumber(br) +
                        ") is off the map (x in [" + FormatNumber(bare.min_x()) + ", " +
                        FormatNumber(bare.max_x()) + "])");
  }
  if (t.y - br < bare.min_y() || t.y + br > bare.max_y()) {
    return bad("y", FormatNumber(t.y) + ": the target (radius " + FormatNumber(br) +
                        ") is off the map (y in [" + FormatNumber(bare.min_y()) + ", " +
                        FormatNumber(bare.max_y()) + "])");
  }
  if (terrain->lander && terrain->lander->DistanceToFootprint(t.x, t.y) < br) {
    return bad("x", "the target at (" + FormatNumber(t.x) + ", " + FormatNumber(t.y) +
                        ") overlaps the lander");
  }
  for (const Rock& o : terrain->rocks) {
    if (o.science_target &&
        (o.position.head<2>() - rock.position.head<2>()).norm() < br + RockBoundingRadius(o)) {
      return bad("x", "the target at (" + FormatNumber(t.x) + ", " + FormatNumber(t.y) +
                          ") overlaps science target " + std::to_string(o.id));
    }
  }
  std::erase_if(terrain->rocks, [&](const Rock& o) {
    return !o.science_target && (o.position.head<2>() - rock.position.head<2>()).norm() <
                                    br + RockBoundingRadius(o) + kTargetClearance;
  });
  rock.position.z() = bare.Height(t.x, t.y);
  rock.id = terrain->next_rock_id++;
  terrain->rocks.push_back(rock);
  RebuildHeights(terrain);
  return rock.id;
}

// ---- scenario files ------------------------------------------------------------------------

void DeclareLanderParams(ParamSet& ps, const std::string& prefix) {
  const LanderParams d;
  auto key = [&prefix](const char* n) {
    return prefix.empty() ? std::string(n) : prefix + "." + n;
  };
  ps.Declare(key("enabled"), false, "place a lander");
  ps.Declare(key("x"), d.x, "[m] deck centre x, site frame");
  ps.Declare(key("y"), d.y, "[m] deck centre y, site frame");
  ps.Declare(key("yaw_deg"), d.yaw_deg, "[deg] direction ramp 0 descends, from +x towards +y");
  ps.Declare(key("deck_height"), d.deck_height, "[m] deck top above the ground");
  ps.Declare(key("deck_thickness"), d.deck_thickness, "[m] deck slab thickness");
  ps.Declare(key("deck_radius"), d.deck_radius, "[m] circumradius of the hexagonal deck");
  ps.Declare(key("ramp_length"), d.ramp_length, "[m] horizontal run of each ramp");
  ps.Declare(key("ramp_width"), d.ramp_width, "[m] ramp width");
  ps.Declare(key("stripe_unit"), d.stripe_unit, "[m] stripe width per code unit");
  ps.Declare(key("stripe_gap"), d.stripe_gap, "[m] gap between stripes");
  ps.Declare(key("rock_clearance"), d.rock_clearance, "[m] rocks this close are removed");
}

Result<std::optional<LanderParams>> LanderParamsFromParamSet(const ParamSet& ps,
                                                             const std::string& prefix) {
  auto key = [&prefix](const std::string& n) { return prefix.empty() ? n : prefix + "." + n; };
  if (!ps.GetBool(key("enabled"))) return std::optional<LanderParams>();
  LanderParams p;
  p.x = ps.GetDouble(key("x"));
  p.y = ps.GetDouble(key("y"));
  p.yaw_deg = ps.GetDouble(key("yaw_deg"));
  p.deck_height = ps.GetDouble(key("deck_height"));
  p.deck_thickness = ps.GetDouble(key("deck_thickness"));
  p.deck_radius = ps.GetDouble(key("deck_radius"));
  p.ramp_length = ps.GetDouble(key("ramp_length"));
  p.ramp_width = ps.GetDouble(key("ramp_width"));
  p.stripe_unit = ps.GetDouble(key("stripe_unit"));
  p.stripe_gap = ps.GetDouble(key("stripe_gap"));
  p.rock_clearance = ps.GetDouble(key("rock_clearance"));
  const Status s = p.Validate();
  if (!s.ok()) {
    // "lander.<field>: ..." -> the field's key in this ParamSet.
    const std::string& m = s.message();
    const std::string field = m.substr(7, m.find(':') - 7);
    return AtParamKey(ps, key(field), s);
  }
  return std::optional<LanderParams>(p);
}

void DeclareScienceTargets(ParamSet& ps, const std::string& key) {
  ps.Declare(key, std::vector<double>{},
             "science targets as a flat list [x, y, diameter, texture_id, ...] (4 per target)");
}

Result<std::vector<ScienceTargetParams>> ScienceTargetsFromParamSet(const ParamSet& ps,
                                                                    const std::string& key) {
  const std::vector<double>& v = ps.GetDoubleList(key);
  if (v.size() % 4 != 0) {
    return InvalidArgument(
        ps.Origin(key).ToString() + ": key '" + key + "': " + std::to_string(v.size()) +
        " numbers is not a multiple of 4 (x, y, diameter, texture_id per target)");
  }
  std::vector<ScienceTargetParams> out;
  for (std::size_t i = 0; i < v.size(); i += 4) {
    ScienceTargetParams t;
    t.x = v[i];
    t.y = v[i + 1];
    t.diameter = v[i + 2];
    if (v[i + 3] < 0 || v[i + 3] != std::floor(v[i + 3]) || v[i + 3] > 1e6) {
      return InvalidArgument(ps.Origin(key).ToString() + ": key '" + key + "': target " +
                             std::to_string(i / 4) + ": texture_id " + FormatNumber(v[i + 3]) +
                             " is not a non-negative integer");
    }
    t.texture_id = static_cast<int>(v[i + 3]);
    out.push_back(t);
  }
  return out;
}

Status PlaceScenarioObjects(Terrain* terrain, const ParamSet& ps, const std::string& lander_prefix,
                            const std::string& targets_key) {
  auto lander = LanderParamsFromParamSet(ps, lander_prefix);
  if (!lander.ok()) return lander.status();
  if (lander->has_value()) {
    const Status s = PlaceLander(terrain, **lander);
    if (!s.ok()) {
      const std::string& m = s.message();
      const std::size_t colon = m.find(':');
      std::string field = m.substr(0, colon);
      if (field.rfind("lander.", 0) == 0) field = field.substr(7);
      const std::string full = lander_prefix.empty() ? field : lander_prefix + "." + field;
      return AtParamKey(ps, ps.Has(full) ? full : lander_prefix + ".x", s);
    }
  }
  auto targets = ScienceTargetsFromParamSet(ps, targets_key);
  if (!targets.ok()) return targets.status();
  for (std::size_t i = 0; i < targets->size(); ++i) {
    auto id = AddScienceTarget(terrain, (*targets)[i]);
    if (!id.ok()) {
      return Status(id.status().code(), ps.Origin(targets_key).ToString() + ": key '" +
                                            targets_key + "': target " + std::to_string(i) + ": " +
                                            id.status().message());
    }
  }
  return Status::Ok();
}

}  // namespace rover::sim::terrain
