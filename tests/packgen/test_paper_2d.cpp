// The published 2D study of [LP] (docs/physics.md §3 table): 4.0 x 4.0 um square, raster spacing
// h = 0.015 um, monodisperse r = 0.075 um, 0-contact and 1-contact. 10 samples per case
// (seeds 1..10). Each mean must lie in the paper's range widened by 3 standard errors of our
// mean (sd / sqrt(10); sd of the density about 0.004-0.008, of Z about 0.1): the paper's ranges
// are themselves spreads over 100 samples, and 3 SE keeps the chance of a false failure of one
// assertion below 0.3 %.
//
// Settings: packgen's 2D defaults (docs/results/packgen-2d-study.md): --tries 1000,
// --directions 10, --max-failures 100, --retire-after 32. The paper gives neither K nor a stop
// rule; K = 10 is inferred from the 1-contact density (it grows with K: about 0.626 at K = 8,
// 0.636 at K = 10, 0.642 at K = 12, 0.647 at K = 16), the rest are packgen's defaults.
// Contact tolerance: a raster bed leaves gaps of the order of h (docs/physics.md §3), so a contact is a
// surface gap <= g, i.e. tol = g / (2 r). The study finds the paper's 0-contact coordination at
// g = 1.1-1.4 h and its 1-contact coordination at g = 2.0-2.3 h: no single gap reproduces both
// (our finding, not a tuned fit). The test checks 0-contact at g = sqrt(2) h (the diagonal of a
// grid cell, tol 0.141) and 1-contact at g = 2 h (tol 0.2), and prints the other.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "powderbed/bed/stats.hpp"
#include "powderbed/packgen/pack.hpp"

namespace {

using namespace powderbed;

constexpr double kUm = 1e-6;
constexpr double kR = 0.075 * kUm;
constexpr double kH = 0.015 * kUm;
constexpr int kSamples = 10;

struct Range {
  double lo, hi;
};

struct Sample {
  double n, density, z_diag_h, z_two_h;
};

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}
double standard_error(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1) / static_cast<double>(v.size()));
}

void expect_in(const char* what, const std::vector<double>& v, Range paper) {
  const double m = mean(v), se = standard_error(v);
  std::printf("  %-28s mean %.4f (SE %.4f), paper %.4g..%.4g\n", what, m, se, paper.lo, paper.hi);
  EXPECT_GE(m, paper.lo - 3 * se) << what;
  EXPECT_LE(m, paper.hi + 3 * se) << what;
}

std::vector<Sample> run_case(int approach) {
  bed::Domain domain;
  domain.dimension = 2;
  domain.upper = {4.0 * kUm, 4.0 * kUm, 0};
  const bed::Psd psd = bed::Psd::mono_radius(kR);
  packgen::PackOptions o;
  o.phases = {{approach, 1.0}};
  o.collision = packgen::Collision::raster;
  o.raster_spacing = kH;
  o.directions = 10;  // packgen's 2D default (kDirections2D)
  std::vector<Sample> out;
  for (int s = 1; s <= kSamples; ++s) {
    const auto result = packgen::pack(domain, psd, o, static_cast<std::uint64_t>(s));
    out.push_back({static_cast<double>(result.bed.n()), bed::packing_density(result.bed),
                   bed::contact_stats(result.bed, std::sqrt(2.0) * kH / (2 * kR)).coordination,
                   bed::contact_stats(result.bed, kH / kR).coordination});
  }
  return out;
}

template <class F>
std::vector<double> column(const std::vector<Sample>& s, F f) {
  std::vector<double> v;
  for (const auto& x : s) v.push_back(f(x));
  return v;
}

TEST(PaperLP2D, MonodisperseZeroContact) {
  const auto s = run_case(0);
  expect_in("particles", column(s, [](auto& x) { return x.n; }), {500, 520});
  expect_in("density", column(s, [](auto& x) { return x.density; }), {0.55, 0.57});
  expect_in("coordination (gap <= 1.41 h)", column(s, [](auto& x) { return x.z_diag_h; }),
            {1.8, 2.1});
  std::printf("  coordination (gap <= 2h)     mean %.4f\n",
              mean(column(s, [](auto& x) { return x.z_two_h; })));
}

TEST(PaperLP2D, MonodisperseOneContact) {
  const auto s = run_case(1);
  expect_in("particles", column(s, [](auto& x) { return x.n; }), {560, 580});
  expect_in("density", column(s, [](auto& x) { return x.density; }), {0.62, 0.64});
  expect_in("coordination (gap <= 2h)", column(s, [](auto& x) { return x.z_two_h; }),
            {3.25, 3.45});
  std::printf("  coordination (gap <= 1.41 h) mean %.4f\n",
              mean(column(s, [](auto& x) { return x.z_diag_h; })));
}

}  // namespace
