// Hard cases of issue 6 for the effective-conductivity solver (docs/physics.md §6) beyond the rattlers
// and k_g = 0 of test_network.cpp: a bed at 2000 K where the T⁴ links dominate, the air
// model's temperature-dependent k_g against a bisection of the one-sphere balance, a bed one
// particle thick against its per-sphere series closed form, a bimodal bed of size ratio 1:8, and
// a Newton start far from the solution. Every solve must converge with nothing NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "powderbed/bed/bed.hpp"
#include "powderbed/keff/gas_lens.hpp"
#include "powderbed/keff/paths.hpp"
#include "powderbed/keff/solve.hpp"

using namespace powderbed;
namespace kf = powderbed::keff;

namespace {

constexpr double kR = 1e-3;  // m: 2 mm spheres, between [KE]'s 1.0 and 3.2 mm steel

// side² × layers spheres on simple cubic sites of pitch 2 kR, radii uniform in
// kR (1 + 1e-5 … 1 + 1e-3): every neighbour pair and every end sphere with its wall overlaps,
// but each contact radius differs (a/r ≈ 0.003–0.045), a disordered network of fixed topology.
// The side faces clear the spheres by 0.01 kR.
bed::Bed lattice_bed(int side, int layers, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> radius(kR * (1 + 1e-5), kR * (1 + 1e-3));
  const double pitch = 2 * kR, margin = 0.01 * kR;
  bed::Bed b;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i)
        b.add(margin + (i + 0.5) * pitch, margin + (j + 0.5) * pitch, (k + 0.5) * pitch,
              radius(rng));
  b.domain.upper = {side * pitch + 2 * margin, side * pitch + 2 * margin, layers * pitch};
  return b;
}

// Size ratio 1:8: two big spheres (R = 8 r) at seeded random places in separate height bands
// (≥ 16.6 r apart: they never overlap) in a 10 × 10 × 19 jittered lattice of small spheres of
// pitch 1.98 r (each small pair overlaps by 0.01–0.03 r, the end layers overlap the walls).
// Small spheres closer to a big centre than R + 0.98 r are dropped: the rest touch the big
// spheres by at most 0.02 r or not at all.
bed::Bed bimodal_bed(unsigned seed) {
  const double r = kR / 8, big = kR, pitch = 1.98 * r, margin = 0.1 * r;
  const int side = 10, layers = 19;
  const double width = side * pitch + 2 * margin, height = 2 * 0.99 * r + (layers - 1) * pitch;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> lateral(big + 0.5 * r, width - big - 0.5 * r),
      band(0, 2 * r), jitter(-0.005 * r, 0.005 * r);
  const double bx[2] = {lateral(rng), lateral(rng)}, by[2] = {lateral(rng), lateral(rng)};
  const double bz[2] = {big + 0.5 * r + band(rng), height - big - 0.5 * r - band(rng)};
  bed::Bed b;
  for (int m = 0; m < 2; ++m) b.add(bx[m], by[m], bz[m], big);
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) {
        const double x = margin + (i + 0.5) * pitch + jitter(rng);
        const double y = margin + (j + 0.5) * pitch + jitter(rng);
        const double z = 0.99 * r + k * pitch + (k > 0 && k < layers - 1 ? jitter(rng) : 0);
        bool clear = true;
        for (int m = 0; m < 2; ++m)
          clear &= std::hypot(x - bx[m], y - by[m], z - bz[m]) >= big + 0.98 * r;
        if (clear) b.add(x, y, z, r);
      }
  b.domain.upper = {width, width, height};
  return b;
}

kf::KeffScene scene(double t_hot, double t_cold, bool contact, bool gas, bool radiation) {
  kf::KeffScene s;
  s.hot_temperature = t_hot;
  s.cold_temperature = t_cold;
  s.contact_path = contact;
  s.gas_path = gas;
  s.radiation_path = radiation;
  s.emissivity = s.wall_emissivity = 0.8;  // oxidised steel
  s.rays = 300;
  return s;
}

double end_temperature(const kf::KeffScene& s, const kf::KeffResult& r, std::uint32_t j) {
  return j == kf::kHotWall ? s.hot_temperature : j == kf::kColdWall ? s.cold_temperature
                                                                     : r.temperature[j];
}

// A link's flow from j into i, written out from docs/physics.md §6 independently of solve.cpp.
double link_flow(const kf::KeffNetwork& net, const kf::KeffLink& l, double ti, double tj) {
  if (l.path == kf::HeatPath::radiation)
    return kf::kStefanBoltzmann * l.conductance * (std::pow(tj, 4) - std::pow(ti, 4));
  double g = l.conductance;
  if (l.path == kf::HeatPath::gas && net.gas_follows_temperature)
    g *= kf::air_conductivity((ti + tj) / 2) / net.gas_reference;
  return g * (tj - ti);
}

// What every hard case must satisfy: Newton reached the tolerance, nothing NaN, k_eff > 0, the
// wall flows agree to the 1e-8, the particles lie between the wall temperatures
// (maximum principle, below), and Tellegen's theorem Σ q ΔT = Q (T_hot − T_cold) holds with the
// flows recomputed link by link from the returned temperatures.
void expect_solved(const kf::KeffNetwork& net, const kf::KeffScene& s, const kf::KeffResult& r) {
  EXPECT_LE(r.residual, s.newton_tolerance);
  ASSERT_TRUE(std::isfinite(r.k_eff));
  EXPECT_GT(r.k_eff, 0);
  EXPECT_NEAR(r.heat_flow_hot, r.heat_flow_cold, 1e-8 * r.heat_flow_hot);
  // Maximum principle: every link's flow has the sign of T_j − T_i (G ΔT, k_g(T̄) ΔT with the air
  // polynomial > 0 on its range, σ G_r (T_j⁴ − T_i⁴)). If the hottest particles were above
  // T_hot, heat would leave their set through any link to a cooler node, and there is one (they
  // reach a wall), so their balance could not close; likewise below T_cold. The returned
  // temperatures miss the exact ones by the Newton residual (≤ 1e-10 of the flows): 1e-6 K.
  std::vector<bool> rattler(r.temperature.size(), false);
  for (const std::uint32_t p : r.rattlers) rattler[p] = true;
  for (std::size_t p = 0; p < r.temperature.size(); ++p) {
    ASSERT_TRUE(std::isfinite(r.temperature[p])) << "particle " << p;
    if (rattler[p]) continue;
    EXPECT_GE(r.temperature[p], s.cold_temperature - 1e-6) << "particle " << p;
    EXPECT_LE(r.temperature[p], s.hot_temperature + 1e-6) << "particle " << p;
  }
  double dissipation = 0, q_hot = 0, q_cold = 0;
  for (const kf::KeffLink& l : net.links) {
    if (rattler[l.i]) continue;
    const double ti = r.temperature[l.i], tj = end_temperature(s, r, l.j);
    const double q = link_flow(net, l, ti, tj);
    dissipation += q * (tj - ti);
    if (l.j == kf::kHotWall) q_hot += q;
    if (l.j == kf::kColdWall) q_cold -= q;
  }
  // Straight from wall to wall through the gaps (radiation): the same flow at both walls.
  const double direct = kf::kStefanBoltzmann * net.wall_exchange *
                        (std::pow(s.hot_temperature, 4) - std::pow(s.cold_temperature, 4));
  q_hot += direct;
  q_cold += direct;
  dissipation += direct * (s.hot_temperature - s.cold_temperature);
  // The solver sums the same flows in the same order up to its own formula: round-off.
  EXPECT_NEAR(q_hot, r.heat_flow_hot, 1e-12 * q_hot);
  EXPECT_NEAR(q_cold, r.heat_flow_cold, 1e-12 * q_hot);
  // With R_p the net inflow of particle p, Σ q ΔT − Q̄ (T_hot − T_cold) = Σ_p (T̄_wall − T_p) R_p,
  // at most ΔT/2 Σ|R_p| ≤ ΔT/2 √N ‖R‖: Newton's ‖R‖ ≤ 1e-10 ‖Σ|q|‖ and ‖Σ|q|‖ ≲ 2 Q × (layers)
  // bound the relative error by ~√N · layers · 1e-10 ≈ 1e-8 (200 spheres) to 6e-8 (bimodal bed).
  // Measured ≤ 3e-11.
  const double q_dt = (q_hot + q_cold) / 2 * (s.hot_temperature - s.cold_temperature);
  EXPECT_NEAR(dissipation, q_dt, 1e-7 * q_dt);
}

}  // namespace

TEST(KeffHardCases, At2000KRadiationDominatesAndNewtonConverges) {
  const bed::Bed b = lattice_bed(5, 8, 3);  // 200 spheres
  const kf::KeffScene s = scene(2100, 1900, true, true, true);
  const kf::KeffNetwork net = kf::build_keff_network(b, s);
  const kf::KeffResult r = kf::solve_keff(b, s, net);
  expect_solved(net, s, r);
  EXPECT_TRUE(r.rattlers.empty());
  // The secant start misses T⁴ by ~(ΔT / T)² ≈ 1 % over this window: quadratic steps from there
  // (3 measured).
  EXPECT_GE(r.newton_iterations, 1u);
  EXPECT_LE(r.newton_iterations, 5u);
  // Radiation carries ~4σT³D ε/(2 − ε) ≈ 2.4 W/mK at 2000 K and D = 2 mm (3.6 measured); the
  // contacts (a/r ≈ 0.02, k_s = 16.2) ~k_s a / r ≈ 0.35 W/mK (0.43), the gas (k_g = 0.026) ~0.3.
  // Share ≈ 0.8 (0.83 measured); 0.5 is what the "T⁴ terms dominate" means.
  EXPECT_GT(r.share_radiation, 0.5);
  EXPECT_GT(r.share_contact, 0);
  EXPECT_GT(r.share_gas, 0);
  EXPECT_NEAR(r.share_contact + r.share_gas + r.share_radiation, 1, 1e-12);  // one sum
}

TEST(KeffHardCases, AirGasModelMatchesBisectionOfOneSphere) {
  // One sphere between the walls, overlapping the cold wall by 1e-3 r and the hot one by 3e-3 r:
  // its balance Σ_links q(T) = 0 is one monotone equation, solved here by bisection.
  bed::Bed b;
  b.add(1.5 * kR, 1.5 * kR, kR * (1 - 1e-3), kR);
  b.domain.upper = {3 * kR, 3 * kR, kR * (2 - 4e-3)};
  for (const bool radiation : {false, true}) {
    kf::KeffScene s = scene(1500, 300, true, true, radiation);
    s.gas_model = kf::GasModel::air;
    const kf::KeffNetwork net = kf::build_keff_network(b, s);
    ASSERT_TRUE(net.gas_follows_temperature);
    const kf::KeffResult r = kf::solve_keff(b, s, net);
    expect_solved(net, s, r);
    for (const kf::KeffLink& l : net.links) ASSERT_TRUE(l.j >= kf::kColdWall);  // walls only
    const auto balance = [&](double t) {
      double sum = 0;
      for (const kf::KeffLink& l : net.links)
        sum += link_flow(net, l, t, l.j == kf::kHotWall ? 1500.0 : 300.0);
      return sum;
    };
    double lo = 300, hi = 1500;  // balance(lo) > 0 > balance(hi)
    for (int k = 0; k < 200 && hi - lo > 1e-12; ++k)
      (balance((lo + hi) / 2) > 0 ? lo : hi) = (lo + hi) / 2;
    // One unknown: Newton's relative residual 1e-10 moves T by ≲ 1e-10 ΔT; 1e-8 ΔT = 12 µK
    // (measured 1e-11 K).
    EXPECT_NEAR(r.temperature[0], (lo + hi) / 2, 1e-8 * 1200) << "radiation " << radiation;
    EXPECT_GE(r.newton_iterations, 1u);
    EXPECT_LE(r.newton_iterations, 8u);  // k_g varies 3× over 300–1500 K, T⁴ 600× (3, 4 measured)
  }
}

TEST(KeffHardCases, AirGasModelOnADisorderedBedWithAndWithoutRadiation) {
  const bed::Bed b = lattice_bed(4, 6, 5);
  for (const bool radiation : {false, true}) {
    kf::KeffScene s = scene(1500, 300, true, true, radiation);
    s.gas_model = kf::GasModel::air;
    const kf::KeffNetwork net = kf::build_keff_network(b, s);
    const kf::KeffResult r = kf::solve_keff(b, s, net);
    SCOPED_TRACE(radiation ? "with radiation" : "without radiation");
    expect_solved(net, s, r);
    EXPECT_LE(r.newton_iterations, 10u);  // as the one sphere (3 and 4 measured)
    EXPECT_GT(r.share_gas, 0);
  }
}

TEST(KeffHardCases, OneParticleThickBedMatchesPerSphereSeries) {
  // 4 × 4 spheres 2.5 r apart (lenses of 1.2 r do not reach each other), radii 0.01–1 % over
  // half the wall distance, centres off mid-height by up to half that excess: every sphere cuts
  // both walls and is an independent series of (contact + gas) to each,
  // k_eff = H / A Σ_p 1 / (1/G_hot,p + 1/G_cold,p).
  const double height = 2 * kR, pitch = 2.5 * kR;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> excess(1e-4, 1e-2), lift(-0.5, 0.5);
  bed::Bed b;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const double e = excess(rng) * kR;
      b.add((i + 0.5) * pitch, (j + 0.5) * pitch, kR + lift(rng) * e, kR + e);
    }
  b.domain.upper = {4 * pitch, 4 * pitch, height};
  const kf::KeffScene s = scene(305, 295, true, true, false);
  const kf::KeffNetwork net = kf::build_keff_network(b, s);
  const kf::KeffResult r = kf::solve_keff(b, s, net);
  expect_solved(net, s, r);
  std::vector<double> g_hot(b.n(), 0), g_cold(b.n(), 0);
  for (const kf::KeffLink& l : net.links) {
    ASSERT_TRUE(l.j == kf::kHotWall || l.j == kf::kColdWall) << "link " << l.i << "-" << l.j;
    (l.j == kf::kHotWall ? g_hot : g_cold)[l.i] += l.conductance;
  }
  double g = 0;
  for (std::size_t p = 0; p < b.n(); ++p) {
    const double rp = b.radius[p];
    const auto wall = [&](double h) {  // Batchelor–O'Brien 2 k_s √(r² − h²) + Rong–Horio lens
      return 2 * s.solid_conductivity * std::sqrt(rp * rp - h * h) +
             s.gas_conductivity * kf::gas_wall_factor(s.lens, rp, h);
    };
    const double hot = wall(height - b.z[p]), cold = wall(b.z[p]);
    // The network's wall links are these two sums: round-off.
    EXPECT_NEAR(g_hot[p], hot, 1e-14 * hot);
    EXPECT_NEAR(g_cold[p], cold, 1e-14 * cold);
    g += 1 / (1 / hot + 1 / cold);
  }
  const double expected = g * height / (b.domain.length(0) * b.domain.length(1));
  // 16 decoupled unknowns solved by CG to 1e-12: k_eff to ~1e-12.
  EXPECT_NEAR(r.k_eff, expected, 1e-10 * expected);
}

TEST(KeffHardCases, OneLayerTangentToBothWalls) {
  // Walls exactly one diameter apart, 4 × 4 equal spheres tangent to them and to each other:
  // no contact area anywhere, the gas lenses carry the heat. By symmetry every sphere sits at the
  // mean wall temperature, the lateral links carry nothing, and each sphere is two equal lens
  // links in series: k_eff = H / A · 16 k_g F_w(r, r) / 2.
  bed::Bed b;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) b.add((2 * i + 1) * kR, (2 * j + 1) * kR, kR, kR);
  b.domain.upper = {8 * kR, 8 * kR, 2 * kR};
  kf::KeffScene s = scene(305, 295, true, true, false);
  const kf::KeffNetwork net = kf::build_keff_network(b, s);
  const kf::KeffResult r = kf::solve_keff(b, s, net);
  expect_solved(net, s, r);
  EXPECT_EQ(r.contact_links, 0u);
  const double expected = 16 * s.gas_conductivity * kf::gas_wall_factor(s.lens, kR, kR) / 2 *
                          b.domain.length(2) / (b.domain.length(0) * b.domain.length(1));
  EXPECT_NEAR(r.k_eff, expected, 1e-10 * expected);  // CG to 1e-12 on 16 unknowns
  // All paths at 1000 K: the Monte-Carlo view factors break the symmetry, no closed form.
  s = scene(1100, 900, true, true, true);
  const kf::KeffNetwork all = kf::build_keff_network(b, s);
  const kf::KeffResult ra = kf::solve_keff(b, s, all);
  expect_solved(all, s, ra);
  EXPECT_GT(ra.share_radiation, 0);
  EXPECT_GT(ra.k_eff, expected);  // radiation adds a parallel path to the same lenses
}

TEST(KeffHardCases, BimodalBedSizeRatioOneToEight) {
  const bed::Bed b = bimodal_bed(17);
  ASSERT_GT(b.n(), 500u);
  for (const bool radiation : {false, true}) {
    kf::KeffScene s = scene(1100, 900, true, true, radiation);
    s.rays = 100;  // the solve is under test, not the view factors (they take most of the time)
    const kf::KeffNetwork net = kf::build_keff_network(b, s);
    const kf::KeffResult r = kf::solve_keff(b, s, net);
    SCOPED_TRACE(radiation ? "with radiation" : "without radiation");
    expect_solved(net, s, r);
    EXPECT_LE(r.newton_iterations, 6u);  // linear, or the secant start of a 200 K window (2)
    if (radiation) {
      EXPECT_TRUE(r.rattlers.empty());  // every sphere sees something
    }
  }
}

TEST(KeffHardCases, NewtonFromAFarStartBacktracksToConvergence) {
  // Radiation only between 2000 K and 300 K: the secant start puts T linear in depth while the
  // solution is closer to linear in T⁴ (2000⁴ / 300⁴ ≈ 2000): the first full Newton step moves
  // a particle by up to 3600 K. Replaying the solver's iteration (same start and halving rule,
  // dense Jacobian) on this bed, its first two steps are halved 3 and 1 times; between 5000 K
  // and 50 K 6, 4 and 2 times. Both then converge quadratically (6 and 8 steps in all, where a
  // 2100/1900 K window takes 3).
  const bed::Bed b = lattice_bed(4, 8, 7);
  for (const auto& [t_hot, t_cold] : {std::pair{2000.0, 300.0}, std::pair{5000.0, 50.0}}) {
    const kf::KeffScene s = scene(t_hot, t_cold, false, false, true);
    const kf::KeffNetwork net = kf::build_keff_network(b, s);
    const kf::KeffResult r = kf::solve_keff(b, s, net);
    SCOPED_TRACE(t_hot);
    expect_solved(net, s, r);
    EXPECT_GT(r.newton_iterations, 3u);  // the damped steps came first
    EXPECT_LE(r.newton_iterations, 30u);  // the solver gives up at 50
  }
}
