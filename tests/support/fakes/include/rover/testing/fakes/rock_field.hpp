#pragma once
/// @file
/// A rock field and a synthetic HAZCAM range image of it (header only, no DDS; target
/// rover_fake_terrain), for tests of terrain assessment and the mobility manager.
///
/// Terrain: flat ground at z = 0 with rocks, each a half-ellipsoid of radius r and height h
/// (z = h sqrt(1 - (d / r)^2) within d < r of its centre; the highest rock wins where they
/// overlap). Site frame x north, y west, z up; metres.
///
/// Image: `cols` azimuths evenly over the field of view (centred forward, or backward for the
/// rear camera; column 0 is the leftmost) by `rows` ground ranges from near to far (row 0 is the
/// farthest, as in a camera image); each pixel is the terrain point at that azimuth and ground
/// range, in the rover frame of `pose` (planar: x, y, heading; the rover's z is 0). A pixel is
/// invalid when nearer terrain hides it from a camera at `camera_height` (its elevation angle is
/// below the largest one seen nearer along its column). No noise: the scan is exact.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace rover::testing {

struct FieldRock {
  double x = 0.0, y = 0.0;  ///< [m] centre, site frame
  double radius = 0.2;      ///< [m]
  double height = 0.3;      ///< [m]
};

struct HazcamSpec {
  double camera_height = 0.8;                ///< [m] above the ground
  double near_range = 0.4, far_range = 4.5;  ///< [m] ground range of the nearest / farthest row
  double fov = 2.1;                          ///< [rad] horizontal field of view (~120 deg)
  int cols = 100, rows = 80;
};

/// One synthetic image: 3 floats per pixel (rover frame), 1 valid byte per pixel, row-major.
struct SyntheticScan {
  int width = 0, height = 0;
  std::vector<float> xyz;
  std::vector<std::uint8_t> valid;
};

class RockField {
 public:
  std::vector<FieldRock>& rocks() { return rocks_; }
  const std::vector<FieldRock>& rocks() const { return rocks_; }

  /// Rocks along the segment a..b, `spacing` apart (both ends included).
  void AddWall(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double spacing, double radius,
               double height) {
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing)));
    for (int i = 0; i <= n; ++i) {
      const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / n);
      rocks_.push_back({p.x(), p.y(), radius, height});
    }
  }

  double HeightAt(double x, double y) const {
    double z = 0.0;
    for (const FieldRock& r : rocks_) {
      const double d2 = (x - r.x) * (x - r.x) + (y - r.y) * (y - r.y);
      if (d2 < r.radius * r.radius) {
        z = std::max(z, r.height * std::sqrt(1.0 - d2 / (r.radius * r.radius)));
      }
    }
    return z;
  }

  /// Smallest distance from (x, y) to a rock's edge (negative inside one).
  double Clearance(double x, double y) const {
    double c = 1e9;
    for (const FieldRock& r : rocks_) c = std::min(c, std::hypot(x - r.x, y - r.y) - r.radius);
    return c;
  }

  /// The image of the file comment from the rover at (x, y, heading); `rear` looks backward.
  SyntheticScan Capture(double x, double y, double heading, bool rear,
                        const HazcamSpec& spec = {}) const {
    SyntheticScan s;
    s.width = spec.cols;
    s.height = spec.rows;
    const std::size_t n = static_cast<std::size_t>(spec.cols) * static_cast<std::size_t>(spec.rows);
    s.xyz.assign(3 * n, 0.0f);
    s.valid.assign(n, 0);
    const double facing = rear ? 3.14159265358979323846 : 0.0;
    const double c = std::cos(heading), sn = std::sin(heading);
    for (int u = 0; u < spec.cols; ++u) {
      const double az = facing + spec.fov * (0.5 - (u + 0.5) / spec.cols);
      double horizon = -1e9;  // steepest elevation tangent seen so far along the column
      for (int r = 0; r < spec.rows; ++r) {  // near to far
        const double range =
            spec.near_range + (spec.far_range - spec.near_range) * r / (spec.rows - 1);
        const double xr = range * std::cos(az), yr = range * std::sin(az);
        const double z = HeightAt(x + c * xr - sn * yr, y + sn * xr + c * yr);
        const double tangent = (z - spec.camera_height) / range;
        if (tangent < horizon) continue;  // hidden
        horizon = tangent;
        const std::size_t k = static_cast<std::size_t>(spec.rows - 1 - r) * spec.cols + u;
        s.valid[k] = 1;
        s.xyz[3 * k] = static_cast<float>(xr);
        s.xyz[3 * k + 1] = static_cast<float>(yr);
        s.xyz[3 * k + 2] = static_cast<float>(z);
      }
    }
    return s;
  }

 private:
  std::vector<FieldRock> rocks_;
};

}  // namespace rover::testing
