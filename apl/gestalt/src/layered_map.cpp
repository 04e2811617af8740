#include "rover/apl/gestalt/layered_map.hpp"

#include <algorithm>

#include "rover/base/check.hpp"

namespace rover::apl::gestalt {

LayeredGoodness::LayeredGoodness(int width, int height, int num_layers) {
  ROVER_DEMAND(num_layers >= 1);
  layers_.assign(static_cast<std::size_t>(num_layers), Grid<std::int16_t>(width, height, kAbsent));
  for (int l = 0; l < num_layers; ++l) discs_.emplace_back(num_layers - 1 - l);
  combined_ = Grid<std::int16_t>(width, height, kAbsent);
}

void LayeredGoodness::Merge(const Grid<std::int16_t>& fresh,
                            const Grid<std::uint8_t>& conservative) {
  ROVER_DEMAND(fresh.width() == combined_.width() && fresh.height() == combined_.height());
  ROVER_DEMAND(conservative.size() == fresh.size());
  Grid<std::int16_t> shrunk;
  for (std::size_t l = 0; l < layers_.size(); ++l) {
    const Grid<std::int16_t>* s = &fresh;
    if (discs_[l].radius() > 0) {
      DiscMax(fresh, discs_[l], kAbsent, &shrunk);
      s = &shrunk;
    }
    Grid<std::int16_t>& layer = layers_[l];
    for (std::size_t k = 0; k < fresh.size(); ++k) {
      if (fresh[k] == kAbsent) continue;
      const std::int16_t v = (*s)[k];
      layer[k] = (conservative[k] != 0 && layer[k] != kAbsent) ? std::min(layer[k], v) : v;
    }
  }
  stale_ = true;
}

void LayeredGoodness::Shift(int di, int dj) {
  for (auto& l : layers_) l.Shift(di, dj, kAbsent);
  stale_ = true;
}

void LayeredGoodness::Forget(const Grid<std::uint8_t>& mask) {
  for (auto& l : layers_) {
    for (std::size_t k = 0; k < l.size(); ++k) {
      if (mask[k] != 0) l[k] = kAbsent;
    }
  }
  stale_ = true;
}

void LayeredGoodness::Clear() {
  for (auto& l : layers_) l.Fill(kAbsent);
  combined_.Fill(kAbsent);
  stale_ = false;
}

const Grid<std::int16_t>& LayeredGoodness::combined() const {
  if (stale_) Recombine();
  return combined_;
}

void LayeredGoodness::Recombine() const {
  stale_ = false;
  const Grid<std::int16_t>& top = layers_.back();  // radius 0: known cells are its own
  combined_ = top;
  Grid<std::int16_t> grown;
  for (std::size_t l = 0; l + 1 < layers_.size(); ++l) {
    DiscMin(layers_[l], discs_[l], kAbsent, &grown);
    for (std::size_t k = 0; k < combined_.size(); ++k) {
      if (combined_[k] == kAbsent || grown[k] == kAbsent) continue;
      combined_[k] = std::min(combined_[k], grown[k]);
    }
  }
}

}  // namespace rover::apl::gestalt
