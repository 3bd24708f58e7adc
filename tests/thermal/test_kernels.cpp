// Each law of docs/physics.md §5 on its own: apparent heat capacity, contact geometry, Beer–Lambert
// laser with the Gusarov extinction, surface losses.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "powderbed/thermal/apparent_heat_capacity.hpp"
#include "powderbed/thermal/beer_lambert_laser.hpp"
#include "powderbed/thermal/contact_conduction.hpp"
#include "powderbed/thermal/surface_losses.hpp"

using namespace powderbed::thermal;
using std::numbers::pi;

TEST(ApparentHeatCapacity, FiveBranches) {
  const ApparentHeatCapacityParams p{1700, 3130, 20, 2.99e5, 6.09e6};
  const double cs = 600, cl = 815, cg = 900;
  const auto c = [&](double t) { return apparent_heat_capacity(t, cs, cl, cg, p); };
  EXPECT_EQ(c(1000), cs);
  EXPECT_EQ(c(1689.999), cs);
  EXPECT_EQ(c(1690), 0.5 * (cs + cl) + 2.99e5 / 20);  // window edges belong to the window
  EXPECT_EQ(c(1700), 0.5 * (cs + cl) + 2.99e5 / 20);
  EXPECT_EQ(c(1710), 0.5 * (cs + cl) + 2.99e5 / 20);
  EXPECT_EQ(c(1710.001), cl);
  EXPECT_EQ(c(3119.999), cl);
  EXPECT_EQ(c(3120), 0.5 * (cl + cg) + 6.09e6 / 20);
  EXPECT_EQ(c(3140), 0.5 * (cl + cg) + 6.09e6 / 20);
  EXPECT_EQ(c(3140.001), cg);
  EXPECT_EQ(c(5000), cg);
}

TEST(ContactConduction, IntersectionCircleOfTwoSpheres) {
  const double r = 10e-6;
  for (const double d : {19.99e-6, 19e-6, 15e-6, 10e-6}) {
    // Equal spheres: the plane bisects d, a = sqrt(r^2 - d^2/4); 1e-12 relative is round-off.
    const double a = std::sqrt(r * r - 0.25 * d * d);
    EXPECT_NEAR(contact_radius(r, r, d), a, 1e-12 * r) << d;
  }
  // Unequal: the circle is the same seen from either sphere.
  const double r1 = 20e-6, r2 = 7e-6, d = 25e-6;
  const double x1 = (d * d + r1 * r1 - r2 * r2) / (2 * d);
  const double a = contact_radius(r1, r2, d);
  EXPECT_NEAR(a * a + x1 * x1, r1 * r1, 1e-12 * r1 * r1);
  EXPECT_NEAR(a * a + (d - x1) * (d - x1), r2 * r2, 1e-12 * r1 * r1);
  EXPECT_NEAR(contact_radius(r2, r1, d), a, 1e-12 * r1);  // either order: round-off apart
  EXPECT_EQ(contact_radius(r, r, 2 * r), 0.0);      // touching: no area
  EXPECT_EQ(contact_radius(r, r, 2.5 * r), 0.0);    // apart
  EXPECT_EQ(contact_radius(r1, r2, 10e-6), r2);     // the small one inside the big one
  EXPECT_DOUBLE_EQ(plane_contact_radius(r, 0.6 * r), 0.8 * r);
  EXPECT_EQ(plane_contact_radius(r, r), 0.0);
  EXPECT_DOUBLE_EQ(conduction_shape_factor(2e-6, 4e-6), pi * 4e-12 / 4e-6);
}

TEST(BeerLambertLaser, GaussianBeamAndGusarovExtinction) {
  // Gusarov: beta = 3 (1 - gamma) / (2 gamma D); [GZ]'s gamma = 0.55, D = 27 µm.
  EXPECT_DOUBLE_EQ(gusarov_extinction(0.55, 27e-6), 3 * 0.45 / (2 * 0.55 * 27e-6));
  EXPECT_NEAR(gusarov_extinction(0.55, 27e-6), 45454.545454545, 1e-6);  // 1/m
  const LaserParams p{200, 54e-6, 0.33, 4e4};
  const double i0 = 2 * 200 / (pi * 54e-6 * 54e-6);
  EXPECT_DOUBLE_EQ(peak_intensity(p), i0);
  EXPECT_DOUBLE_EQ(absorbed_flux(p, 0, 0), 0.33 * i0);
  // At r = w the intensity is exp(-2) of the peak; 1/beta deep it is exp(-1) of the surface.
  EXPECT_NEAR(absorbed_flux(p, 54e-6 * 54e-6, 0), 0.33 * i0 * std::exp(-2.0), 1e-12 * i0);
  EXPECT_NEAR(absorbed_flux(p, 0, 1 / 4e4), 0.33 * i0 * std::exp(-1.0), 1e-12 * i0);
  // The beam carries P: ∫ I 2πr dr = I0 π w^2 / 2 = P.
  EXPECT_DOUBLE_EQ(peak_intensity(p) * pi * 54e-6 * 54e-6 / 2, 200);
}

TEST(SurfaceLosses, ConvectionAndRadiation) {
  const SurfaceParams p{40, 0.33, 363};
  const double area = pi * 1e-10;
  EXPECT_DOUBLE_EQ(convection_gain(p, 363, area), 0.0);
  EXPECT_DOUBLE_EQ(convection_gain(p, 1363, area), -40 * 1000 * area);
  EXPECT_DOUBLE_EQ(radiation_gain(p, 363, area), 0.0);
  const double t = 2000;
  EXPECT_NEAR(radiation_gain(p, t, area),
              0.33 * kStefanBoltzmann * (std::pow(363.0, 4) - std::pow(t, 4)) * area,
              1e-12 * 0.33 * kStefanBoltzmann * std::pow(t, 4) * area);  // round-off
  // d(loss)/dT = 4 eps sigma T^3 A, by central differences (step 1e-3 K: truncation ~1e-12).
  const double h = 1e-3;
  const double slope = -(radiation_gain(p, t + h, area) - radiation_gain(p, t - h, area)) / (2 * h);
  EXPECT_NEAR(radiation_conductance(p, t, area), slope, 1e-6 * slope);
}
