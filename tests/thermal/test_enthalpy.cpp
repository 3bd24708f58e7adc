// The enthalpy form of the apparent heat capacity (docs/physics.md §5, enthalpy.hpp): across a window
// the curve absorbs exactly the latent heat plus the sensible heat of the mean capacity, and
// the tabulated inverse returns the temperature within a fraction of a kelvin.
#include <gtest/gtest.h>

#include <cmath>

#include "powderbed/thermal/enthalpy.hpp"
#include "powderbed/thermal/material.hpp"
#include "sinter_beds.hpp"

using namespace powderbed;

namespace {

// 316L with the window `window`, the solver's table range (enthalpy from T0 = 363 K, table from
// T0/2 to T_v + ΔT + 5000 K).
struct Curve {
  thermal::Material material;
  thermal::EnthalpyCurve per_kg, per_m3;
  explicit Curve(double window)
      : material(make(window)),
        per_kg(material, thermal::EnthalpyCurve::Per::kilogram, 363, 181.5, 3130 + window + 5000),
        per_m3(material, thermal::EnthalpyCurve::Per::cubic_metre, 363, 181.5,
               3130 + window + 5000) {}
  static thermal::Material make(double window) {
    thermal::PhaseChange phase;
    phase.window = window;
    return thermal::Material(test::table_316l(), phase, 1400, thermal::LiquidConductivity::solid);
  }
};

}  // namespace

TEST(Enthalpy, MeltingAndVaporisationAbsorbExactlyTheLatentHeat) {
  for (const double window : {20.0, 1.0}) {
    const Curve c(window);
    const auto& p = c.material.phase_change();
    const double half = 0.5 * window;
    const double c_solid = c.material.solid_specific_heat(p.melting_point);  // held from 1400 K
    const double c_liquid = c.material.liquid_specific_heat();
    const double melt = c.per_kg.enthalpy(p.melting_point + half) -
                        c.per_kg.enthalpy(p.melting_point - half);
    const double expected_melt = p.latent_melt + 0.5 * (c_solid + c_liquid) * window;
    // The window's capacity is constant and its ends are breakpoints of the curve: the
    // integral is exact up to round-off of a ~1e6 J/kg cumulative sum, 1e-9 relative.
    EXPECT_NEAR(melt, expected_melt, 1e-9 * expected_melt) << "window " << window;
    // The gas has no data of its own ([GZ]): c_g = c_l.
    const double vapour = c.per_kg.enthalpy(p.boiling_point + half) -
                          c.per_kg.enthalpy(p.boiling_point - half);
    const double expected_vapour = p.latent_vapour + c_liquid * window;
    EXPECT_NEAR(vapour, expected_vapour, 1e-9 * expected_vapour) << "window " << window;
    // Outside the windows the curve has the plain capacities: the enthalpy from T0 to 293 K's
    // neighbour 366 K is the trapezoid of the linear table, exact for a linear c.
    const double sensible = c.per_kg.enthalpy(366) - c.per_kg.enthalpy(363);
    const double c363 = c.material.solid_specific_heat(363);
    EXPECT_NEAR(sensible, 0.5 * (c363 + 485) * 3, 1e-9 * sensible);
    // Zero at T0 up to the round-off of shifting a ~1e5 J/kg cumulative sum.
    EXPECT_NEAR(c.per_kg.enthalpy(363), 0.0, 1e-9);
  }
}

// Per cubic metre the integrand rho(T) c(T) is quadratic where the density blends across the
// melting window; two-point Gauss–Legendre is exact for it. Check against composite Simpson.
TEST(Enthalpy, VolumetricCurveIntegratesDensityTimesCapacity) {
  const Curve c(20);
  const auto& m = c.material;
  const double lo = 1690, hi = 1710;  // the melting window exactly
  const int n = 2000;
  const double h = (hi - lo) / n;
  double simpson = 0;
  for (int i = 0; i <= n; ++i) {
    const double t = lo + h * i;
    const double f = m.density(t) * m.apparent_heat_capacity(t);
    simpson += f * (i == 0 || i == n ? 1 : (i % 2 == 1 ? 4 : 2));
  }
  simpson *= h / 3;
  // Simpson is exact for the quadratic integrand; 1e-9 covers round-off of 2000 terms of 1e8.
  EXPECT_NEAR(c.per_m3.enthalpy(hi) - c.per_m3.enthalpy(lo), simpson, 1e-9 * simpson);
}

// The inverse is linear interpolation in a 65536-point table evenly spaced in enthalpy: about
// 190 J/kg per entry (12.4 MJ/kg range). Where T(e) is smooth the error is ~1e-6 K; in an entry
// that straddles a kink of T(e) (a window edge) it is at most step |1/c_a - 1/c_b| / 4
// <= 190 / (4 * 452) = 0.1 K. no result here needs finer; 0.11 K is that bound.
TEST(Enthalpy, InverseRoundTripsWithinTheTableError) {
  for (const double window : {20.0, 1.0}) {
    const Curve c(window);
    double worst = 0, worst_m3 = 0;
    for (double t = 200; t < 8000; t += 0.37) {
      worst = std::max(worst, std::abs(c.per_kg.temperature(c.per_kg.enthalpy(t)) - t));
      worst_m3 = std::max(worst_m3, std::abs(c.per_m3.temperature(c.per_m3.enthalpy(t)) - t));
    }
    EXPECT_LT(worst, 0.11) << "window " << window;
    EXPECT_LT(worst_m3, 0.11) << "window " << window;
    // Inside the windows the capacity is huge (L/ΔT) and T(e) is nearly flat: the round trip
    // is far better there.
    const double tm = c.material.phase_change().melting_point;
    EXPECT_NEAR(c.per_kg.temperature(c.per_kg.enthalpy(tm)), tm, 0.01 * window);
    // Beyond the table ends the curve continues linearly with the end capacity.
    EXPECT_NEAR(c.per_kg.temperature(c.per_kg.enthalpy(100)), 100, 1e-6);
    EXPECT_NEAR(c.per_kg.temperature(c.per_kg.enthalpy(9000)), 9000, 1e-6);
  }
}

TEST(Enthalpy, MinimumCapacityIsTheSolidAtTheTableStart) {
  const Curve c(20);
  // 452 J/kgK at 293 K and below (held) is the smallest capacity of 316L.
  EXPECT_DOUBLE_EQ(c.per_kg.min_capacity(), 452.0);
  EXPECT_DOUBLE_EQ(c.per_kg.capacity(1700), 0.5 * (c.material.solid_specific_heat(1700) + 815) +
                                                2.99e5 / 20);
}
