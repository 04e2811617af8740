#include "rover/apl/enav/clearance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rover/base/format.hpp"

namespace rover::apl::enav {
namespace {

constexpr double kPiece = 0.2;  // [m] longest side of a box piece covered by one disc

const char* LayerName(HazardLayer l) {
  switch (l) {
    case HazardLayer::kWheel: return "wheel";
    case HazardLayer::kRocker: return "rocker";
    case HazardLayer::kBody: return "body";
  }
  return "?";
}

}  // namespace

ClearanceChecker::ClearanceChecker(const HeightTerrain& terrain) : terrain_(&terrain) {
  const EnavOptions& o = terrain.options();
  parts_ = o.contact_parts.empty() ? o.rover.ContactParts() : o.contact_parts;
  pad_ = o.planar_margin + 0.5 * o.cell_size;
  for (int p = 0; p < static_cast<int>(parts_.size()); ++p) {
    const hwconfig::ContactPart& part = parts_[static_cast<std::size_t>(p)];
    HazardLayer layer = HazardLayer::kBody;
    if (part.clearance <= terrain.limit(HazardLayer::kWheel)) {
      layer = HazardLayer::kWheel;
    } else if (part.name.rfind("rocker", 0) == 0) {
      layer = HazardLayer::kRocker;
    }
    if (part.is_disc) {
      discs_.push_back({part.centre, part.radius, layer, p});
      continue;
    }
    const Eigen::Vector2d size = part.max - part.min;
    const int nx = std::max(1, static_cast<int>(std::ceil(size.x() / kPiece)));
    const int ny = std::max(1, static_cast<int>(std::ceil(size.y() / kPiece)));
    const Eigen::Vector2d piece(size.x() / nx, size.y() / ny);
    for (int a = 0; a < nx; ++a) {
      for (int b = 0; b < ny; ++b) {
        const Eigen::Vector2d c = part.min + Eigen::Vector2d((a + 0.5) * piece.x(),
                                                              (b + 0.5) * piece.y());
        discs_.push_back({c, 0.5 * piece.norm(), layer, p});
      }
    }
    if (part.name == "body") {
      const double step = o.cell_size;
      for (double x = part.min.x() + 0.5 * step; x < part.max.x(); x += step) {
        for (double y = part.min.y() + 0.5 * step; y < part.max.y(); y += step) {
          body_cells_.emplace_back(x, y);
        }
      }
    }
  }
}

double ClearanceChecker::WheelHeight(const geometry::Pose2& pose, int wheel, bool* known) const {
  const EnavOptions& o = terrain_->options();
  const nav_core::HeightMap& m = *terrain_->height_map();
  const Eigen::Vector3d c = o.rover.WheelCentre(wheel);
  const double hx = o.rover.wheel_radius, hy = 0.5 * o.rover.wheel_width;
  double best = -1e9;
  *known = false;
  for (double dx = -hx; dx <= hx + 1e-9; dx += o.cell_size) {
    for (double dy = -hy; dy <= hy + 1e-9; dy += o.cell_size) {
      const Eigen::Vector2d p = pose.ToSite({c.x() + dx, c.y() + dy});
      int i = 0, j = 0;
      m.CellOf(p.x(), p.y(), &i, &j);
      if (!m.Contains(i, j)) continue;
      const std::size_t k = m.Index(i, j);
      if (m.count[k] == 0) continue;
      *known = true;
      best = std::max(best, static_cast<double>(m.z_mean[k]));
    }
  }
  return best;
}

bool Exempt::Contains(int part, std::size_t k) const {
  return std::binary_search(entries.begin(), entries.end(), std::make_pair(part, k));
}

bool Exempt::Has(std::size_t k) const {
  return std::any_of(entries.begin(), entries.end(), [k](const auto& e) { return e.second == k; });
}

template <class F>
bool ClearanceChecker::ForHazards(HazardLayer layer, const Eigen::Vector2d& c, double reach,
                                  F f) const {
  const nav_core::HeightMap& m = *terrain_->height_map();
  static constexpr std::uint8_t kBit[3] = {nav_core::kHazardWheel, nav_core::kHazardRocker,
                                           nav_core::kHazardBody};
  const std::uint8_t bit = kBit[static_cast<int>(layer)];
  int i0 = 0, j0 = 0, i1 = 0, j1 = 0;
  m.CellOf(c.x() - reach, c.y() - reach, &i0, &j0);
  m.CellOf(c.x() + reach, c.y() + reach, &i1, &j1);
  const double r2 = reach * reach;
  for (int j = std::max(0, j0); j <= std::min(m.height - 1, j1); ++j) {
    for (int i = std::max(0, i0); i <= std::min(m.width - 1, i1); ++i) {
      const std::size_t k = m.Index(i, j);
      if ((m.hazard[k] & bit) == 0) continue;
      if ((m.CellCenter(i, j) - c).squaredNorm() > r2) continue;
      if (f(k)) return true;
    }
  }
  return false;
}

Exempt ClearanceChecker::Touching(const geometry::Pose2& pose, double extra) const {
  Exempt e;
  for (const PartDisc& d : discs_) {
    const Eigen::Vector2d c = pose.ToSite(d.centre);
    if (terrain_->DistanceAt(d.layer, c) > d.radius + pad_ + extra) continue;
    ForHazards(d.layer, c, d.radius + pad_ + extra, [&](std::size_t k) {
      e.entries.emplace_back(d.part, k);
      return false;
    });
  }
  std::sort(e.entries.begin(), e.entries.end());
  e.entries.erase(std::unique(e.entries.begin(), e.entries.end()), e.entries.end());
  return e;
}

double ClearanceChecker::Room(const geometry::Pose2& pose) const {
  double room = std::numeric_limits<double>::infinity();
  for (const PartDisc& d : discs_) {
    room = std::min(room, static_cast<double>(terrain_->DistanceAt(d.layer, pose.ToSite(d.centre))) -
                              d.radius - pad_);
  }
  return room;
}

PoseCheck ClearanceChecker::CheckPose(const geometry::Pose2& pose, bool ace,
                                      const Exempt* exempt) const {
  PoseCheck r;
  for (const PartDisc& d : discs_) {
    const Eigen::Vector2d c = pose.ToSite(d.centre);
    const double dist = terrain_->DistanceAt(d.layer, c);
    if (dist <= d.radius + pad_ &&
        (exempt == nullptr || exempt->empty() ||
         ForHazards(d.layer, c, d.radius + pad_,
                    [&](std::size_t k) { return !exempt->Contains(d.part, k); }))) {
      r.ok = false;
      r.why = parts_[static_cast<std::size_t>(d.part)].name + " " +
              FormatNumber(std::max(0.0, dist - d.radius), 2) + " m from a " +
              LayerName(d.layer) + " hazard";
      return r;
    }
  }
  if (!ace) return r;
  const EnavOptions& o = terrain_->options();
  const hwconfig::RoverDescription& rd = o.rover;
  // Wheel heights; unknown patches take the mean of the known ones.
  double z[hwconfig::kNumWheels];
  bool known[hwconfig::kNumWheels];
  double sum = 0.0;
  int n = 0;
  for (int w = 0; w < hwconfig::kNumWheels; ++w) {
    z[w] = WheelHeight(pose, w, &known[w]);
    if (known[w]) {
      sum += z[w];
      n += 1;
    } else {
      r.unknown_wheels += 1;
      r.unknown_mask |= static_cast<std::uint8_t>(1U << w);
    }
  }
  if (n == 0) return r;  // nothing known under the wheels: only the parts check applies
  for (int w = 0; w < hwconfig::kNumWheels; ++w) {
    if (!known[w]) z[w] = sum / n;
  }
  const double x_f = rd.front_wheel_x, x_m = rd.middle_wheel_x, x_r = rd.rear_wheel_x;
  const double x_b = 0.5 * (x_m + x_r), x_p = rd.rocker_pivot_x;
  double rho[2], beta[2], zp[2];
  for (int side = 0; side < 2; ++side) {
    const int base = side == 0 ? 0 : 3;  // LF LM LR, RF RM RR
    const double zf = z[base], zm = z[base + 1], zr = z[base + 2];
    beta[side] = std::atan2(zm - zr, x_m - x_r);
    const double zb = 0.5 * (zm + zr);
    rho[side] = std::atan2(zf - zb, x_f - x_b);
    zp[side] = zb + (x_p - x_b) * std::tan(rho[side]);
  }
  const double pitch = 0.5 * (rho[0] + rho[1]);
  const double roll = std::atan2(zp[0] - zp[1], rd.Track());
  for (int side = 0; side < 2; ++side) {
    const double rocker = rho[side] - pitch, bogie = beta[side] - rho[side];
    if (std::abs(rocker) > rd.rocker_limit - o.suspension_margin) {
      r.ok = false;
      r.why = std::string(side == 0 ? "left" : "right") + " rocker at " +
              FormatNumber(rocker / kDegree, 3) + " deg";
      return r;
    }
    if (std::abs(bogie) > rd.bogie_limit - o.suspension_margin) {
      r.ok = false;
      r.why = std::string(side == 0 ? "left" : "right") + " bogie at " +
              FormatNumber(bogie / kDegree, 3) + " deg";
      return r;
    }
  }
  r.tilt = std::acos(std::clamp(std::cos(pitch) * std::cos(roll), -1.0, 1.0));
  if (r.tilt > o.max_tilt) {
    r.ok = false;
    r.why = "tilt " + FormatNumber(r.tilt / kDegree, 3) + " deg";
    return r;
  }
  const nav_core::HeightMap& m = *terrain_->height_map();
  const double z0 = 0.5 * (zp[0] + zp[1]) + rd.BellyClearance() - o.clearance_margin;
  const double tp = std::tan(pitch), tr = std::tan(roll);
  for (const Eigen::Vector2d& b : body_cells_) {
    const Eigen::Vector2d p = pose.ToSite(b);
    int i = 0, j = 0;
    m.CellOf(p.x(), p.y(), &i, &j);
    if (!m.Contains(i, j)) continue;
    const std::size_t k = m.Index(i, j);
    if (m.count[k] == 0) continue;
    const double belly = z0 + b.x() * tp + b.y() * tr;
    if (m.z_mean[k] > belly) {
      r.ok = false;
      r.why = "belly " + FormatNumber(m.z_mean[k] - belly + o.clearance_margin, 2) +
              " m into the ground at rover (" + FormatNumber(b.x(), 2) + ", " +
              FormatNumber(b.y(), 2) + ")";
      return r;
    }
  }
  return r;
}

}  // namespace rover::apl::enav
