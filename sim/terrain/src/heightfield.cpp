#include "rover/sim/heightfield.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/check.hpp"

namespace rover::sim::terrain {

const char* SoilName(Soil s) {
  switch (s) {
    case Soil::kBedrock: return "bedrock";
    case Soil::kFirmSoil: return "firm_soil";
    case Soil::kLooseSand: return "loose_sand";
  }
  return "?";
}

HeightField::HeightField(int nx, int ny, double resolution, Eigen::Vector2d origin)
    : nx_(nx), ny_(ny), resolution_(resolution), origin_(origin) {
  ROVER_DEMAND(nx >= 2 && ny >= 2 && resolution > 0.0);
  heights_.assign(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), 0.0f);
  soils_.assign(heights_.size(), Soil::kFirmSoil);
}

bool HeightField::Contains(double x, double y) const {
  return x >= min_x() && x <= max_x() && y >= min_y() && y <= max_y();
}

double HeightField::HeightAndGradient(double x, double y, Eigen::Vector2d* gradient) const {
  const double fx = std::clamp((x - origin_.x()) / resolution_, 0.0, nx_ - 1.0);
  const double fy = std::clamp((y - origin_.y()) / resolution_, 0.0, ny_ - 1.0);
  const int i = std::min(static_cast<int>(fx), nx_ - 2);
  const int j = std::min(static_cast<int>(fy), ny_ - 2);
  const double u = fx - i;
  const double v = fy - j;
  const double h00 = at(i, j), h10 = at(i + 1, j), h01 = at(i, j + 1), h11 = at(i + 1, j + 1);
  if (gradient != nullptr) {
    const bool clamped_x = x < min_x() || x > max_x();
    const bool clamped_y = y < min_y() || y > max_y();
    (*gradient)(0) = clamped_x ? 0.0 : ((h10 - h00) * (1 - v) + (h11 - h01) * v) / resolution_;
    (*gradient)(1) = clamped_y ? 0.0 : ((h01 - h00) * (1 - u) + (h11 - h10) * u) / resolution_;
  }
  return h00 * (1 - u) * (1 - v) + h10 * u * (1 - v) + h01 * (1 - u) * v + h11 * u * v;
}

double HeightField::Height(double x, double y) const { return HeightAndGradient(x, y, nullptr); }

Eigen::Vector3d HeightField::Normal(double x, double y) const {
  Eigen::Vector2d g;
  HeightAndGradient(x, y, &g);
  return Eigen::Vector3d(-g(0), -g(1), 1.0).normalized();
}

void HeightField::NearestCell(double x, double y, int* i, int* j) const {
  *i = std::clamp(static_cast<int>(std::lround((x - origin_.x()) / resolution_)), 0, nx_ - 1);
  *j = std::clamp(static_cast<int>(std::lround((y - origin_.y()) / resolution_)), 0, ny_ - 1);
}

Soil HeightField::SoilAt(double x, double y) const {
  int i = 0, j = 0;
  NearestCell(x, y, &i, &j);
  return soil(i, j);
}

}  // namespace rover::sim::terrain
