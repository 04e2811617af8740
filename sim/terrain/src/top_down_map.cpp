#include "rover/sim/terrain/top_down_map.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "rover/base/format.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace rover::sim::terrain {
namespace {

// BGR colours.
const cv::Scalar kFirmSoil(88, 128, 184);
const cv::Scalar kLooseSand(128, 184, 222);
const cv::Scalar kBedrock(96, 104, 128);
const cv::Scalar kRed(0, 0, 255);
const cv::Scalar kYellow(0, 230, 255);
const cv::Scalar kDark(30, 40, 60);
const cv::Scalar kCyan(255, 255, 0);
const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kBlack(0, 0, 0);

cv::Scalar Bgr(const MapColor& c) { return cv::Scalar(c.b, c.g, c.r); }

class Painter {
 public:
  Painter(cv::Mat* img, double s, double max_x, double max_y)
      : img_(img), s_(s), max_x_(max_x), max_y_(max_y) {}
  cv::Point2d Px(double x, double y) const { return {(max_y_ - y) * s_, (max_x_ - x) * s_}; }
  cv::Point Pi(double x, double y) const {
    const cv::Point2d p = Px(x, y);
    return {static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y))};
  }
  std::vector<cv::Point> Poly(const std::vector<Eigen::Vector2d>& pts) const {
    std::vector<cv::Point> out;
    out.reserve(pts.size());
    for (const auto& p : pts) out.push_back(Pi(p.x(), p.y()));
    return out;
  }
  double s() const { return s_; }
  cv::Mat& img() { return *img_; }

 private:
  cv::Mat* img_;
  double s_, max_x_, max_y_;
};

void Text(cv::Mat& img, const std::string& text, cv::Point org, double scale, const cv::Scalar& c) {
  const int thick = std::max(1, static_cast<int>(std::lround(scale * 2.0)));
  cv::putText(img, text, org, cv::FONT_HERSHEY_SIMPLEX, scale, kBlack, thick + 2, cv::LINE_AA);
  cv::putText(img, text, org, cv::FONT_HERSHEY_SIMPLEX, scale, c, thick, cv::LINE_AA);
}

}  // namespace

Status MapOptions::Validate() const {
  if (!(std::isfinite(pixels_per_metre) && pixels_per_metre >= 0.0 && pixels_per_metre <= 1000.0)) {
    return InvalidArgument("map.pixels_per_metre: " + FormatNumber(pixels_per_metre) +
                           " is out of range [0, 1000]");
  }
  if (max_pixels < 16 || max_pixels > 20000) {
    return InvalidArgument("map.max_pixels: " + std::to_string(max_pixels) +
                           " is out of range [16, 20000]");
  }
  if (!(obstacle_height > 0.0)) {
    return InvalidArgument("map.obstacle_height: " + FormatNumber(obstacle_height) +
                           " must be > 0");
  }
  for (std::size_t i = 0; i < cell_layers.size(); ++i) {
    const MapCellLayer& l = cell_layers[i];
    const std::size_t n = static_cast<std::size_t>(std::max(0, l.width)) *
                          static_cast<std::size_t>(std::max(0, l.height));
    if (!(l.resolution > 0) || l.width < 0 || l.height < 0 || l.value.size() != n ||
        l.known.size() != n || !std::isfinite(l.origin_x) || !std::isfinite(l.origin_y) ||
        !(l.opacity > 0 && l.opacity <= 1)) {
      return InvalidArgument("map.cell_layers[" + std::to_string(i) + "] '" + l.label +
                             "': needs resolution > 0, width x height values and known flags, "
                             "opacity in (0, 1]");
    }
  }
  for (std::size_t i = 0; i < polylines.size(); ++i) {
    const MapPolyline& pl = polylines[i];
    if (pl.thickness < 1 || pl.thickness > 50) {
      return InvalidArgument("map.polylines[" + std::to_string(i) + "].thickness: " +
                             std::to_string(pl.thickness) + " is out of range [1, 50]");
    }
    for (const auto& p : pl.points) {
      if (!p.allFinite()) {
        return InvalidArgument("map.polylines[" + std::to_string(i) + "] '" + pl.label +
                               "': a point is not finite");
      }
    }
  }
  return Status::Ok();
}

Eigen::Vector2d MapImage::ToPixel(double x, double y) const {
  return {map_col0 + (max_y - y) * pixels_per_metre, map_row0 + (max_x - x) * pixels_per_metre};
}

MapColor MapImage::At(int col, int row) const {
  const std::size_t i = (static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                         static_cast<std::size_t>(col)) *
                        3;
  return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

namespace {

// The map with its title band above and its legend beside it; `map_origin` and `map_size` say
// where the map itself is in the image.
Result<cv::Mat> Render(const Terrain& t, const MapOptions& o, double* scale, cv::Point* map_origin,
                       cv::Size* map_size) {
  ROVER_RETURN_IF_ERROR(o.Validate());
  const HeightField& h = t.natural;
  if (h.nx() < 2 || h.ny() < 2) return InvalidArgument("map: the terrain is empty");
  const double ext_x = h.max_x() - h.min_x(), ext_y = h.max_y() - h.min_y();
  double s = o.pixels_per_metre > 0.0 ? o.pixels_per_metre : 1.0 / h.resolution();
  s = std::min(s, (o.max_pixels - 1) / std::max(ext_x, ext_y));
  *scale = s;
  const int width = static_cast<int>(std::floor(ext_y * s)) + 1;
  const int height = static_cast<int>(std::floor(ext_x * s)) + 1;
  cv::Mat img(height, width, CV_8UC3);

  // Hillshade x soil colour x elevation tint.
  float zmin = t.bare.heights().empty() ? 0.0f : t.bare.heights()[0], zmax = zmin;
  for (float z : t.bare.heights()) {
    zmin = std::min(zmin, z);
    zmax = std::max(zmax, z);
  }
  const double zspan = std::max(1e-6, static_cast<double>(zmax - zmin));
  const Eigen::Vector3d sun = Eigen::Vector3d(0.5, 0.5, std::sqrt(0.5)).normalized();
  for (int r = 0; r < height; ++r) {
    auto* row = img.ptr<cv::Vec3b>(r);
    const double x = h.max_x() - r / s;
    for (int c = 0; c < width; ++c) {
      const double y = h.max_y() - c / s;
      Eigen::Vector2d g;
      const double z = h.HeightAndGradient(x, y, &g);
      const Eigen::Vector3d n = Eigen::Vector3d(-g.x(), -g.y(), 1.0).normalized();
      const double shade = std::clamp(0.25 + 0.75 * n.dot(sun) / sun.z(), 0.15, 1.3);
      const double tint = 0.85 + 0.3 * std::clamp((z - zmin) / zspan, 0.0, 1.0);
      const Soil soil = h.SoilAt(x, y);
      const cv::Scalar& base =
          soil == Soil::kLooseSand ? kLooseSand : (soil == Soil::kBedrock ? kBedrock : kFirmSoil);
      for (int k = 0; k < 3; ++k) {
        row[c][k] = cv::saturate_cast<uchar>(base[k] * shade * tint);
      }
    }
  }

  Painter p(&img, s, h.max_x(), h.max_y());
  const double font = std::clamp(std::min(width, height) / 1600.0, 0.35, 1.0);

  // Cell layers (a goodness map): grey by value, unknown cells untouched, bounds dashed.
  for (const MapCellLayer& l : o.cell_layers) {
    for (int j = 0; j < l.height; ++j) {
      for (int i = 0; i < l.width; ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(l.width) +
                              static_cast<std::size_t>(i);
        if (!l.known[k]) continue;
        const double x0 = l.origin_x + i * l.resolution, y0 = l.origin_y + j * l.resolution;
        // North up, west left: the cell's (x1, y1) corner is its top-left pixel.
        const cv::Point a = p.Pi(x0 + l.resolution, y0 + l.resolution), b = p.Pi(x0, y0);
        const cv::Rect cell = cv::Rect(a, b) & cv::Rect(0, 0, width, height);
        if (cell.area() <= 0) continue;
        cv::Mat roi = img(cell);
        const double v = l.value[k];
        roi = roi * (1.0 - l.opacity) + cv::Scalar(v, v, v) * l.opacity;
      }
    }
    const double x0 = l.origin_x, y0 = l.origin_y;
    const double x1 = x0 + l.width * l.resolution, y1 = y0 + l.height * l.resolution;
    const std::vector<Eigen::Vector2d> edges = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}};
    for (std::size_t e = 0; e + 1 < edges.size(); ++e) {
      const Eigen::Vector2d d = edges[e + 1] - edges[e];
      const int dashes = std::max(2, static_cast<int>(d.norm() * s / 12.0));
      for (int q = 0; q < dashes; q += 2) {
        cv::line(img, p.Pi((edges[e] + d * q / dashes).x(), (edges[e] + d * q / dashes).y()),
                 p.Pi((edges[e] + d * (q + 1) / dashes).x(), (edges[e] + d * (q + 1) / dashes).y()),
                 kWhite, 1, cv::LINE_AA);
      }
    }
  }

  // Keep-out disc.
  const StartParams& st = t.params.start;
  if (o.draw_keep_out && st.keep_out_radius > 0.0) {
    const int segments = 48;
    for (int k = 0; k < segments; k += 2) {
      const double a0 = 2.0 * std::numbers::pi * k / segments,
                   a1 = 2.0 * std::numbers::pi * (k + 1) / segments;
      cv::line(
          img,
          p.Pi(st.x + st.keep_out_radius * std::cos(a0), st.y + st.keep_out_radius * std::sin(a0)),
          p.Pi(st.x + st.keep_out_radius * std::cos(a1), st.y + st.keep_out_radius * std::sin(a1)),
          kWhite, 1, cv::LINE_AA);
    }
    const int arm = std::max(4, static_cast<int>(0.3 * s));
    const cv::Point c = p.Pi(st.x, st.y);
    cv::line(img, c - cv::Point(arm, 0), c + cv::Point(arm, 0), kWhite, 1, cv::LINE_AA);
    cv::line(img, c - cv::Point(0, arm), c + cv::Point(0, arm), kWhite, 1, cv::LINE_AA);
  }

  // Rocks by height class.
  if (o.draw_rocks) {
    for (const Rock& rock : t.rocks) {
      if (rock.science_target) continue;
      const double rad_px = RockBoundingRadius(rock) * s;
      cv::Scalar colour;
      int thick = 1;
      if (rock.height > o.obstacle_height) {
        colour = kRed;
        thick = rad_px > 8.0 ? 2 : 1;
      } else if (rock.height > 0.5 * o.obstacle_height) {
        colour = kYellow;
      } else if (rad_px >= 1.5) {
        colour = kDark;
      } else {
        continue;
      }
      const int n = std::clamp(static_cast<int>(rad_px), 8, 48);
      const std::vector<cv::Point> poly = p.Poly(RockOutline(rock, n));
      cv::polylines(img, poly, true, colour, thick, cv::LINE_AA);
    }
  }

  // Lander: upward-facing quads, lowest first.
  if (t.lander) {
    std::vector<const LanderQuad*> quads;
    for (const LanderQuad& q : t.lander->quads) {
      if (q.Normal().z() > 0.05) quads.push_back(&q);
    }
    auto top = [](const LanderQuad* q) {
      double z = q->corners[0].z();
      for (const auto& c : q->corners) z = std::max(z, c.z());
      return z;
    };
    std::stable_sort(quads.begin(), quads.end(), [&](const LanderQuad* a, const LanderQuad* b) {
      if (a->part == LanderPart::kStripe || b->part == LanderPart::kStripe) {
        return (a->part != LanderPart::kStripe) && (b->part == LanderPart::kStripe);
      }
      return top(a) < top(b);
    });
    for (const LanderQuad* q : quads) {
      std::vector<cv::Point> poly;
      for (const auto& c : q->corners) poly.push_back(p.Pi(c.x(), c.y()));
      const double lit = 0.6 + 0.4 * q->Normal().dot(sun);
      const cv::Scalar col(255 * q->albedo.z() * lit, 255 * q->albedo.y() * lit,
                           255 * q->albedo.x() * lit);
      cv::fillConvexPoly(img, poly, col, cv::LINE_AA);
    }
    std::vector<Eigen::Vector2d> hex(t.lander->deck_vertices.begin(),
                                     t.lander->deck_vertices.end());
    cv::polylines(img, p.Poly(hex), true, kBlack, 1, cv::LINE_AA);
  }

  // Science targets.
  for (const Rock& rock : t.rocks) {
    if (!rock.science_target) continue;
    const std::vector<cv::Point> poly = p.Poly(RockOutline(rock, 32));
    cv::polylines(img, poly, true, kCyan, 2, cv::LINE_AA);
    const cv::Point c = p.Pi(rock.position.x(), rock.position.y());
    const int off = static_cast<int>(RockBoundingRadius(rock) * s) + 4;
    Text(img, "T" + std::to_string(rock.id), c + cv::Point(off, -off), font * 0.8, kCyan);
  }

  // Overlays.
  for (const MapPolyline& pl : o.polylines) {
    if (pl.points.empty()) continue;
    const std::vector<cv::Point> poly = p.Poly(pl.points);
    if (pl.dashed) {
      // Dashes of ~10 px along the whole polyline, gaps as long.
      double run = 0;
      for (std::size_t k = 0; k + 1 < poly.size(); ++k) {
        const cv::Point2d a = poly[k], b = poly[k + 1];
        const double len = cv::norm(b - a);
        if (len <= 0) continue;
        const int pieces = std::max(1, static_cast<int>(len / 2.0));
        for (int q = 0; q < pieces; ++q) {
          const cv::Point2d u = a + (b - a) * (static_cast<double>(q) / pieces);
          const cv::Point2d v = a + (b - a) * (static_cast<double>(q + 1) / pieces);
          if (std::fmod(run, 20.0) < 10.0) {
            cv::line(img, u, v, Bgr(pl.color), pl.thickness, cv::LINE_AA);
          }
          run += len / pieces;
        }
      }
    } else {
      cv::polylines(img, poly, false, Bgr(pl.color), pl.thickness, cv::LINE_AA);
    }
    if (pl.mark_ends) {
      const int r = 2 + 2 * pl.thickness;
      cv::circle(img, poly.front(), r, Bgr(pl.color), std::max(1, pl.thickness / 2 + 1),
                 cv::LINE_AA);
      cv::rectangle(img, poly.back() - cv::Point(r, r), poly.back() + cv::Point(r, r),
                    Bgr(pl.color), std::max(1, pl.thickness / 2 + 1), cv::LINE_AA);
    }
  }

  for (const MapLabel& l : o.labels) {
    const cv::Point at = p.Pi(l.at.x(), l.at.y());
    Text(img, l.text, at, std::max(font, 0.4), Bgr(l.color));
  }

  // Scale bar (bottom left): the round length closest to a fifth of the width.
  {
    double best = 1.0;
    for (double l : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0}) {
      if (std::abs(l * s - 0.2 * width) < std::abs(best * s - 0.2 * width)) best = l;
    }
    const int len = static_cast<int>(std::lround(best * s));
    const int bar_h = std::max(4, height / 150);
    const cv::Point a(std::max(10, width / 40), height - std::max(12, height / 30));
    cv::rectangle(img, a - cv::Point(1, 1), a + cv::Point(len + 1, bar_h + 1), kBlack, cv::FILLED);
    cv::rectangle(img, a, a + cv::Point(len / 2, bar_h), kWhite, cv::FILLED);
    Text(img, FormatNumber(best) + " m", a + cv::Point(0, -bar_h), font, kWhite);
  }
  // North arrow (top right).
  {
    const int len = std::max(20, height / 20);
    const cv::Point base(width - std::max(20, width / 30), std::max(20, height / 30) + len);
    cv::arrowedLine(img, base, base - cv::Point(0, len), kWhite, 2, cv::LINE_AA, 0, 0.3);
    Text(img, "N", base + cv::Point(-static_cast<int>(8 * font), static_cast<int>(24 * font)), font,
         kWhite);
  }
  // The map is done; the title goes in a band above it and the legend in a panel beside it, so
  // that neither hides what the run did and both stay readable however small the map is.
  const double text_scale = std::max(font, 0.45);
  const int line = static_cast<int>(26 * text_scale) + 4;
  cv::Mat legend;
  if (o.draw_legend) {
    struct Entry {
      std::string text;
      cv::Scalar colour;
      bool swatch;
      int line = 0;  // > 0: a line of this width, not a box (paths)
    };
    std::vector<Entry> entries = {
        {"firm soil", kFirmSoil, true},
        {"loose sand", kLooseSand, true},
        {"bedrock", kBedrock, true},
        {"rock > " + FormatNumber(o.obstacle_height) + " m high", kRed, false},
        {"rock > " + FormatNumber(0.5 * o.obstacle_height) + " m high", kYellow, false},
        {"smaller rock", kDark, false},
    };
    bool any_target = false;
    for (const Rock& r : t.rocks) any_target = any_target || r.science_target;
    if (any_target) entries.push_back({"science target", kCyan, false});
    if (o.draw_keep_out && st.keep_out_radius > 0.0) {
      entries.push_back({"rock-free start disc (+ = start)", kWhite, false});
    }
    for (const MapCellLayer& l : o.cell_layers) {
      if (!l.label.empty()) entries.push_back({l.label, cv::Scalar(128, 128, 128), true});
    }
    bool any_ends = false;
    for (const MapPolyline& pl : o.polylines) {
      if (!pl.label.empty()) {
        entries.push_back({pl.label + (pl.dashed ? " (dashed)" : ""), Bgr(pl.color), false,
                           pl.thickness});
      }
      any_ends = any_ends || (pl.mark_ends && !pl.label.empty());
    }
    if (any_ends) entries.push_back({"path: o start, [] end", kBlack, false});
    int text_w = 0;
    for (const Entry& e : entries) {
      int base = 0;
      text_w = std::max(
          text_w, cv::getTextSize(e.text, cv::FONT_HERSHEY_SIMPLEX, text_scale, 1, &base).width);
    }
    const int box_w = text_w + line + 20;
    const int box_h = line * static_cast<int>(entries.size()) + 12;
    legend = cv::Mat(std::max(box_h, height), box_w, CV_8UC3, cv::Scalar(235, 235, 235));
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const Entry& e = entries[i];
      const cv::Point org(6, 6 + line * static_cast<int>(i));
      const cv::Rect sw(org + cv::Point(0, line / 6), cv::Size(line - 8, line - 8));
      if (e.swatch) {
        cv::rectangle(legend, sw, e.colour, cv::FILLED);
      } else if (e.line > 0) {
        const int mid = sw.y + sw.height / 2;
        cv::line(legend, {sw.x, mid}, {sw.x + sw.width, mid}, e.colour, std::max(2, e.line),
                 cv::LINE_AA);
      } else {
        cv::rectangle(legend, sw, e.colour, 2);
      }
      cv::putText(legend, e.text, org + cv::Point(line, line - 8), cv::FONT_HERSHEY_SIMPLEX,
                  text_scale, kBlack, 1, cv::LINE_AA);
    }
  }
  const int total_w = width + legend.cols;
  // The title, broken at spaces into as many lines as the width needs.
  std::vector<std::string> title_lines;
  if (!o.title.empty()) {
    std::string current;
    std::size_t pos = 0;
    while (pos <= o.title.size()) {
      std::size_t end = o.title.find(' ', pos);
      if (end == std::string::npos) end = o.title.size();
      const std::string word = o.title.substr(pos, end - pos);
      const std::string trial = current.empty() ? word : current + " " + word;
      int base = 0;
      const int w = cv::getTextSize(trial, cv::FONT_HERSHEY_SIMPLEX, text_scale, 1, &base).width;
      if (w > total_w - 12 && !current.empty()) {
        title_lines.push_back(current);
        current = word;
      } else {
        current = trial;
      }
      pos = end + 1;
    }
    if (!current.empty()) title_lines.push_back(current);
  }
  const int band = title_lines.empty() ? 0 : line * static_cast<int>(title_lines.size()) + 8;
  cv::Mat out(std::max(height, legend.rows) + band, total_w, CV_8UC3, cv::Scalar(235, 235, 235));
  for (std::size_t i = 0; i < title_lines.size(); ++i) {
    cv::putText(out, title_lines[i], cv::Point(6, line * static_cast<int>(i + 1)),
                cv::FONT_HERSHEY_SIMPLEX, text_scale, kBlack, 1, cv::LINE_AA);
  }
  img.copyTo(out(cv::Rect(0, band, width, height)));
  if (!legend.empty()) legend.copyTo(out(cv::Rect(width, band, legend.cols, legend.rows)));
  *map_origin = cv::Point(0, band);
  *map_size = cv::Size(width, height);
  return out;
}

}  // namespace

Result<MapImage> RenderTopDownMap(const Terrain& terrain, const MapOptions& options) {
  double s = 0.0;
  cv::Point origin;
  cv::Size size;
  auto img = Render(terrain, options, &s, &origin, &size);
  if (!img.ok()) return img.status();
  MapImage out;
  out.width = img->cols;
  out.height = img->rows;
  out.pixels_per_metre = s;
  out.map_col0 = origin.x;
  out.map_row0 = origin.y;
  out.map_width = size.width;
  out.map_height = size.height;
  out.max_x = terrain.natural.max_x();
  out.max_y = terrain.natural.max_y();
  out.rgb.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 3);
  for (int r = 0; r < out.height; ++r) {
    const auto* row = img->ptr<cv::Vec3b>(r);
    for (int c = 0; c < out.width; ++c) {
      const std::size_t i = (static_cast<std::size_t>(r) * static_cast<std::size_t>(out.width) +
                             static_cast<std::size_t>(c)) *
                            3;
      out.rgb[i] = row[c][2];
      out.rgb[i + 1] = row[c][1];
      out.rgb[i + 2] = row[c][0];
    }
  }
  return out;
}

Status WriteTopDownMap(const Terrain& terrain, const std::string& path, const MapOptions& options) {
  double s = 0.0;
  cv::Point origin;
  cv::Size size;
  auto img = Render(terrain, options, &s, &origin, &size);
  if (!img.ok()) return img.status();
  try {
    if (!cv::imwrite(path, *img)) return Unavailable(path + ": cannot write the map image");
  } catch (const cv::Exception& e) {
    return Unavailable(path + ": cannot write the map image: " + e.what());
  }
  return Status::Ok();
}

}  // namespace rover::sim::terrain
