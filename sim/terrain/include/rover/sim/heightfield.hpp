#pragma once
/// @file
/// A regular grid of terrain heights with a soil type per cell, in the site frame (x north,
/// y west, z up; metres). The simulator's physics (wheel contact), renderer and judge all read
/// terrain through this class.
///
/// Cell (i, j) has its sample at  origin + (i * resolution, j * resolution);  i runs along x
/// (0..nx-1), j along y (0..ny-1). Height(x, y) interpolates bilinearly between samples and
/// clamps to the border outside the grid.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace rover::sim::terrain {

enum class Soil : std::uint8_t {
  kBedrock = 0,    ///< hard rock outcrop: little sinkage, little slip
  kFirmSoil = 1,   ///< packed soil / duricrust: moderate slip on slopes
  kLooseSand = 2,  ///< drift material: slip rises steeply with slope (near 100% at 20 deg)
};
const char* SoilName(Soil s);

class HeightField {
 public:
  HeightField() = default;
  /// Preconditions: nx, ny >= 2; resolution > 0. Heights start at 0, soil at kFirmSoil.
  HeightField(int nx, int ny, double resolution, Eigen::Vector2d origin = Eigen::Vector2d::Zero());

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  double resolution() const { return resolution_; }
  const Eigen::Vector2d& origin() const { return origin_; }
  /// Extent of the grid: [origin, origin + (n - 1) * resolution].
  double min_x() const { return origin_.x(); }
  double min_y() const { return origin_.y(); }
  double max_x() const { return origin_.x() + (nx_ - 1) * resolution_; }
  double max_y() const { return origin_.y() + (ny_ - 1) * resolution_; }
  bool Contains(double x, double y) const;

  /// Sample access. Preconditions: 0 <= i < nx, 0 <= j < ny.
  float& at(int i, int j) { return heights_[Index(i, j)]; }
  float at(int i, int j) const { return heights_[Index(i, j)]; }
  Soil& soil(int i, int j) { return soils_[Index(i, j)]; }
  Soil soil(int i, int j) const { return soils_[Index(i, j)]; }

  /// [m] bilinear height at (x, y), clamped to the grid.
  double Height(double x, double y) const;
  /// Height and its gradient (dz/dx, dz/dy) of the bilinear interpolant at (x, y).
  double HeightAndGradient(double x, double y, Eigen::Vector2d* gradient) const;
  /// Upward unit normal of the interpolated surface at (x, y).
  Eigen::Vector3d Normal(double x, double y) const;
  /// Soil of the nearest sample.
  Soil SoilAt(double x, double y) const;

  /// Sample index nearest to (x, y), clamped.
  void NearestCell(double x, double y, int* i, int* j) const;

  const std::vector<float>& heights() const { return heights_; }
  const std::vector<Soil>& soils() const { return soils_; }

 private:
  std::size_t Index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i);
  }
  int nx_ = 0;
  int ny_ = 0;
  double resolution_ = 1.0;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  std::vector<float> heights_;
  std::vector<Soil> soils_;
};

}  // namespace rover::sim::terrain
