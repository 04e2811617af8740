#pragma once
/// @file
/// Units of the sequence language. Every number an argument, constant or comparison takes has a
/// dimension; a literal may name its unit (`30 cm`, `0.5 rad`, `2 min`) and is converted to the
/// unit its context expects, or carry none and is read in that unit. Conversion is linear:
///   value_in_target = value * from.to_si / to.to_si.
/// Known units: length m cm mm km; angle deg rad; time s ms min h; speed m/s cm/s;
/// curvature 1/m (no suffix form); pixel px; counts take no unit.

#include <string>
#include <string_view>
#include <vector>

#include "rover/base/status.hpp"

namespace rover::apl::sequencer {

enum class Dimension { kNone, kLength, kAngle, kTime, kSpeed, kCurvature, kPixel };

struct Unit {
  std::string_view name;  ///< "cm"
  Dimension dimension = Dimension::kNone;
  double to_si = 1.0;  ///< metres, radians, seconds, m/s, 1/m or pixels per unit
};

/// The unit spelled `name` (case-sensitive), or nullptr.
const Unit* FindUnit(std::string_view name);
/// The unit `name` that a table or quantity declares; a name that is not a unit is a
/// programming error. "" is the dimensionless unit.
const Unit& DeclaredUnit(std::string_view name);
/// "a length", "an angle", ... for messages.
std::string DimensionPhrase(Dimension d);
/// The unit names of a dimension ("m, cm, mm, km"), for messages.
std::string UnitsOf(Dimension d);
/// The names of every unit (for "did you mean").
std::vector<std::string> UnitNames();

/// `value` given in `from` expressed in `to`. Errors: InvalidArgument when the dimensions differ,
/// e.g. "unit 's' is a time; distance takes a length (m, cm, mm, km)" (`what` names the
/// consumer: "distance").
Result<double> ConvertUnit(double value, const Unit& from, const Unit& to, std::string_view what);

}  // namespace rover::apl::sequencer
