#pragma once
/// @file
/// Layered goodness maps (seed 000 "Layered Goodness Maps"): the memory that keeps an obstacle
/// in the map after it has left the field of view.
///
/// Near the edge of a field of view the rover disc of a cell is only partly seen, so a fresh
/// assessment there can miss an obstacle that an earlier scan saw whole; overwriting the map with
/// it would let the rover steer back into the obstacle. Instead the fresh goodness F is merged
/// into L layers, layer l with a shrink radius s_l = L - 1 - l cells (MER: L = 7, discs of radius
/// 1 cell for layer 6 up to 7 cells for layer 0, shrinking obstacle blobs by 6 - l cells):
///
///   shrunk_l(c) = max_{c' in D(c, s_l), F(c') known} F(c')           (obstacles shrink by s_l)
///   layer_l(c)  = min(layer_l(c), shrunk_l(c))  where c is merged conservatively and was known,
///                 shrunk_l(c)                     elsewhere F(c) is known (new overrides old),
///                 unchanged                       where F(c) is unknown;
///   grown_l(c)  = min_{c' in D(c, s_l), known} layer_l(c')           (obstacles grow back)
///   combined(c) = min_l grown_l(c)                                    (the most conservative)
///
/// with D(c, s) the disc of radius s cells about c. For one scan into an empty map combined = F
/// (grey closing is extensive and layer L-1 is F itself). Later, a fresh scan that re-evaluates
/// the edge of an obstacle's blob from a partial disc overwrites those cells in every layer, but
/// the shrunk core of the obstacle (in the low layers) lies outside the new view, survives, and
/// grows back over them. Low values only in layer 0 are "point" obstacles such as one rock; low
/// values only in higher layers are dispersed ones.
///
/// Values are goodness 0..255 in int16 cells; kAbsent marks unknown. All layers share one set of
/// known cells.

#include <cstdint>
#include <vector>

#include "rover/apl/gestalt/disc.hpp"
#include "rover/apl/gestalt/grid.hpp"

namespace rover::apl::gestalt {

class LayeredGoodness {
 public:
  static constexpr std::int16_t kAbsent = -1;

  LayeredGoodness() = default;
  /// Preconditions: width, height >= 0, num_layers >= 1.
  LayeredGoodness(int width, int height, int num_layers);

  int num_layers() const { return static_cast<int>(layers_.size()); }
  /// Shrink radius of layer l, in cells: num_layers - 1 - l.
  int shrink_radius(int l) const { return num_layers() - 1 - l; }

  /// Merges fresh goodness (kAbsent where the scan assessed nothing); `conservative` (nonzero)
  /// marks cells where min(old, new) is kept. Preconditions: both grids match the map's size.
  void Merge(const Grid<std::int16_t>& fresh, const Grid<std::uint8_t>& conservative);
  /// Scrolls every layer (see Grid::Shift).
  void Shift(int di, int dj);
  /// Makes the cells marked in `mask` unknown in every layer.
  void Forget(const Grid<std::uint8_t>& mask);
  void Clear();

  /// min over layers of the grown layers; kAbsent = unknown. Recomputed on first use after a
  /// change (so a Shift followed by a Merge recombines once).
  const Grid<std::int16_t>& combined() const;
  /// Layer l as stored (shrunk). Preconditions: 0 <= l < num_layers().
  const Grid<std::int16_t>& layer(int l) const { return layers_[static_cast<std::size_t>(l)]; }

 private:
  void Recombine() const;

  std::vector<Grid<std::int16_t>> layers_;
  std::vector<DiscSpans> discs_;  ///< per layer, radius shrink_radius(l)
  mutable Grid<std::int16_t> combined_;
  mutable bool stale_ = false;
};

}  // namespace rover::apl::gestalt
