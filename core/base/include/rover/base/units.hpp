#pragma once
/// @file
/// Unit constants the whole stack shares, so that no file defines its own. Angles are radians
/// everywhere in code; a value in degrees is multiplied by `kDegree` where it enters (a
/// parameter, a scenario key, a test's literal). C++17-clean: the simulator's Simbody
/// translation units include it.

namespace rover {

inline constexpr double kPi = 3.14159265358979323846;
/// [rad] one degree.
inline constexpr double kDegree = kPi / 180.0;
/// [m/s^2] surface gravity of Mars (the simulator's and the pose estimator's default).
inline constexpr double kMarsGravity = 3.711;

/// [rad] of an angle in degrees.
constexpr double DegToRad(double deg) { return deg * kDegree; }

}  // namespace rover
