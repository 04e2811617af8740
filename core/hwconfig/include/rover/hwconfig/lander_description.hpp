#pragma once
/// @file
/// The lander the rover returns to, as the rover knows it: dimensions and the coded stripes on
/// its two ramps. The simulator builds its lander from this description (sim/terrain) and the
/// rendezvous (apl/rendezvous) recognises it from the same one, so the two cannot drift apart.
///
/// Geometry. A hexagonal deck (circumradius `deck_radius`, top `deck_height` above the ground at
/// its centre, `deck_thickness` thick) on six truss legs, and two ramps of width `ramp_width`
/// leaving opposite deck edges (apothem = deck_radius cos 30 deg from the centre) down to the
/// ground `ramp_length` further out (horizontal run). Ramp 0 descends along the lander's yaw,
/// ramp 1 opposite.
///
/// Stripes. Each ramp carries six dark stripes across it, of widths `stripe_unit * code` along
/// the ramp surface, `stripe_gap` apart, `kStripeMargin` short of the ramp's side edges, the
/// block of six centred on the ramp surface. Codes bottom to top are kRampStripeCodes: within a
/// ramp every width is unique and every ordered pair of neighbouring codes occurs once over both
/// ramps, so a stripe seen with a neighbour names its ramp and index.
///
/// Ramp-surface frame G (per ramp): origin at the centre of the ramp surface (middle of the
/// stripe block), u up the slope along the surface towards the deck, v across, to the left
/// when facing up the ramp, w = u x v out of the surface. Units metres.

#include <array>

#include "rover/base/status.hpp"

namespace rover {
template <class Options>
class ParamBinder;
}  // namespace rover

namespace rover::hwconfig {

/// Stripe width codes per ramp, bottom to top.
inline constexpr std::array<std::array<int, 6>, 2> kRampStripeCodes = {
    {{2, 3, 4, 5, 6, 7}, {7, 5, 3, 6, 4, 2}}};
inline constexpr int kStripesPerRamp = 6;
/// [m] stripes end this far inside the ramp's side edges.
inline constexpr double kStripeMargin = 0.10;

/// One stripe in its ramp-surface frame G.
struct StripeLayout {
  int ramp = 0;
  int index = 0;       ///< 0 = lowest on the ramp
  int code = 0;        ///< width in stripe units
  double width = 0.0;  ///< [m] along u
  double length = 0.0; ///< [m] along v
  double u = 0.0;      ///< [m] centre along u (the stripe spans v in [-length/2, length/2])
};

struct LanderDescription {
  double deck_height = 1.0;     ///< [m] deck top above the bare ground at the centre
  double deck_thickness = 0.2;  ///< [m]
  double deck_radius = 1.5;     ///< [m] circumradius of the hexagonal deck (= edge length)
  double ramp_length = 3.0;     ///< [m] horizontal run of a ramp beyond the deck edge
  double ramp_width = 1.4;      ///< [m] (<= deck_radius, the edge the ramp hangs from)
  double stripe_unit = 0.03;    ///< [m] stripe width per code unit
  double stripe_gap = 0.15;     ///< [m] gap between neighbouring stripes along the ramp

  /// Checks every field and that the stripes fit on the ramp; messages start with
  /// "<prefix><field>: " and name the value.
  Status Validate(const char* prefix = "lander.") const;
  /// Binds the fields under their own names (deck_height, ..., stripe_gap).
  static void BindParams(ParamBinder<LanderDescription>& b);

  /// [m] deck centre to the middle of a deck edge: deck_radius cos 30 deg.
  double Apothem() const;
  /// [m] length of the six-stripe block along the ramp surface.
  double StripeBlockLength() const;
  /// Stripe `index` (0..5) of ramp `ramp` (0..1) in its ramp-surface frame.
  StripeLayout Stripe(int ramp, int index) const;
};

}  // namespace rover::hwconfig
