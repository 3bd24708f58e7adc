// Effective conductivity network (docs/physics.md §6, issue 6): a simple cubic column of slightly
// overlapping spheres between the walls against its closed-form series conductance, with and
// without the Hertz correction; wall flows agree and Tellegen's theorem holds on a disordered
// bed with both paths; rattlers and floating clusters are reported and left out of the solve.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/keff/solve.hpp"

using namespace powderbed;
namespace kf = powderbed::keff;

namespace {

constexpr double kR = 0.5e-3;            // particle radius, m
constexpr double kOverlap = 1e-3 * kR;   // pair overlap and wall overlap, m
constexpr int kColumn = 5;

// kColumn spheres on the z axis at x = y = kR, each overlapping its neighbours and the end ones
// the walls by kOverlap; the box is `width` wide in x and y.
bed::Bed column(double width = 2 * kR) {
  bed::Bed b;
  const double z0 = kR - kOverlap, pitch = 2 * kR - kOverlap;
  for (int k = 0; k < kColumn; ++k) b.add(kR, kR, z0 + k * pitch, kR);
  b.domain.upper = {width, width, z0 + (kColumn - 1) * pitch + kR - kOverlap};
  return b;
}

kf::KeffScene contact_only() {
  kf::KeffScene s;
  s.gas_path = false;
  return s;
}

// k_eff of the column from its series conductance: two wall contacts and kColumn - 1 pairs.
double series_keff(const bed::Bed& b, const kf::KeffScene& s, double a_pair, double a_wall) {
  const double g_pair = 2 * s.solid_conductivity * a_pair;
  const double g_wall = 2 * s.solid_conductivity * a_wall;
  const double g = 1 / (2 / g_wall + (kColumn - 1) / g_pair);
  return g * b.domain.length(2) / (b.domain.length(0) * b.domain.length(1));
}

// Round-off of a 5-unknown direct solve is ~1e-15; 1e-10 leaves room without hiding an error
// in any of the conductances (each enters the series sum at the percent level).
constexpr double kExact = 1e-10;

}  // namespace

TEST(Keff, ColumnMatchesSeriesContactConductance) {
  const bed::Bed b = column();
  const kf::KeffScene s = contact_only();
  const kf::KeffResult r = kf::solve_keff(b, s);
  const double d = 2 * kR - kOverlap;
  const double a_pair = std::sqrt(kR * kR - d * d / 4);
  const double a_wall = std::sqrt(kR * kR - (kR - kOverlap) * (kR - kOverlap));
  const double expected = series_keff(b, s, a_pair, a_wall);
  EXPECT_NEAR(r.k_eff, expected, kExact * expected);
  EXPECT_NEAR(r.heat_flow_hot, r.heat_flow_cold, 1e-8 * r.heat_flow_hot);
  EXPECT_DOUBLE_EQ(r.share_contact, 1.0);
  EXPECT_EQ(r.share_gas, 0.0);
  EXPECT_TRUE(r.rattlers.empty());
  EXPECT_EQ(r.contact_links, static_cast<std::size_t>(kColumn + 1));
  // Temperatures fall monotonically from the hot (top) wall to the cold (bottom) one.
  for (int k = 1; k < kColumn; ++k) EXPECT_GT(r.temperature[k], r.temperature[k - 1]);
}

TEST(Keff, ColumnWithHertzCorrectionAndCalibration) {
  const bed::Bed b = column();
  kf::KeffScene s = contact_only();
  s.contact.hertz_correction = true;
  s.contact.circle = kf::ContactCircle::hertz;  // the closed form below is the Hertz circle's
  s.contact.young_scale = 1000;  // δ_h = δ_s S^{-2/3} = δ_s / 100
  s.calibration = 1.3;
  const kf::KeffResult r = kf::solve_keff(b, s);
  // a = A_c √(R* δ_h): R* = r/2 for a pair, r for the wall.
  const double a_pair = 1.3 * std::sqrt(kR / 2 * kOverlap / 100);
  const double a_wall = 1.3 * std::sqrt(kR * kOverlap / 100);
  const double expected = series_keff(b, s, a_pair, a_wall);
  EXPECT_NEAR(r.k_eff, expected, kExact * expected);
}

TEST(Keff, ZeroGasConductivityIsContactOnly) {
  // Issue 6 hard case: k_g = 0 with contacts only gives no gas links and the contact answer.
  const bed::Bed b = column();
  kf::KeffScene s;
  s.gas_conductivity = 0;
  const kf::KeffResult r = kf::solve_keff(b, s);
  const double k_contact = kf::solve_keff(b, contact_only()).k_eff;
  EXPECT_EQ(r.gas_links, 0u);
  EXPECT_NEAR(r.k_eff, k_contact, kExact * k_contact);
}

TEST(Keff, AxisXGivesTheSameColumn) {
  // The column laid along x: the result must not depend on which axis carries the flow.
  const bed::Bed along_z = column();
  bed::Bed along_x = along_z;
  along_x.x = along_z.z;
  along_x.z = along_z.x;
  const auto& upper = along_z.domain.upper;
  along_x.domain.upper = {upper[2], upper[1], upper[0]};
  kf::KeffScene s = contact_only();
  const double k_z = kf::solve_keff(along_z, s).k_eff;
  s.axis = 0;
  EXPECT_NEAR(kf::solve_keff(along_x, s).k_eff, k_z, kExact * k_z);
}

TEST(Keff, RattlersAndFloatingClustersAreReportedAndLeftOut) {
  const double width = 8 * kR;
  const bed::Bed plain = column(width);
  bed::Bed b = plain;
  const double mid = b.domain.upper[2] / 2;
  b.add(6 * kR, 6 * kR, mid, kR);                    // a rattler
  b.add(6 * kR, 2 * kR, mid, kR);                    // a floating pair ...
  b.add(6 * kR, 2 * kR, mid + 2 * kR - kOverlap, kR);  // ... touching each other only
  kf::KeffScene s;  // both paths: the lenses of the extra particles reach nothing either
  const kf::KeffResult with = kf::solve_keff(b, s);
  const kf::KeffResult without = kf::solve_keff(plain, s);
  ASSERT_EQ(with.rattlers.size(), 3u);
  EXPECT_EQ(with.rattlers[0], static_cast<std::uint32_t>(kColumn));
  // The same linear system up to the ordering of the unknowns: equal to round-off.
  EXPECT_NEAR(with.k_eff, without.k_eff, 1e-12 * without.k_eff);
  for (double t : with.temperature) EXPECT_TRUE(std::isfinite(t));
  EXPECT_EQ(with.temperature[kColumn], (s.hot_temperature + s.cold_temperature) / 2);
}

TEST(Keff, DisorderedBedWallFlowsAgreeAndTellegenHolds) {
  // A jittered 4 x 4 x 6 cubic lattice of polydisperse spheres, both paths on, gas k_g / k_s
  // ~ 1e-3 as in the study: a wide spread of conductances.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-0.04 * kR, 0.04 * kR), size(0.9 * kR, 1.02 * kR);
  bed::Bed b;
  const double pitch = 1.95 * kR;
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        b.add(kR + i * pitch + jitter(rng), kR + j * pitch + jitter(rng),
              0.98 * kR + k * pitch + jitter(rng), size(rng));
  b.domain.upper = {4 * pitch + 0.1 * kR, 4 * pitch + 0.1 * kR, 5 * pitch + 1.96 * kR};
  kf::KeffScene s;  // constant k_g: a linear network, whose links' G the Tellegen sum uses
  const kf::KeffNetwork net = kf::build_keff_network(b, s);
  const kf::KeffResult r = kf::solve_keff(b, s, net);
  // Issue 6: the two wall flows agree to 1e-8 relative (the direct solve reaches ~1e-14).
  EXPECT_NEAR(r.heat_flow_hot, r.heat_flow_cold, 1e-8 * r.heat_flow_hot);
  EXPECT_GT(r.share_contact, 0);
  EXPECT_GT(r.share_gas, 0);
  EXPECT_NEAR(r.share_contact + r.share_gas, 1, 1e-14);  // shares of one sum: round-off
  // Tellegen: Σ G ΔT² over the links equals Q_wall (T_hot − T_cold) for the solved network.
  double dissipation = 0;
  for (const kf::KeffLink& l : net.links) {
    const double tj = l.j == kf::kHotWall    ? s.hot_temperature
                      : l.j == kf::kColdWall ? s.cold_temperature
                                             : r.temperature[l.j];
    dissipation += l.conductance * (tj - r.temperature[l.i]) * (tj - r.temperature[l.i]);
  }
  const double q_dt = r.heat_flow_hot * (s.hot_temperature - s.cold_temperature);
  EXPECT_NEAR(dissipation, q_dt, 1e-9 * q_dt);  // both sides exact up to the solve's residual
  for (double t : r.temperature) {
    EXPECT_GE(t, s.cold_temperature);  // maximum principle of a conductance network
    EXPECT_LE(t, s.hot_temperature);
  }
}

TEST(Keff, NoParticleAtAWallIsRefusedNamingTheWall) {
  bed::Bed b = column();
  b.domain.upper[2] += kR;  // the top particle no longer reaches the hot wall, nor its lens
  try {
    kf::solve_keff(b, contact_only());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hot wall"), std::string::npos) << e.what();
  }
}

TEST(Keff, BadScenesAndBedsAreRefused) {
  const bed::Bed b = column();
  kf::KeffScene s;
  s.hot_temperature = s.cold_temperature;
  EXPECT_THROW(kf::solve_keff(b, s), InputError);
  s = kf::KeffScene{};
  s.solid_conductivity = -1;
  EXPECT_THROW(kf::solve_keff(b, s), InputError);
  s = kf::KeffScene{};
  s.contact_path = s.gas_path = false;
  EXPECT_THROW(kf::solve_keff(b, s), InputError);
  bed::Bed periodic = b;
  periodic.domain.periodic[2] = true;
  EXPECT_THROW(kf::solve_keff(periodic, kf::KeffScene{}), InputError);
  bed::Bed outside = b;
  outside.z[0] = -1e-3;
  EXPECT_THROW(kf::solve_keff(outside, kf::KeffScene{}), InputError);
}
