#include "rover/hwconfig/lander_description.hpp"

#include <cmath>
#include <string>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/base/range_check.hpp"
#include "rover/base/units.hpp"

namespace rover::hwconfig {
namespace {

int StripeUnitsTotal(int ramp) {
  int s = 0;
  for (int c : kRampStripeCodes[static_cast<std::size_t>(ramp)]) s += c;
  return s;
}

}  // namespace

Status LanderDescription::Validate(const char* prefix) const {
  const std::string p(prefix);
  ROVER_RETURN_IF_ERROR(CheckRange(p + "deck_height", deck_height, 0.2, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "deck_thickness", deck_thickness, Bounds{0.0, deck_height, true, true}, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "deck_radius", deck_radius, 0.3, 10.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "ramp_length", ramp_length, Bounds::OpenLow(0.0, 20.0), "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "ramp_width", ramp_width, Bounds::OpenLow(0.0, deck_radius), "m"));
  ROVER_RETURN_IF_ERROR(CheckPositive(p + "stripe_unit", stripe_unit, "m"));
  ROVER_RETURN_IF_ERROR(CheckNonNegative(p + "stripe_gap", stripe_gap, "m"));
  if (StripeBlockLength() > ramp_length) {
    return InvalidArgument(p + "stripe_unit: the six stripes need " +
                           FormatNumber(StripeBlockLength()) + " m along the ramp, more than " +
                           p + "ramp_length " + FormatNumber(ramp_length));
  }
  if (!(ramp_width > 2.0 * kStripeMargin)) {
    return InvalidArgument(p + "ramp_width: " + FormatNumber(ramp_width) +
                           " m leaves no room for stripes (" + FormatNumber(kStripeMargin) +
                           " m margins)");
  }
  return Status::Ok();
}

void LanderDescription::BindParams(ParamBinder<LanderDescription>& b) {
  using D = LanderDescription;
  b.Bind("deck_height", &D::deck_height, "m", "deck top above the ground at the deck centre");
  b.Bind("deck_thickness", &D::deck_thickness, "m", "deck slab thickness");
  b.Bind("deck_radius", &D::deck_radius, "m", "circumradius of the hexagonal deck");
  b.Bind("ramp_length", &D::ramp_length, "m", "horizontal run of a ramp beyond the deck edge");
  b.Bind("ramp_width", &D::ramp_width, "m", "ramp width (at most deck_radius)");
  b.Bind("stripe_unit", &D::stripe_unit, "m", "stripe width per code unit (codes 2..7)");
  b.Bind("stripe_gap", &D::stripe_gap, "m", "gap between neighbouring stripes along the ramp");
}

double LanderDescription::Apothem() const { return deck_radius * std::cos(30.0 * kDegree); }

double LanderDescription::StripeBlockLength() const {
  return StripeUnitsTotal(0) * stripe_unit + (kStripesPerRamp - 1) * stripe_gap;
}

StripeLayout LanderDescription::Stripe(int ramp, int index) const {
  ROVER_DEMAND(ramp >= 0 && ramp < 2 && index >= 0 && index < kStripesPerRamp);
  const auto& codes = kRampStripeCodes[static_cast<std::size_t>(ramp)];
  double from_bottom = 0.0;
  for (int s = 0; s < index; ++s) {
    from_bottom += codes[static_cast<std::size_t>(s)] * stripe_unit + stripe_gap;
  }
  StripeLayout st;
  st.ramp = ramp;
  st.index = index;
  st.code = codes[static_cast<std::size_t>(index)];
  st.width = st.code * stripe_unit;
  st.length = ramp_width - 2.0 * kStripeMargin;
  st.u = -0.5 * StripeBlockLength() + from_bottom + 0.5 * st.width;
  return st;
}

}  // namespace rover::hwconfig
