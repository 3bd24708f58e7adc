// Radiation path of the effective-conductivity network (docs/physics.md §6, issue 6): Monte-Carlo view
// factors (sphere on a plane, closed-box rows, reciprocity and its 1/√rays error, thread
// independence) and the Newton solve of the nonlinear network (energy conservation, a closed
// form for one sphere, few steps).
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <utility>

#include "powderbed/bed/bed.hpp"
#include "powderbed/keff/radiation.hpp"
#include "powderbed/keff/solve.hpp"
#include "powderbed/keff/view_factors.hpp"

using namespace powderbed;
namespace kf = powderbed::keff;

namespace {

constexpr double kR = 0.5e-3;  // m

double area(const bed::Bed& b, std::uint32_t p) {
  return 4 * std::numbers::pi * b.radius[p] * b.radius[p];
}

// side³ jittered simple cubic lattice of pitch 2.2 r_0, radii 0.8–1.0 r_0: no two spheres touch
// (so reciprocity holds exactly in the limit), the side faces are mirrors, the z faces walls.
bed::Bed loose_lattice(int side, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> radius(0.8 * kR, kR), jitter(-0.05 * kR, 0.05 * kR);
  const double pitch = 2.2 * kR;
  bed::Bed b;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k)
        b.add((i + 0.5) * pitch + jitter(rng), (j + 0.5) * pitch + jitter(rng),
              (k + 0.5) * pitch + jitter(rng), radius(rng));
  b.domain.upper = {side * pitch, side * pitch, side * pitch};
  return b;
}

// Sum of each particle's row (self, particles and walls).
std::vector<double> row_sums(const kf::ViewFactors& vf, std::size_t n) {
  std::vector<double> sum(n, 0);
  for (const auto& e : vf.entries) sum[e.i] += e.f;
  return sum;
}

std::map<std::pair<std::uint32_t, std::uint32_t>, double> pair_factors(const kf::ViewFactors& vf) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, double> f;
  for (const auto& e : vf.entries)
    if (e.j != kf::kHotWall && e.j != kf::kColdWall && e.j != e.i)
      f[{e.i, e.j}] = e.f;
  return f;
}

// RMS over pairs with F ≥ 0.02 both ways of the reciprocity error A_i F_ij − A_j F_ji, raw and
// over its binomial standard error √(A_i² F_ij(1−F_ij) + A_j² F_ji(1−F_ji)) / √rays.
std::pair<double, double> reciprocity_rms(const bed::Bed& b, const kf::ViewFactors& vf) {
  const auto f = pair_factors(vf);
  double raw = 0, scaled = 0;
  int count = 0;
  for (const auto& [key, fij] : f) {
    const auto [i, j] = key;
    if (i >= j) continue;
    const auto back = f.find({j, i});
    if (back == f.end() || fij < 0.02 || back->second < 0.02) continue;
    const double fji = back->second, ai = area(b, i), aj = area(b, j);
    const double err = ai * fij - aj * fji;
    const double se = std::sqrt((ai * ai * fij * (1 - fij) + aj * aj * fji * (1 - fji)) /
                                static_cast<double>(vf.rays));
    raw += err * err / (ai * aj);
    scaled += err * err / (se * se);
    ++count;
  }
  EXPECT_GT(count, 50);
  return {std::sqrt(raw / count), std::sqrt(scaled / count)};
}

// One sphere of radius kR in a 4 × 4 × 3 kR box, 1.3 kR below the hot wall, 1.7 kR above the cold.
bed::Bed sphere_between_walls() {
  bed::Bed b;
  b.add(2 * kR, 2 * kR, 1.7 * kR, kR);
  b.domain.upper = {4 * kR, 4 * kR, 3 * kR};
  return b;
}

kf::KeffScene radiation_only(double t_hot, double t_cold) {
  kf::KeffScene s;
  s.contact_path = false;
  s.gas_path = false;
  s.radiation_path = true;
  s.hot_temperature = t_hot;
  s.cold_temperature = t_cold;
  s.rays = 2000;
  return s;
}

}  // namespace

TEST(KeffViewFactors, SphereRestingOnPlaneSeesHalf) {
  // One sphere touching the cold wall in a box 400 r wide. The side mirrors make an infinite
  // lattice of images 400 r apart that intercept grazing downward rays: about
  // (z/2ℓ)(1 + ln(ℓ/z)) of the rays with ℓ = (400 r)² / 2r the free path, ~5e-5 here, against
  // 4e-3 in a 40 r box (measured 0.4962 there, 2.4 standard errors low).
  bed::Bed b;
  b.add(200 * kR, 200 * kR, kR, kR);
  b.domain.upper = {400 * kR, 400 * kR, 4 * kR};
  const std::size_t rays = 100000;
  const kf::ViewFactors vf = kf::view_factors(b, {rays, 7, 2, {}});
  double f = 0;
  for (const auto& e : vf.entries)
    if (e.j == kf::kColdWall) f = e.f;
  // F = 0.5 exactly for a sphere tangent to an infinite plane; the estimate is binomial with
  // standard error √(F(1−F)/N) = 1.6e-3: 3 standard errors.
  const double se = std::sqrt(0.25 / static_cast<double>(rays));
  EXPECT_NEAR(f, 0.5, 3 * se);
}

TEST(KeffViewFactors, RowsSumToOneInAClosedBox) {
  const bed::Bed b = loose_lattice(4, 3);
  const kf::ViewFactors vf = kf::view_factors(b, {500, 1, 2, {}});
  EXPECT_EQ(vf.lost_rays, 0u);
  // Walls and mirrors close the box: every ray hits something, and a row is a sum of 500 counts
  // over 500, exact but for the round-off of the division.
  for (const double s : row_sums(vf, b.n())) EXPECT_NEAR(s, 1, 1e-12);
}

TEST(KeffViewFactors, ReciprocityWithinMonteCarloErrorShrinkingAsOneOverRootRays) {
  const bed::Bed b = loose_lattice(3, 5);
  const auto [raw_coarse, scaled_coarse] =
      reciprocity_rms(b, kf::view_factors(b, {1000, 2, 2, {}}));
  const auto [raw_fine, scaled_fine] = reciprocity_rms(b, kf::view_factors(b, {100000, 2, 2, {}}));
  // The errors are sampling noise: RMS over the standard error ≈ 1 (a systematic error, e.g. a
  // wrong emission law or a missed hit, would grow with the rays). 1.5 allows for the RMS of
  // ~100 pairs (±10 %) and the pairs sharing rays.
  EXPECT_LT(scaled_coarse, 1.5);
  EXPECT_LT(scaled_fine, 1.5);
  // 100× the rays: the error shrinks 10× (1/√rays); the RMS of ~100 pairs scatters by ~10 %
  // each, so 6–16.
  EXPECT_GT(raw_coarse / raw_fine, 6);
  EXPECT_LT(raw_coarse / raw_fine, 16);
}

TEST(KeffViewFactors, SameForAnyThreadCount) {
  const bed::Bed b = loose_lattice(3, 9);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const kf::ViewFactors one = kf::view_factors(b, {300, 4, 2, {}});
  omp_set_num_threads(3);
  const kf::ViewFactors three = kf::view_factors(b, {300, 4, 2, {}});
  omp_set_num_threads(threads);
  ASSERT_EQ(one.entries.size(), three.entries.size());
  for (std::size_t k = 0; k < one.entries.size(); ++k) {
    EXPECT_EQ(one.entries[k].i, three.entries[k].i);
    EXPECT_EQ(one.entries[k].j, three.entries[k].j);
    EXPECT_EQ(one.entries[k].f, three.entries[k].f);
  }
}

TEST(KeffRadiation, OneSphereMatchesItsClosedForm) {
  // A sphere between the walls exchanges with each through a grey link: in steady state
  // Q = σ (T_h⁴ − T_c⁴) / (1/G_h + 1/G_c), and T⁴ = (G_h T_h⁴ + G_c T_c⁴) / (G_h + G_c); the
  // walls see each other past it through G_w, which adds σ G_w (T_h⁴ − T_c⁴) to both flows.
  const bed::Bed b = sphere_between_walls();
  kf::KeffScene s = radiation_only(900, 600);
  s.emissivity = 0.7;
  s.wall_emissivity = 0.4;
  const kf::KeffNetwork net = kf::build_keff_network(b, s);
  double g_hot = 0, g_cold = 0;
  for (const auto& l : net.links) (l.j == kf::kHotWall ? g_hot : g_cold) += l.conductance;
  const kf::KeffResult r = kf::solve_keff(b, s, net);
  const double h4 = std::pow(900.0, 4), c4 = std::pow(600.0, 4);
  EXPECT_GT(net.wall_exchange, 0);  // the sphere covers π/16 of the walls
  const double q = kf::kStefanBoltzmann * (h4 - c4) * (1 / (1 / g_hot + 1 / g_cold) +
                                                      net.wall_exchange);
  // Newton stops at a relative residual of 1e-10, one unknown: the flows to ~1e-10.
  EXPECT_NEAR(r.heat_flow_hot, q, 1e-9 * q);
  EXPECT_NEAR(r.heat_flow_cold, q, 1e-9 * q);
  EXPECT_NEAR(std::pow(r.temperature[0], 4), (g_hot * h4 + g_cold * c4) / (g_hot + g_cold),
              1e-9 * h4);
  EXPECT_DOUBLE_EQ(r.share_radiation, 1);
}

TEST(KeffRadiation, RadiationOnlyNetworkConservesEnergy) {
  const bed::Bed b = loose_lattice(4, 11);
  const kf::KeffResult r = kf::solve_keff(b, radiation_only(1200, 400));
  EXPECT_EQ(r.rattlers.size(), 0u);
  EXPECT_GT(r.radiation_links, 0u);
  // The bound on the wall-flow mismatch (it is the sum of the Newton residuals).
  EXPECT_NEAR(r.heat_flow_hot, r.heat_flow_cold, 1e-8 * r.heat_flow_hot);
  EXPECT_LE(r.residual, 1e-10);
  EXPECT_LE(r.newton_iterations, 8u);  // quadratic convergence from the secant start
  EXPECT_DOUBLE_EQ(r.share_radiation, 1);
  for (const double t : r.temperature) {
    EXPECT_GT(t, 400);
    EXPECT_LT(t, 1200);
  }
}

TEST(KeffRadiation, NewtonConvergesInAFewStepsWithAllPaths) {
  // A lattice of spheres overlapping each other and the walls by 1e-3 r, with contact, gas and
  // radiation.
  bed::Bed b;
  const double overlap = 1e-3 * kR, pitch = 2 * kR - overlap, side = 3 * pitch + 2 * kR;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k)
        b.add(kR + i * pitch, kR + j * pitch, kR - overlap + k * pitch, kR);
  b.domain.upper = {side, side, side - 2 * overlap};
  kf::KeffScene s;
  s.radiation_path = true;
  s.hot_temperature = 1500;
  s.cold_temperature = 1300;
  s.rays = 1000;
  const kf::KeffResult r = kf::solve_keff(b, s);
  EXPECT_GE(r.newton_iterations, 1u);
  EXPECT_LE(r.newton_iterations, 5u);  // the secant start is close: quadratic steps
  EXPECT_NEAR(r.heat_flow_hot, r.heat_flow_cold, 1e-8 * r.heat_flow_hot);
  EXPECT_GT(r.share_radiation, 0);
  // Tellegen: the shares are parts of one sum.
  EXPECT_NEAR(r.share_contact + r.share_gas + r.share_radiation, 1, 1e-12);
  // Radiation adds a parallel path: k_eff rises over the conduction-only network.
  kf::KeffScene conduction = s;
  conduction.radiation_path = false;
  EXPECT_GT(r.k_eff, kf::solve_keff(b, conduction).k_eff);
}

TEST(KeffRadiation, ParallelPlatesPastATinySphere) {
  // A sphere of 1e-3 of the gap, radiation only: the walls see each other (F = 1 less the
  // sphere's shadow, ~1e-6) and exchange σ (T_h⁴ − T_c⁴) A / (2/ε_w − 1), grey parallel plates.
  // Both models give it: the pair model's wall link is that formula, the radiosity model's walls
  // are two radiosity nodes.
  bed::Bed b;
  const double gap = 1e-2, r = 1e-3 * gap;
  b.add(gap / 2, gap / 2, gap / 2, r);
  b.domain.upper = {gap, gap, gap};
  for (const kf::RadiationModel model : {kf::RadiationModel::pair, kf::RadiationModel::radiosity}) {
    kf::KeffScene s = radiation_only(900, 500);
    s.radiation_model = model;
    s.wall_emissivity = 0.6;
    s.rays = 200;
    const kf::KeffResult res = kf::solve_keff(b, s);
    const double plates = kf::kStefanBoltzmann * (std::pow(900.0, 4) - std::pow(500.0, 4)) *
                          gap * gap / (2 / 0.6 - 1);
    // The shadow and the sphere's own path are O((r/gap)²) = 1e-6 of the flow; the wall-to-wall
    // F is counted from 1e6 rays per wall, nearly all of which cross (binomial error ~0).
    EXPECT_NEAR(res.heat_flow_hot, plates, 1e-4 * plates);
    EXPECT_NEAR(res.heat_flow_cold, res.heat_flow_hot, 1e-8 * plates);
  }
}

TEST(KeffRadiation, RadiosityModelLetsARadiationOnlySphereIgnoreItsEmissivity) {
  // A sphere that carries heat by radiation alone has no net exchange of its own: in the grey
  // enclosure its radiosity equals its blackbody power and its surface resistance carries
  // nothing, so the heat it passes between black walls is σ (T_h⁴ − T_c⁴) / (1/S_h + 1/S_c)
  // whatever its ε (a re-radiating surface). The pair formula of docs/physics.md §6 instead puts (1−ε)/(εA) in
  // each of its two links, and its flow falls with ε.
  const bed::Bed b = sphere_between_walls();
  kf::KeffScene s = radiation_only(900, 600);
  s.wall_emissivity = 1;
  s.radiation_model = kf::RadiationModel::radiosity;
  const auto flow = [&](double eps, kf::RadiationModel model) {
    kf::KeffScene t = s;
    t.emissivity = eps;
    t.radiation_model = model;
    return kf::solve_keff(b, t).heat_flow_hot;
  };
  const double black = flow(1, kf::RadiationModel::radiosity);
  // Same rays, same exchange areas: the grey sphere's radiosity node removes its surface
  // resistance from the path exactly, to Newton's 1e-10.
  EXPECT_NEAR(flow(0.3, kf::RadiationModel::radiosity), black, 1e-9 * black);
  EXPECT_NEAR(flow(1, kf::RadiationModel::pair), black, 1e-12 * black);  // black: one network
  EXPECT_LT(flow(0.3, kf::RadiationModel::pair), 0.9 * black);
}

TEST(KeffRadiation, RadiosityNetworkOnABedConservesEnergy) {
  const bed::Bed b = loose_lattice(4, 5);
  kf::KeffScene s = radiation_only(1300, 1100);
  s.radiation_model = kf::RadiationModel::radiosity;
  s.emissivity = 0.3;
  s.wall_emissivity = 0.5;
  const kf::KeffNetwork net = kf::build_keff_network(b, s);
  EXPECT_EQ(net.node_count, 2 * b.n() + 2);  // a radiosity node per sphere and per wall
  const kf::KeffResult r = kf::solve_keff(b, s, net);
  ASSERT_EQ(r.temperature.size(), b.n());
  EXPECT_NEAR(r.heat_flow_hot, r.heat_flow_cold, 1e-8 * r.heat_flow_hot);  // the bound
  EXPECT_LE(r.residual, s.newton_tolerance);
  for (const double t : r.temperature) {
    EXPECT_GT(t, 1100);
    EXPECT_LT(t, 1300);
  }
  // With black walls and no conduction every sphere's net exchange is zero, so its radiosity
  // is its blackbody power and the grey network is the black one (as for the single sphere
  // above); the pair formula's per-link surface resistances lower the flow instead.
  s.wall_emissivity = 1;
  kf::KeffScene black = s, pair = s;
  black.emissivity = 1;
  pair.radiation_model = kf::RadiationModel::pair;
  const double k_black = kf::solve_keff(b, black).k_eff;
  EXPECT_NEAR(kf::solve_keff(b, s).k_eff, k_black, 1e-8 * k_black);  // Newton's 1e-10, summed
  EXPECT_LT(kf::solve_keff(b, pair).k_eff, 0.9 * k_black);
}

TEST(KeffRadiation, NetworkReportsTheViewFactorErrorShrinkingAsOneOverRootRays) {
  const bed::Bed b = loose_lattice(3, 9);
  kf::KeffScene s = radiation_only(1000, 900);
  s.rays = 1000;
  const double coarse = kf::build_keff_network(b, s).reciprocity_error;
  s.rays = 10000;
  const double fine = kf::build_keff_network(b, s).reciprocity_error;
  EXPECT_GT(coarse, 0);
  // 10x the rays: √10 = 3.16 less error; 2-5 allows the error's own scatter over ~100 pairs.
  EXPECT_GT(coarse / fine, 2.0);
  EXPECT_LT(coarse / fine, 5.0);
}
