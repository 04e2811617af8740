#include "rover/apl/gestalt/disc.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rover/base/check.hpp"

namespace rover::apl::gestalt {
namespace {

// Sliding extreme of window 2w + 1 along one row (van Herk / Gil-Werman). `in` has `n` values;
// out[i] = op over in[i - w .. i + w] (outside = identity). `pad`, `g`, `h` are scratch.
template <class Op>
void SlidingRow(const std::int16_t* in, int n, int w, std::int16_t identity, Op op,
                std::int16_t* out, std::vector<std::int16_t>& pad, std::vector<std::int16_t>& g,
                std::vector<std::int16_t>& h) {
  if (w == 0) {
    std::copy(in, in + n, out);
    return;
  }
  const int k = 2 * w + 1;
  const int len = n + 2 * w;
  pad.assign(static_cast<std::size_t>(len), identity);
  std::copy(in, in + n, pad.begin() + w);
  g.resize(static_cast<std::size_t>(len));
  h.resize(static_cast<std::size_t>(len));
  for (int x = 0; x < len; ++x) {
    g[x] = (x % k == 0) ? pad[x] : op(g[x - 1], pad[x]);
  }
  for (int x = len - 1; x >= 0; --x) {
    h[x] = (x == len - 1 || (x + 1) % k == 0) ? pad[x] : op(h[x + 1], pad[x]);
  }
  for (int i = 0; i < n; ++i) out[i] = op(h[i], g[i + 2 * w]);
}

template <class Op>
void DiscExtreme(const Grid<std::int16_t>& v, const DiscSpans& disc, std::int16_t absent,
                 std::int16_t identity, Op op, Grid<std::int16_t>* out) {
  ROVER_DEMAND(out != nullptr && out != &v);
  const int W = v.width(), H = v.height();
  // Values with `absent` replaced by the operation's identity.
  Grid<std::int16_t> in(W, H, identity);
  for (std::size_t k = 0; k < v.size(); ++k) in[k] = v[k] == absent ? identity : v[k];
  // One row-filtered copy per distinct half-width.
  std::vector<int> widths;
  for (int dy = -disc.radius(); dy <= disc.radius(); ++dy) widths.push_back(disc.half_width(dy));
  std::sort(widths.begin(), widths.end());
  widths.erase(std::unique(widths.begin(), widths.end()), widths.end());
  std::vector<Grid<std::int16_t>> rows(widths.size(), Grid<std::int16_t>(W, H, identity));
  std::vector<std::int16_t> pad, g, h;
  for (std::size_t wi = 0; wi < widths.size(); ++wi) {
    for (int j = 0; j < H; ++j) {
      SlidingRow(&in.at(0, j), W, widths[wi], identity, op, &rows[wi].at(0, j), pad, g, h);
    }
  }
  std::vector<std::size_t> row_of(static_cast<std::size_t>(2 * disc.radius() + 1));
  for (int dy = -disc.radius(); dy <= disc.radius(); ++dy) {
    row_of[static_cast<std::size_t>(dy + disc.radius())] = static_cast<std::size_t>(
        std::lower_bound(widths.begin(), widths.end(), disc.half_width(dy)) - widths.begin());
  }
  if (out->width() != W || out->height() != H) *out = Grid<std::int16_t>(W, H, absent);
  for (int j = 0; j < H; ++j) {
    for (int i = 0; i < W; ++i) {
      std::int16_t e = identity;
      for (int dy = -disc.radius(); dy <= disc.radius(); ++dy) {
        const int jj = j + dy;
        if (jj < 0 || jj >= H) continue;
        e = op(e, rows[row_of[static_cast<std::size_t>(dy + disc.radius())]].at(i, jj));
      }
      out->at(i, j) = e == identity ? absent : e;
    }
  }
}

}  // namespace

DiscSpans::DiscSpans(double radius_cells) {
  ROVER_DEMAND(radius_cells >= 0.0 && std::isfinite(radius_cells));
  // A small tolerance keeps exact radii (r = 2: (0, 2) is inside) robust to rounding.
  const double r2 = radius_cells * radius_cells + 1e-9;
  radius_ = static_cast<int>(std::floor(radius_cells + 1e-9));
  half_widths_.assign(static_cast<std::size_t>(2 * radius_ + 1), 0);
  cell_count_ = 0;
  for (int dy = -radius_; dy <= radius_; ++dy) {
    const int w = static_cast<int>(std::floor(std::sqrt(std::max(0.0, r2 - dy * dy))));
    half_widths_[static_cast<std::size_t>(dy + radius_)] = w;
    cell_count_ += 2 * w + 1;
  }
}

void DilateMask(const Grid<std::uint8_t>& mask, const DiscSpans& disc, Grid<std::uint8_t>* out) {
  ROVER_DEMAND(out != nullptr && out != &mask);
  Grid<int> counts(mask.width(), mask.height(), 0);
  for (std::size_t k = 0; k < mask.size(); ++k) counts[k] = mask[k] != 0 ? 1 : 0;
  RowPrefix<int> prefix;
  prefix.Build(counts);
  if (out->width() != mask.width() || out->height() != mask.height()) {
    *out = Grid<std::uint8_t>(mask.width(), mask.height(), 0);
  }
  for (int j = 0; j < mask.height(); ++j) {
    for (int i = 0; i < mask.width(); ++i) {
      out->at(i, j) = prefix.DiscSum(i, j, disc) > 0 ? 1 : 0;
    }
  }
}

void DiscMax(const Grid<std::int16_t>& v, const DiscSpans& disc, std::int16_t absent,
             Grid<std::int16_t>* out) {
  DiscExtreme(
      v, disc, absent, std::numeric_limits<std::int16_t>::min(),
      [](std::int16_t a, std::int16_t b) { return a > b ? a : b; }, out);
}

void DiscMin(const Grid<std::int16_t>& v, const DiscSpans& disc, std::int16_t absent,
             Grid<std::int16_t>* out) {
  DiscExtreme(
      v, disc, absent, std::numeric_limits<std::int16_t>::max(),
      [](std::int16_t a, std::int16_t b) { return a < b ? a : b; }, out);
}

}  // namespace rover::apl::gestalt
