// Side walls and what a keff run reports (issue 35): a simple-cubic lattice between the x faces
// against its closed form with both contact circles (k_eff wall to wall, k_core, the walls'
// shares of the drop); the wall contact radius against its closed form and as the pair's limit
// r_j → ∞; the k_core estimator on a uniform conductor (exact); the profile's R².
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/keff/core_conductivity.hpp"
#include "powderbed/keff/paths.hpp"
#include "powderbed/keff/profile.hpp"
#include "powderbed/keff/solve.hpp"

using namespace powderbed;
namespace kf = powderbed::keff;

namespace {

constexpr double kR = 0.5e-3;           // particle radius, m
constexpr double kOverlap = 1e-3 * kR;  // pair and wall overlap, m
constexpr int kLayers = 8;              // along x, between the walls
constexpr int kRows = 3;                // in y and in z

// kLayers × kRows × kRows spheres on a simple-cubic lattice of pitch 2r − δ, the first and last
// layers overlapping the x faces by δ; the y and z faces enclose the rows (adiabatic).
bed::Bed lattice() {
  bed::Bed b;
  const double pitch = 2 * kR - kOverlap;
  for (int i = 0; i < kLayers; ++i)
    for (int j = 0; j < kRows; ++j)
      for (int k = 0; k < kRows; ++k)
        b.add(kR - kOverlap + i * pitch, pitch / 2 + j * pitch, pitch / 2 + k * pitch, kR);
  b.domain.upper = {2 * (kR - kOverlap) + (kLayers - 1) * pitch, kRows * pitch, kRows * pitch};
  return b;
}

kf::KeffScene along_x(kf::ContactCircle circle) {
  kf::KeffScene s;
  s.axis = 0;
  s.gas_path = false;  // contact only: the closed form is a series of contact conductances
  s.contact.circle = circle;
  return s;
}

// A 216-unknown CG solve to 1e-12 of the flows; 1e-9 leaves room without hiding a wrong
// conductance (each enters at the percent level).
constexpr double kSolve = 1e-9;

}  // namespace

TEST(KeffWalls, LatticeBetweenSideWallsMatchesItsClosedFormWithBothCircles) {
  const bed::Bed b = lattice();
  const double pitch = 2 * kR - kOverlap;
  for (const kf::ContactCircle circle : {kf::ContactCircle::hertz, kf::ContactCircle::geometric}) {
    const kf::KeffScene s = along_x(circle);
    const bool hertz = circle == kf::ContactCircle::hertz;
    // Hertz: a = √(R* δ), R* = r/2 for a pair, r for a wall. Geometric: the intersection circles.
    const double a_pair = hertz ? std::sqrt(kR / 2 * kOverlap)
                                : std::sqrt(kR * kR - pitch * pitch / 4);
    const double a_wall = hertz ? std::sqrt(kR * kOverlap)
                                : std::sqrt(kR * kR - (kR - kOverlap) * (kR - kOverlap));
    const double g_pair = 2 * s.solid_conductivity * a_pair;
    const double g_wall = 2 * s.solid_conductivity * a_wall;
    const double g_row = 1 / (2 / g_wall + (kLayers - 1) / g_pair);
    const double area = b.domain.length(1) * b.domain.length(2);
    const double k_eff = kRows * kRows * g_row * b.domain.length(0) / area;
    const kf::KeffResult r = kf::solve_keff(b, s);
    EXPECT_NEAR(r.k_eff, k_eff, kSolve * k_eff);
    // The core: one pair conductance per pitch of a row of cross-section pitch².
    const double flux = (r.heat_flow_hot + r.heat_flow_cold) / 2 / area;
    const kf::CoreConductivity c = kf::core_conductivity(b, s.axis, r.temperature, r.rattlers, flux,
                                                         s.hot_temperature, s.cold_temperature);
    const double k_core = g_pair / pitch;
    EXPECT_NEAR(c.k_core, k_core, kSolve * k_core);
    EXPECT_EQ(c.particles, static_cast<std::size_t>((kLayers - 4) * kRows * kRows));
    // Each wall's share: the wall contact's drop less the core line's over the half-pitch
    // r − δ from the first centre to the wall.
    const double dt = s.hot_temperature - s.cold_temperature;
    const double q_row = g_row * dt;
    const double drop = (q_row / g_wall - q_row / g_pair * (kR - kOverlap) / pitch) / dt;
    EXPECT_NEAR(c.drop_hot, drop, 1e-8);
    EXPECT_NEAR(c.drop_cold, drop, 1e-8);
  }
  // The two circles: δ ≪ r, so the geometric pair radius is √2 the Hertz one (a² ≈ 2 R* δ).
  const kf::KeffResult hertz = kf::solve_keff(b, along_x(kf::ContactCircle::hertz));
  const kf::KeffResult geo = kf::solve_keff(b, along_x(kf::ContactCircle::geometric));
  EXPECT_NEAR(geo.k_eff / hertz.k_eff, std::sqrt(2.0), 1e-3);  // O(δ/r) = 1e-3 from √2
}

TEST(KeffWalls, WallContactRadiusIsItsClosedFormAndThePairsLimit) {
  // A linear-spring bed (k_n), read at E*: δ_h = (3 k_n δ / (4 E* √r))^{2/3} at a wall.
  kf::ContactRadiusParams p;
  p.hertz_correction = true;
  p.law = kf::BedContactLaw::linear;
  p.stiffness = 1e5;
  p.wall_modulus = 1.1e11;
  p.pair_modulus = 1.1e11;
  const double delta = 2e-6;
  const double delta_h = std::pow(3 * p.stiffness * delta / (4 * p.wall_modulus * std::sqrt(kR)),
                                  2.0 / 3.0);
  p.circle = kf::ContactCircle::hertz;
  EXPECT_NEAR(kf::wall_contact_radius(p, kR, kR - delta), std::sqrt(kR * delta_h),
              1e-14 * kR);
  p.circle = kf::ContactCircle::geometric;
  // R_c = √(2 r δ_h − δ_h²): the plane's cut through the sphere at the corrected overlap.
  EXPECT_NEAR(kf::wall_contact_radius(p, kR, kR - delta), std::sqrt(2 * kR * delta_h - delta_h * delta_h),
              1e-14 * kR);
  // The pair law at r_j → ∞ is the wall's: both circles, without correction. The pair's
  // R* = r r_j / (r + r_j) and intersection circle differ from the wall's by O(r / r_j).
  kf::ContactRadiusParams raw;
  for (const kf::ContactCircle circle : {kf::ContactCircle::hertz, kf::ContactCircle::geometric}) {
    raw.circle = circle;
    const double wall = kf::wall_contact_radius(raw, kR, kR - delta);
    const double big = 1e6 * kR;
    EXPECT_NEAR(kf::pair_contact_radius(raw, kR, big, kR + big - delta), wall, 1e-5 * wall);
  }
}

TEST(KeffWalls, CoreConductivityOfAUniformConductorIsExact) {
  // Centres in a box, temperatures on the straight line of a conductor k: the estimator
  // returns k, no drop at either wall, and an R² of 1, to round-off.
  bed::Bed b;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  b.domain.upper = {4e-3, 2e-3, 12e-3};
  // Pairs placed symmetrically about the centres of 30 bins: each bin's mean temperature is
  // then the line's at its centre exactly, so the profile's R² is 1 to round-off too.
  constexpr int kBins = 30;
  const double width = 12e-3 / kBins;
  for (int bin = 0; bin < kBins; ++bin)
    for (int p = 0; p < 8; ++p) {
      const double centre = (bin + 0.5) * width, offset = (u(rng) - 0.5) * width;
      for (const double z : {centre + offset, centre - offset})
        b.add(4e-3 * u(rng), 2e-3 * u(rng), z, 0.2e-3);
    }
  const double k = 0.37, t_cold = 295, t_hot = 305, h = b.domain.length(2);
  std::vector<double> t(b.n());
  for (std::size_t p = 0; p < b.n(); ++p) t[p] = t_cold + (t_hot - t_cold) * b.z[p] / h;
  const double flux = k * (t_hot - t_cold) / h;
  const kf::CoreConductivity c = kf::core_conductivity(b, 2, t, {}, flux, t_hot, t_cold);
  EXPECT_NEAR(c.k_core, k, 1e-12 * k);
  EXPECT_NEAR(c.drop_hot, 0, 1e-12);
  EXPECT_NEAR(c.drop_cold, 0, 1e-12);
  EXPECT_NEAR(c.margin, 4 * 0.2e-3, 1e-15);  // two mean diameters (a mean of 480 radii)
  const kf::TemperatureProfile profile = kf::temperature_profile(b, 2, t, {}, kBins);
  EXPECT_NEAR(kf::profile_r_squared(profile), 1, 1e-12);
  // A jump at the hot wall (the top bins 1 K cooler) is seen by R².
  for (std::size_t p = 0; p < b.n(); ++p)
    if (b.z[p] > h - 2e-3) t[p] -= 1;
  EXPECT_LT(kf::profile_r_squared(kf::temperature_profile(b, 2, t, {}, kBins)), 0.99);
}

TEST(KeffWalls, AnAxisWhoseWallsTheBedDoesNotReachSaysHowFar) {
  bed::Bed b = lattice();
  b.domain.upper[1] += 3 * kR;  // along y the last rows stop 3 r short of the upper face
  kf::KeffScene s = along_x(kf::ContactCircle::geometric);
  s.axis = 1;
  try {
    kf::solve_keff(b, s);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("hot wall"), std::string::npos) << what;
    EXPECT_NE(what.find("nearest particle"), std::string::npos) << what;
    EXPECT_NE(what.find("0.0015 m"), std::string::npos) << what;  // 3 r plus the half-overlap
  }
}
