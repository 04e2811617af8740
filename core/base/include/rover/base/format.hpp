#pragma once
/// @file
/// Number formatting for messages, logs and reports: one form everywhere, so that an error about
/// a value reads the same whichever module raised it.

#include <span>
#include <string>

namespace rover {

/// `v` with `significant` significant digits in the shortest of fixed or exponent form, as
/// printf's %g does ("0.125", "1e-06", "nan", "inf", "-inf"). Preconditions: 1 <= significant
/// <= 17.
std::string FormatNumber(double v, int significant = 6);

/// An image or grid size as "<width>x<height>" ("640x480").
std::string FormatSize(int width, int height);

// The simulator's Simbody translation unit is C++17 (no std::span); it uses FormatNumber only.
#if __cplusplus >= 202002L
/// "[a, b, c]" with FormatNumber for each element.
std::string FormatList(std::span<const double> values, int significant = 6);
#endif

}  // namespace rover
