#include "rover/base/format.hpp"

#include <cstdio>

#include "rover/base/check.hpp"

namespace rover {

std::string FormatNumber(double v, int significant) {
  ROVER_DEMAND(significant >= 1 && significant <= 17);
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", significant, v);
  return buf;
}

std::string FormatSize(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

std::string FormatList(std::span<const double> values, int significant) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) out += ", ";
    out += FormatNumber(values[i], significant);
  }
  return out + "]";
}

}  // namespace rover
