#include "rover/apl/sequencer/units.hpp"

#include <array>
#include <numbers>

#include "rover/base/check.hpp"
#include "rover/base/units.hpp"

namespace rover::apl::sequencer {
namespace {

constexpr std::array<Unit, 16> kUnits{{
    {"", Dimension::kNone, 1.0},
    {"m", Dimension::kLength, 1.0},
    {"cm", Dimension::kLength, 0.01},
    {"mm", Dimension::kLength, 0.001},
    {"km", Dimension::kLength, 1000.0},
    {"deg", Dimension::kAngle, kDegree},
    {"rad", Dimension::kAngle, 1.0},
    {"s", Dimension::kTime, 1.0},
    {"ms", Dimension::kTime, 0.001},
    {"min", Dimension::kTime, 60.0},
    {"h", Dimension::kTime, 3600.0},
    {"m/s", Dimension::kSpeed, 1.0},
    {"cm/s", Dimension::kSpeed, 0.01},
    {"1/m", Dimension::kCurvature, 1.0},
    {"px", Dimension::kPixel, 1.0},
    {"count", Dimension::kNone, 1.0},  // declared-only alias of "" for integer arguments
}};

}  // namespace

const Unit* FindUnit(std::string_view name) {
  if (name.empty() || name == "count") return nullptr;  // never written after a number
  for (const Unit& u : kUnits) {
    if (u.name == name) return &u;
  }
  return nullptr;
}

const Unit& DeclaredUnit(std::string_view name) {
  for (const Unit& u : kUnits) {
    if (u.name == name) return u;
  }
  ROVER_DEMAND_MSG(false, "the command table or a quantity declares an unknown unit");
  ROVER_UNREACHABLE();
}

std::string DimensionPhrase(Dimension d) {
  switch (d) {
    case Dimension::kNone: return "a plain number";
    case Dimension::kLength: return "a length";
    case Dimension::kAngle: return "an angle";
    case Dimension::kTime: return "a time";
    case Dimension::kSpeed: return "a speed";
    case Dimension::kCurvature: return "a curvature";
    case Dimension::kPixel: return "a pixel coordinate";
  }
  ROVER_UNREACHABLE();
}

std::string UnitsOf(Dimension d) {
  std::string out;
  for (const Unit& u : kUnits) {
    if (u.dimension != d || u.name.empty() || u.name == "count") continue;
    if (!out.empty()) out += ", ";
    out += u.name;
  }
  return out.empty() ? "no unit" : out;
}

std::vector<std::string> UnitNames() {
  std::vector<std::string> out;
  for (const Unit& u : kUnits) {
    if (!u.name.empty() && u.name != "count") out.emplace_back(u.name);
  }
  return out;
}

Result<double> ConvertUnit(double value, const Unit& from, const Unit& to, std::string_view what) {
  if (from.dimension != to.dimension) {
    std::string m = "unit '" + std::string(from.name) + "' is " + DimensionPhrase(from.dimension) +
                    "; " + std::string(what) + " takes " + DimensionPhrase(to.dimension);
    if (to.dimension != Dimension::kNone) m += " (" + UnitsOf(to.dimension) + ")";
    return InvalidArgument(m);
  }
  return value * from.to_si / to.to_si;
}

}  // namespace rover::apl::sequencer
