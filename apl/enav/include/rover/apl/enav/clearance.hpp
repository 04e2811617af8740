#pragma once
/// @file
/// ClearanceChecker: the approximate clearance evaluation of one rover pose over a HeightTerrain
/// (after Otsu et al., "Fast approximate clearance evaluation for rovers with articulated
/// suspension systems", J. Field Robotics 2020, as Mars 2020's ENav runs it on its best
/// candidate paths), built on core/hwconfig's contact parts and suspension layout.
///
/// Parts (rover frame, plan view): every contact part of the rover description becomes a set of
/// discs that covers it (a wheel disc as it is; a band or the body box cut into pieces no longer
/// than 0.2 m, each covered by the disc through its corners). A disc of radius r about c passes
/// when the terrain's distance field of the part's hazard class at c exceeds
///   r + planar_margin + cell_size / 2
/// (the half cell: a hazard cell's centre may lie that far inside the cell). Classes: parts with
/// clearance below the wheel step (wheels, bogie links) meet wheel hazards, the rocker links
/// rocker hazards, the body body hazards (HeightTerrain's limits).
///
/// Suspension (within ace_length along a path; the ACE part): each wheel's height is the highest
/// known mean in its contact patch (the wheel's footprint, wheel_radius x wheel_width/2 about the
/// centre); per side the bogie joins the middle and rear wheels, the rocker joins the front wheel
/// and the bogie pivot's point on the wheel line:
///   beta_s = atan2(z_M - z_R, x_M - x_R),   z_B = (z_M + z_R) / 2,
///   rho_s  = atan2(z_F - z_B, x_F - x_B),   z_P = z_B + (x_P - x_B) tan(rho_s)   (at the pivot x)
/// The differential averages the rockers: body pitch theta = (rho_L + rho_R) / 2 (nose up
/// positive here), roll phi = atan2(z_PL - z_PR, track) (left up positive); rocker angle
/// rho_s - theta, bogie angle beta_s - rho_s, each within its stop less suspension_margin; tilt
/// acos(cos theta cos phi) <= max_tilt; the belly plane z = (z_PL + z_PR)/2 + belly +
/// x tan theta + y tan phi must stay clearance_margin above every known mean under the body box.
/// Unknown wheel patches take the plane of the known ones (or the rover's own cell) and are
/// counted (CheckPath limits their share within known_length).

#include <string>
#include <vector>

#include "rover/apl/enav/height_terrain.hpp"
#include "rover/geometry/planar.hpp"

namespace rover::apl::enav {

/// A disc of a contact part (rover frame) and the hazard class it meets.
struct PartDisc {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;
  HazardLayer layer = HazardLayer::kWheel;
  int part = 0;  ///< index into the contact parts (for messages)
};

/// Hazard cells a check ignores, each for one part only: those a part touches already where
/// the rover stands (each cell of the part's hazard class within its reach plus `extra` at the
/// start pose). The rover is on them, so the map is wrong or the contact has happened; either
/// way that part must be free to move off them. Another part reaching them is checked as usual
/// (a turn in place that swings the rear wheel onto the rock beside the middle wheel fails), and
/// rocks under the belly between the wheels are not touched and stay checked.
struct Exempt {
  /// (contact part index, height-map cell index), sorted.
  std::vector<std::pair<int, std::size_t>> entries;
  /// Whether part `part` may ignore cell `k`.
  bool Contains(int part, std::size_t k) const;
  /// Whether any part may ignore cell `k`.
  bool Has(std::size_t k) const;
  bool empty() const { return entries.empty(); }
};

/// What a check found; `ok` false names the first failure.
struct PoseCheck {
  bool ok = true;
  std::string why;         ///< e.g. "wheel_lf 0.04 m from a wheel hazard", "tilt 23.1 deg"
  int unknown_wheels = 0;  ///< wheel patches without a known cell
  std::uint8_t unknown_mask = 0;  ///< bit w set: wheel w's patch unknown
  double tilt = 0.0;       ///< [rad] predicted (0 when the ACE part was not run)
};

class ClearanceChecker {
 public:
  /// `terrain` must outlive the checker. Its options give the parts, margins and limits.
  explicit ClearanceChecker(const HeightTerrain& terrain);

  /// The part discs check at `pose`, plus the suspension, tilt and belly when `ace`.
  /// Hazard cells in `exempt` (when given) do not count.
  PoseCheck CheckPose(const geometry::Pose2& pose, bool ace, const Exempt* exempt = nullptr) const;
  /// [m] The room the parts have at `pose`: the least, over the part discs, of the distance to
  /// the nearest hazard of the disc's class less its reach (radius and the check's pad).
  /// The parts check of CheckPose (nothing exempt) passes exactly where Room > 0; a route
  /// search asks Room > its margin. Negative where a part touches a hazard.
  double Room(const geometry::Pose2& pose) const;
  /// The hazard cells the parts touch at `pose`, their reach grown by `extra` [m].
  Exempt Touching(const geometry::Pose2& pose, double extra) const;
  const std::vector<PartDisc>& discs() const { return discs_; }
  const std::vector<hwconfig::ContactPart>& parts() const { return parts_; }

 private:
  // Calls f(cell index) for each hazard cell of `layer` within `reach` of site point c until f
  // returns true; returns whether it did.
  template <class F>
  bool ForHazards(HazardLayer layer, const Eigen::Vector2d& c, double reach, F f) const;
  double WheelHeight(const geometry::Pose2& pose, int wheel, bool* known) const;

  const HeightTerrain* terrain_;
  std::vector<hwconfig::ContactPart> parts_;
  std::vector<PartDisc> discs_;
  std::vector<Eigen::Vector2d> body_cells_;  ///< rover-frame sample points under the body
  double pad_ = 0.0;                         ///< planar_margin + cell / 2
};

}  // namespace rover::apl::enav
