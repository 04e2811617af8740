#pragma once
/// @file
/// The Golombek & Rapp (1997) rock size-frequency model and sampling from it.
///
/// Cumulative fractional area covered by rocks of diameter >= D (D in metres):
///     F_k(D) = k exp(-q(k) D),      q(k) = 1.79 + 0.152 / k,
/// k = total fraction of the surface covered by rocks (all sizes). Viking Lander 1 is k ~ 0.07,
/// Viking Lander 2 k ~ 0.17; Mars rock abundance ranges over about 0.05-0.40.
///
/// A rock of diameter D covers a(D) = pi D^2 / 4 (circular footprint of equal area), so the
/// differential number density [rocks m^-2 per metre of diameter] is
///     n(D) = -F_k'(D) / a(D) = 4 k q exp(-q D) / (pi D^2).
/// n diverges as D -> 0, so a generated field is truncated to D in [d_min, d_max].
///
/// For a Poisson field of such rocks over an area A, the area fraction of rocks with D in
/// [d0, d1] has mean F_k(d0) - F_k(d1) and variance (1/A) * integral_{d0}^{d1} n(D) a(D)^2 dD
/// (used by tests to set a statistically justified tolerance).

#include "rover/sim/terrain/random.hpp"

namespace rover::sim::terrain {

/// q(k) = 1.79 + 0.152 / k   [1/m]. Precondition: k > 0.
double RockExponent(double k);
/// F_k(D): fraction of the surface covered by rocks of diameter >= d. k = 0 gives 0.
double RockCumulativeArea(double k, double d);
/// F_k(d0) - F_k(d1): fraction covered by rocks with diameter in [d0, d1].
double RockAreaFraction(double k, double d0, double d1);
/// n(D) [rocks m^-2 m^-1].
double RockNumberDensity(double k, double d);
/// Expected number of rocks per square metre with D in [d0, d1] (numerical quadrature).
double RockCountPerArea(double k, double d0, double d1);
/// Variance of the area fraction of rocks with D in [d0, d1] over a Poisson field of area
/// `area` [m^2].
double RockAreaFractionVariance(double k, double d0, double d1, double area);
/// Draws one diameter from n(D) restricted to [d_min, d_max] (rejection sampling from the
/// 1/D^2 envelope, accept with probability exp(-q (D - d_min))).
/// Preconditions: k > 0, 0 < d_min < d_max.
double SampleRockDiameter(double k, double d_min, double d_max, Rng* rng);

}  // namespace rover::sim::terrain
