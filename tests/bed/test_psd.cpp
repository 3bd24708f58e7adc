// Particle size distributions (docs/physics.md §1): parsing, analytic moments, sampling, KS distance,
// error messages.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/psd.hpp"

namespace {

using powderbed::InputError;
using powderbed::bed::Psd;
using powderbed::bed::PsdComponent;
using powderbed::bed::Rng;
using powderbed::bed::SizeVariable;

const std::string table_path = std::string(POWDERBED_TEST_DATA) + "/psd_table.csv";

// [GZ] Table 3 bimodal bed (docs/physics.md §1), as written in the issue.
const std::string bimodal =
    "gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6,count=550+"
    "gauss:mean=8e-6,sd=2e-6,min=4e-6,max=12e-6,count=3000";
// [LP] Table 2, read as radii.
const std::string lp_table2 = "gauss:mean=0.075e-6,sd=0.0375e-6,min=0.015e-6,max=0.15e-6,on=radius";

std::vector<double> draw(const Psd& psd, std::size_t n, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<double> r(n);
  for (auto& x : r) x = psd.sample_radius(rng);
  return r;
}

// Composite Simpson rule, an independent check of the closed-form moments.
double simpson(const std::function<double(double)>& f, double a, double b, int n = 20000) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += f(a + i * h) * (i % 2 ? 4 : 2);
  return sum * h / 3;
}

// Raw moment E[r^k] of the radius by quadrature of the density x -> pdf(x) on [a, b] (radius).
double quadrature_moment(const std::function<double(double)>& pdf, double a, double b, int k) {
  return simpson([&](double x) { return std::pow(x, k) * pdf(x); }, a, b) / simpson(pdf, a, b);
}

std::string error_of(const std::string& spec) {
  try {
    Psd::parse(spec);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// ---------------------------------------------------------------------------------- parsing

TEST(Psd, ParsesMonoOnDiameterAndRadius) {
  const Psd d = Psd::parse("mono:d=30e-6");
  ASSERT_EQ(d.components().size(), 1u);
  EXPECT_EQ(d.components()[0].kind, PsdComponent::Kind::mono);
  EXPECT_EQ(d.components()[0].on, SizeVariable::diameter);
  EXPECT_DOUBLE_EQ(d.mean_radius(), 15e-6);
  EXPECT_DOUBLE_EQ(d.min_radius(), 15e-6);
  EXPECT_DOUBLE_EQ(d.max_radius(), 15e-6);
  EXPECT_DOUBLE_EQ(d.mean_radius_cubed(), 15e-6 * 15e-6 * 15e-6);
  EXPECT_EQ(d.total_count(), 0u);
  EXPECT_EQ(d.text(), "mono:d=30e-6");

  const Psd r = Psd::parse(" mono: r = 0.075e-6 ");
  EXPECT_EQ(r.components()[0].on, SizeVariable::radius);
  EXPECT_DOUBLE_EQ(r.mean_radius(), 0.075e-6);

  const Psd m = Psd::mono_radius(2e-6);
  Rng rng(1);
  EXPECT_EQ(m.sample_radius(rng), 2e-6);
  EXPECT_EQ(Psd::parse(m.text()).mean_radius(), 2e-6);
}

TEST(Psd, ParsesTheIssueBimodalExample) {
  const Psd psd = Psd::parse(bimodal);
  ASSERT_EQ(psd.components().size(), 2u);
  const auto& big = psd.components()[0];
  const auto& small = psd.components()[1];
  EXPECT_EQ(big.kind, PsdComponent::Kind::gauss);
  EXPECT_EQ(big.on, SizeVariable::diameter);
  EXPECT_DOUBLE_EQ(big.mean, 30e-6);
  EXPECT_DOUBLE_EQ(big.sd, 5e-6);
  EXPECT_DOUBLE_EQ(big.min, 20e-6);
  EXPECT_DOUBLE_EQ(big.max, 40e-6);
  EXPECT_EQ(big.count, 550u);
  EXPECT_EQ(small.count, 3000u);
  EXPECT_DOUBLE_EQ(big.number_fraction, 550.0 / 3550.0);
  EXPECT_DOUBLE_EQ(small.number_fraction, 3000.0 / 3550.0);
  EXPECT_EQ(psd.total_count(), 3550u);
  EXPECT_DOUBLE_EQ(psd.min_radius(), 2e-6);   // small component's min diameter 4 um, halved
  EXPECT_DOUBLE_EQ(psd.max_radius(), 20e-6);  // big component's max diameter 40 um, halved
  // Both windows are symmetric about their means, so the truncated means are the means.
  // 1e-12 relative: a few roundings of the closed form.
  EXPECT_NEAR(psd.mean_radius(), (550 * 15e-6 + 3000 * 4e-6) / 3550, 1e-12 * 15e-6);
}

TEST(Psd, ParsesLpTable2OnRadius) {
  const Psd psd = Psd::parse(lp_table2);
  const auto& c = psd.components()[0];
  EXPECT_EQ(c.on, SizeVariable::radius);
  EXPECT_DOUBLE_EQ(psd.min_radius(), 0.015e-6);
  EXPECT_DOUBLE_EQ(psd.max_radius(), 0.15e-6);
  // Window [-1.6, 2] sd around the mean: the truncated mean lies above the mean.
  EXPECT_GT(psd.mean_radius(), 0.075e-6);
  EXPECT_LT(psd.mean_radius(), 0.09e-6);
}

TEST(Psd, SplitsComponentsOnlyBeforeAKind) {
  // '+' in exponents belongs to the number; '+' before a letter (blanks allowed) splits.
  const Psd psd = Psd::parse("mono:d=2e+0 + mono:r=3e-0+mono:d=1E+1");
  ASSERT_EQ(psd.components().size(), 3u);
  EXPECT_DOUBLE_EQ(psd.components()[0].mean, 2.0);
  EXPECT_DOUBLE_EQ(psd.components()[1].mean, 3.0);
  EXPECT_DOUBLE_EQ(psd.components()[2].mean, 10.0);
  for (const auto& c : psd.components()) EXPECT_DOUBLE_EQ(c.number_fraction, 1.0 / 3.0);
}

TEST(Psd, WeightsByFractionAndVolumeFraction) {
  const Psd frac = Psd::parse("mono:d=10e-6,frac=0.2+mono:d=20e-6,frac=0.6");
  EXPECT_DOUBLE_EQ(frac.components()[0].number_fraction, 0.25);
  EXPECT_DOUBLE_EQ(frac.components()[1].number_fraction, 0.75);
  EXPECT_EQ(frac.total_count(), 0u);
  // Equal volumes of spheres whose radii differ by 2: 8 small ones per big one.
  const Psd vfrac = Psd::parse("mono:d=10e-6,vfrac=0.5+mono:d=20e-6,vfrac=0.5");
  EXPECT_DOUBLE_EQ(vfrac.components()[0].number_fraction, 8.0 / 9.0);
  EXPECT_DOUBLE_EQ(vfrac.components()[1].number_fraction, 1.0 / 9.0);
  // vfrac on distributions divides by each component's analytic E[r^3].
  const Psd mixed = Psd::parse(
      "gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6,vfrac=0.3+lognormal:median=8e-6,gsd=1.3,vfrac="
      "0.7");
  const double n0 = 0.3 / radius_moment(mixed.components()[0], 3);
  const double n1 = 0.7 / radius_moment(mixed.components()[1], 3);
  EXPECT_DOUBLE_EQ(mixed.components()[0].number_fraction, n0 / (n0 + n1));
  // Volume fraction of component 0 recovered from the number fractions.
  const double v0 = mixed.components()[0].number_fraction * radius_moment(mixed.components()[0], 3);
  EXPECT_NEAR(v0 / mixed.mean_radius_cubed(), 0.3, 1e-12);  // roundings only
}

TEST(Psd, ReadsTableAndIntegratesItsBins) {
  const Psd psd = Psd::parse("table:file=" + table_path);
  const auto& c = psd.components()[0];
  ASSERT_EQ(c.kind, PsdComponent::Kind::table);
  // Seven rows plus the empty 45-50 um gap bin.
  ASSERT_EQ(c.fractions.size(), 8u);
  EXPECT_EQ(c.fractions[6], 0.0);
  EXPECT_DOUBLE_EQ(psd.min_radius(), 7.5e-6);
  EXPECT_DOUBLE_EQ(psd.max_radius(), 30e-6);
  // Uniform within bins: the mean is the fraction-weighted bin centre (radius = diameter / 2).
  const double lo[] = {15, 20, 25, 30, 35, 40, 50};
  const double hi[] = {20, 25, 30, 35, 40, 45, 60};
  const double f[] = {0.10, 0.22, 0.28, 0.20, 0.12, 0.06, 0.02};
  double mean = 0, cube = 0;
  for (int i = 0; i < 7; ++i) {
    const double a = lo[i] * 0.5e-6, b = hi[i] * 0.5e-6;
    mean += f[i] * (a + b) / 2;
    cube += f[i] * (b * b * b * b - a * a * a * a) / (4 * (b - a));
  }
  EXPECT_NEAR(psd.mean_radius(), mean, 1e-12 * mean);  // roundings only
  EXPECT_NEAR(psd.mean_radius_cubed(), cube, 1e-12 * cube);
  EXPECT_DOUBLE_EQ(psd.cdf_radius(10e-6), 0.10);     // end of the first bin
  EXPECT_DOUBLE_EQ(psd.cdf_radius(23e-6), 0.98);     // inside the gap
  EXPECT_DOUBLE_EQ(psd.cdf_radius(11.25e-6), 0.21);  // middle of the second bin
  // on=radius reads the same edges as radii.
  EXPECT_DOUBLE_EQ(Psd::parse("table:file=" + table_path + ",on=radius").max_radius(), 60e-6);
}

// ------------------------------------------------------------------------ analytic moments

TEST(Psd, ClosedFormMomentsMatchQuadrature) {
  // Simpson with 2e4 panels on smooth densities is exact to ~1e-13 relative; 1e-9 leaves room.
  const double tol = 1e-9;
  {
    const Psd psd = Psd::parse(lp_table2);
    auto pdf = [](double r) { return std::exp(-0.5 * std::pow((r - 0.075e-6) / 0.0375e-6, 2)); };
    for (int k = 1; k <= 3; ++k) {
      const double q = quadrature_moment(pdf, 0.015e-6, 0.15e-6, k);
      EXPECT_NEAR(radius_moment(psd.components()[0], k), q, tol * q) << "gauss k=" << k;
    }
  }
  {
    // Lognormal on diameter, median 30 um, gsd 1.5, window [10, 60] um diameter.
    const Psd psd = Psd::parse("lognormal:median=30e-6,gsd=1.5,min=10e-6,max=60e-6");
    const double mu = std::log(15e-6), sigma = std::log(1.5);
    auto pdf = [&](double r) {
      return std::exp(-0.5 * std::pow((std::log(r) - mu) / sigma, 2)) / r;
    };
    for (int k = 1; k <= 3; ++k) {
      const double q = quadrature_moment(pdf, 5e-6, 30e-6, k);
      EXPECT_NEAR(radius_moment(psd.components()[0], k), q, tol * q) << "lognormal k=" << k;
    }
  }
  {
    // Far in the upper tail: window [6, 7] sd.
    const Psd psd = Psd::parse("gauss:mean=0,sd=1,min=6,max=7,on=radius");
    auto pdf = [](double r) { return std::exp(-0.5 * r * r); };
    for (int k = 1; k <= 3; ++k) {
      const double q = quadrature_moment(pdf, 6, 7, k);
      EXPECT_NEAR(radius_moment(psd.components()[0], k), q, tol * q) << "tail k=" << k;
    }
  }
}

// -------------------------------------------------------------------------------- sampling

// Sample mean and variance of 2e5 draws against the analytic truncated-normal moments. The
// tolerance is 5 standard errors (SE of the mean sqrt(var/n); SE of the variance
// sqrt((m4 - var^2)/n) with m4 the sample fourth central moment): a correct sampler fails a
// check with probability ~6e-7.
void check_sample_moments(const std::string& spec, std::uint64_t seed) {
  const Psd psd = Psd::parse(spec);
  const std::size_t n = 200000;
  const auto r = draw(psd, n, seed);
  double mean = 0;
  for (const double x : r) mean += x;
  mean /= n;
  double var = 0, m4 = 0;
  for (const double x : r) {
    const double d = x - mean;
    var += d * d;
    m4 += d * d * d * d;
  }
  var /= n - 1;
  m4 /= n;
  const double mean_exact = psd.mean_radius();
  const double var_exact = psd.mean_radius_squared() - mean_exact * mean_exact;
  EXPECT_NEAR(mean, mean_exact, 5 * std::sqrt(var_exact / n)) << spec;
  EXPECT_NEAR(var, var_exact, 5 * std::sqrt((m4 - var * var) / n)) << spec;
  EXPECT_GE(*std::min_element(r.begin(), r.end()), psd.min_radius()) << spec;
  EXPECT_LE(*std::max_element(r.begin(), r.end()), psd.max_radius()) << spec;
}

TEST(Psd, SampleMomentsMatchTruncatedNormal) {
  check_sample_moments(lp_table2, 11);
  check_sample_moments("gauss:mean=30e-6,sd=10e-6,min=10e-6,max=50e-6", 12);  // [GZ] Table 3
  check_sample_moments(bimodal, 13);
}

TEST(Psd, FarTailWindowSamplesInsideWithFiniteValues) {
  // Phi(6) rounds to 1 - 1e-9: a lower-tail inverse CDF would lose all precision here, and
  // rejection sampling would need ~1e9 tries per particle.
  const Psd psd = Psd::parse("gauss:mean=0,sd=1,min=6,max=7,on=radius");
  const auto r = draw(psd, 10000, 21);
  for (const double x : r) {
    ASSERT_TRUE(std::isfinite(x));
    ASSERT_GE(x, 6.0);
    ASSERT_LE(x, 7.0);
  }
  EXPECT_LT(ks_distance(r, psd), 1.63 / std::sqrt(10000.0));  // 1 % KS critical value
  // Still finite 30 sd out (window mass ~5e-198), and the mirror image in the lower tail.
  for (const std::string spec :
       {"gauss:mean=0,sd=1,min=30,max=31,on=radius", "gauss:mean=40,sd=1,min=1,max=10,on=radius"}) {
    const Psd far = Psd::parse(spec);
    for (const double x : draw(far, 1000, 22)) {
      ASSERT_TRUE(std::isfinite(x)) << spec;
      ASSERT_GE(x, far.min_radius()) << spec;
      ASSERT_LE(x, far.max_radius()) << spec;
    }
    EXPECT_TRUE(std::isfinite(far.mean_radius_cubed())) << spec;
  }
}

TEST(Psd, KsDistanceOfSamplesIsBelowTheOnePercentCriticalValue) {
  // n = 1e4 samples per PSD, fixed seeds; D_n < 1.63 / sqrt(n) is the asymptotic 1 % critical
  // value of the one-sample KS test.
  const std::size_t n = 10000;
  const double critical = 1.63 / std::sqrt(static_cast<double>(n));
  const std::vector<std::string> specs = {
      lp_table2,
      "gauss:mean=27e-6,sd=4.25e-6,min=10e-6,max=50e-6",
      "lognormal:median=30e-6,gsd=1.4",
      "lognormal:median=30e-6,gsd=1.4,min=20e-6,max=40e-6,on=radius",
      "lognormal:d10=15e-6,d50=28e-6,d90=45e-6",
      "table:file=" + table_path,
      bimodal,
      "gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6,frac=0.3+table:file=" + table_path +
          ",frac=0.7"};
  std::uint64_t seed = 100;
  for (const auto& spec : specs) {
    const double d = ks_distance(draw(Psd::parse(spec), n, ++seed), Psd::parse(spec));
    EXPECT_LT(d, critical) << spec;
  }
  // A wrong PSD is told apart: LP samples against a shifted window.
  const double wrong = ks_distance(draw(Psd::parse(lp_table2), n, 7),
                                   Psd::parse("gauss:mean=0.08e-6,sd=0.0375e-6,min=0.015e-6,"
                                              "max=0.15e-6,on=radius"));
  EXPECT_GT(wrong, critical);
}

TEST(Psd, KsDistanceHandlesTiesAndPointMasses) {
  const Psd mono = Psd::parse("mono:r=1");
  EXPECT_EQ(ks_distance({1, 1, 1, 1}, mono), 0.0);
  // Half the samples at the atom of a 50/50 mono mixture, half at the other: exact fit.
  const Psd two = Psd::parse("mono:r=1+mono:r=2");
  EXPECT_EQ(ks_distance({1, 2, 2, 1}, two), 0.0);
  EXPECT_DOUBLE_EQ(ks_distance({1, 1, 1, 2}, two), 0.25);
  EXPECT_EQ(ks_distance({}, two), 0.0);
}

TEST(Psd, SamplingIsDeterministicWithTwoDrawsPerSample) {
  for (const std::string& spec : {bimodal, std::string("mono:d=1e-6"), lp_table2}) {
    const Psd psd = Psd::parse(spec);
    Rng a(5), b(5);
    for (int i = 0; i < 100; ++i) psd.sample_radius(a);
    b.discard(200);
    EXPECT_EQ(a(), b()) << spec;
    EXPECT_EQ(draw(psd, 50, 9), draw(psd, 50, 9)) << spec;
  }
}

TEST(Psd, QuantileInvertsTheCdf) {
  // 1e-9 in probability: the inverse CDF is exact up to erfc/erfc_inv rounding (~1e-15),
  // amplified by at most the window-mass normalisation.
  for (const std::string& spec :
       {lp_table2, std::string("lognormal:median=30e-6,gsd=1.4,min=20e-6,max=40e-6"),
        "table:file=" + table_path, std::string("gauss:mean=0,sd=1,min=6,max=7")}) {
    const Psd psd = Psd::parse(spec);
    const auto& c = psd.components()[0];
    for (const double u : {0.0, 0.01, 0.3, 0.5, 0.77, 0.999}) {
      EXPECT_NEAR(cdf_radius(c, quantile_radius(c, u)), u, 1e-9) << spec << " u=" << u;
    }
  }
}

TEST(Psd, D10D50D90FitReproducesItsQuantiles) {
  // z90 = Phi^-1(0.9); sigma = ln(d90/d10) / (2 z90), mu = ln d50.
  const double z90 = 1.2815515655446004;
  const Psd psd = Psd::parse("lognormal:d10=15e-6,d50=30e-6,d90=60e-6,basis=number");
  const auto& c = psd.components()[0];
  EXPECT_NEAR(c.mu, std::log(30e-6), 1e-12);
  EXPECT_NEAR(c.sigma, std::log(4.0) / (2 * z90), 1e-12);
  // Log-symmetric input: all three quantiles reproduced. 1e-6: the default ±5 sigma window
  // removes 2.9e-7 of the mass on each side, shifting the CDF by less than that.
  EXPECT_NEAR(psd.cdf_radius(7.5e-6), 0.1, 1e-6);
  EXPECT_NEAR(psd.cdf_radius(15e-6), 0.5, 1e-6);
  EXPECT_NEAR(psd.cdf_radius(30e-6), 0.9, 1e-6);
  // Skewed input: the median exactly, d10 and d90 by their geometric mean ratio (the least-
  // squares fit with mu pinned by d50 splits the misfit equally between them).
  const Psd skew = Psd::parse("lognormal:d10=10e-6,d50=30e-6,d90=60e-6,basis=number");
  EXPECT_NEAR(skew.cdf_radius(15e-6), 0.5, 1e-6);
  const auto& s = skew.components()[0];
  const double q10 = std::exp(s.mu - z90 * s.sigma), q90 = std::exp(s.mu + z90 * s.sigma);
  EXPECT_NEAR(q90 / q10, 6.0, 1e-12);
  EXPECT_NEAR(skew.cdf_radius(q10 / 2), 0.1, 1e-6);
  EXPECT_NEAR(skew.cdf_radius(q90 / 2), 0.9, 1e-6);
}

TEST(Psd, CdfIsAMixtureFromZeroToOne) {
  const Psd psd = Psd::parse(bimodal);
  EXPECT_EQ(psd.cdf_radius(1.9e-6), 0.0);
  EXPECT_EQ(psd.cdf_radius(20e-6), 1.0);
  // Between the two windows (6 um < r < 10 um) the CDF sits at the small fraction.
  EXPECT_DOUBLE_EQ(psd.cdf_radius(8e-6), 3000.0 / 3550.0);
  double last = 0;
  for (double r = 1e-6; r < 21e-6; r += 0.1e-6) {
    EXPECT_GE(psd.cdf_radius(r), last);
    last = psd.cdf_radius(r);
  }
}

// ------------------------------------------------------------------------------------ errors

struct BadSpec {
  std::string spec;
  std::vector<std::string> words;  // all must appear in the message
};

TEST(Psd, MalformedSpecsThrowOneLineNamingTheField) {
  const std::string g = "gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6";
  const std::vector<BadSpec> cases = {
      {"", {"--psd", "empty"}},
      {"weibull:k=2", {"component 1 (weibull)", "unknown kind"}},
      {"mono", {"component 1 (mono)", "kind:key=value"}},
      {g + ",wibble=1", {"component 1 (gauss)", "unknown key 'wibble'"}},
      {"gauss:mean=30e-6,sd=5e-6,min=20e-6", {"component 1 (gauss)", "missing key 'max'"}},
      {"gauss:mean=30um,sd=5e-6,min=20e-6,max=40e-6", {"(gauss)", "mean", "30um", "not a number"}},
      {"gauss:mean=nan,sd=5e-6,min=20e-6,max=40e-6", {"(gauss)", "mean", "not a number"}},
      {"mono:d=0", {"component 1 (mono)", "d = 0", "> 0"}},
      {"mono:r=-1e-6", {"(mono)", "r = -1e-6"}},
      {"mono:d=1,r=1", {"(mono)", "exactly one of d="}},
      {"gauss:mean=30e-6,sd=-5e-6,min=20e-6,max=40e-6", {"(gauss)", "sd = -5e-6", "sd >= 0"}},
      {"gauss:mean=30e-6,sd=5e-6,min=40e-6,max=20e-6", {"(gauss)", "min 4e-05 > max 2e-05"}},
      {"gauss:mean=30e-6,sd=5e-6,min=0,max=20e-6", {"(gauss)", "min = 0"}},
      {"gauss:mean=30e-6,sd=5e-6,min=-1e-6,max=20e-6", {"(gauss)", "min = -1e-6"}},
      {"gauss:mean=0,sd=1,min=40,max=41", {"(gauss)", "window [40, 41]", "no probability mass"}},
      {"gauss:mean=30e-6,sd=5e-6,min=20e-6,max=20e-6", {"(gauss)", "no probability mass"}},
      {"gauss:mean=10e-6,sd=0,min=20e-6,max=40e-6", {"(gauss)", "sd = 0", "mean 10e-6"}},
      {g + ",on=area", {"(gauss)", "on = 'area'"}},
      {"lognormal:median=30e-6,gsd=1", {"(lognormal)", "gsd = 1", "> 1"}},
      {"lognormal:median=30e-6,gsd=0.5", {"(lognormal)", "gsd"}},
      {"lognormal:median=30e-6", {"(lognormal)", "missing key 'gsd'"}},
      {"lognormal:min=1e-6", {"(lognormal)", "missing key 'median'"}},
      {"lognormal:d10=30e-6,d50=20e-6,d90=60e-6", {"(lognormal)", "d10", "d10 < d50 < d90"}},
      {"lognormal:d10=10e-6,d50=20e-6", {"(lognormal)", "missing key 'd90'"}},
      {"lognormal:median=30e-6,gsd=1.5,d50=20e-6", {"(lognormal)", "not both"}},
      {"lognormal:median=30e-6,gsd=1.5,min=40e-6,max=30e-6", {"(lognormal)", "min", "max"}},
      {"mono:d=1e-6,count=0", {"(mono)", "count = '0'", "positive integer"}},
      {"mono:d=1e-6,count=2.5", {"(mono)", "count = '2.5'"}},
      {"mono:d=1e-6,count=-3", {"(mono)", "count = '-3'"}},
      {"mono:d=1e-6,count=many", {"(mono)", "count = 'many'"}},
      {"mono:d=1e-6,frac=0", {"(mono)", "frac = 0", "0 < frac <= 1"}},
      {"mono:d=1e-6,frac=1.5", {"(mono)", "frac = 1.5"}},
      {"mono:d=1e-6,vfrac=2", {"(mono)", "vfrac = 2"}},
      {"mono:d=1e-6,count=5,frac=0.5", {"(mono)", "more than one of count, frac, vfrac"}},
      {"mono:d=1e-6,count=5+mono:d=2e-6,frac=0.5", {"component 2 (mono)", "frac mixed with count"}},
      {"mono:d=1e-6,frac=0.5+mono:d=2e-6,count=5", {"component 2 (mono)", "count mixed with frac"}},
      {"mono:d=1e-6,count=5+mono:d=2e-6", {"component 2 (mono)", "no count/frac/vfrac"}},
      {"mono:d=1e-6+mono:d=2e-6,frac=0.5", {"component 1 (mono)", "component 2 has frac"}},
      {"mono:d=1e-6+gauss:mean=1,sd=-1,min=1,max=2", {"component 2 (gauss)", "sd"}},
      {"mono:d=1e-6,d=2e-6", {"(mono)", "key 'd' given twice"}},
      {"mono:d=1e-6,", {"(mono)", "empty field"}},
      {"mono:d", {"(mono)", "field 'd' is not key=value"}},
      {"table:file=/nonexistent/psd.csv", {"(table)", "'/nonexistent/psd.csv'", "cannot be read"}},
      {"table:on=radius", {"(table)", "missing key 'file'"}},
  };
  for (const auto& c : cases) {
    const std::string msg = error_of(c.spec);
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_EQ(msg.rfind(c.spec.empty() ? "--psd: " : "--psd: component ", 0), 0u) << msg;
    for (const auto& w : c.words) {
      EXPECT_NE(msg.find(w), std::string::npos)
          << "spec '" << c.spec << "': '" << w << "' not in: " << msg;
    }
  }
  // The option name given by the caller starts the message.
  try {
    Psd::parse("mono:d=-1", "--size");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--size: component 1 (mono)", 0), 0u) << e.what();
  }
  EXPECT_THROW(Psd::mono_radius(0), InputError);
}

TEST(Psd, MalformedTableFilesNameFileAndLine) {
  const auto dir = std::filesystem::temp_directory_path() / "powderbed_test_psd";
  std::filesystem::create_directories(dir);
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"size,count\n1e-6,2e-6,1\n", {"line 1", "header 'size,count'"}},
      {"edge_low,edge_high,fraction\n1e-6,2e-6,0.5\n2e-6,abc,0.5\n", {"line 3", "'abc'"}},
      {"edge_low,edge_high,fraction\n1e-6,2e-6\n", {"line 2", "expected edge_low"}},
      {"edge_low,edge_high,fraction\n2e-6,1e-6,1\n", {"line 2", "edge_low < edge_high"}},
      {"edge_low,edge_high,fraction\n0,1e-6,1\n", {"line 2", "0 < edge_low"}},
      {"edge_low,edge_high,fraction\n1e-6,2e-6,-1\n", {"line 2", "fraction -1"}},
      {"edge_low,edge_high,fraction\n1e-6,3e-6,1\n2e-6,4e-6,1\n", {"line 3", "non-overlapping"}},
      {"edge_low,edge_high,fraction\n1e-6,2e-6,0\n", {"no bin with a fraction > 0"}},
      {"# only a comment\n", {"no header"}},
  };
  int i = 0;
  for (const auto& [content, words] : cases) {
    const auto path = (dir / ("bad" + std::to_string(i++) + ".csv")).string();
    std::ofstream(path) << content;
    const std::string msg = error_of("table:file=" + path);
    EXPECT_NE(msg.find("--psd: component 1 (table): file '" + path + "'"), std::string::npos)
        << msg;
    for (const auto& w : words) EXPECT_NE(msg.find(w), std::string::npos) << w << " in " << msg;
  }
  // Windows line endings and blanks around cells are fine.
  const auto ok = (dir / "crlf.csv").string();
  std::ofstream(ok) << "edge_low, edge_high, fraction\r\n1e-6, 2e-6, 3\r\n";
  EXPECT_DOUBLE_EQ(Psd::parse("table:file=" + ok + ",on=radius").mean_radius(), 1.5e-6);
  std::filesystem::remove_all(dir);
}

}  // namespace

namespace {

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// Asymptotic sd of the volume-weighted sample q-quantile of N diameters from a lognormal with
// number parameters mu, sigma (ln d). The weighted quantile m solves sum w_i (1{d_i <= m} - q)
// = 0 with w = d^3; as an M-estimator its variance is E[w^2 (1{d <= m} - q)^2] / (N (dG/dm)^2)
// with G(m) = E[w 1{d <= m}], dG/dm = w(m) f_n(m) = E[w] f_v(m), f_v the volume density.
// Lognormal partial moments: E[d^k 1{d <= m}] = exp(k mu + k^2 sigma^2 / 2) Phi((ln m - mu -
// k sigma^2) / sigma).
double weighted_quantile_sd(double mu, double sigma, double q, double m, std::size_t n) {
  const auto moment = [&](int k) { return std::exp(k * mu + 0.5 * k * k * sigma * sigma); };
  const auto below = [&](int k) {
    return moment(k) * normal_cdf((std::log(m) - mu - k * sigma * sigma) / sigma);
  };
  const double numerator = (1 - q) * (1 - q) * below(6) + q * q * (moment(6) - below(6));
  const double mu_v = mu + 3 * sigma * sigma;
  const double z = (std::log(m) - mu_v) / sigma;
  const double f_v = std::exp(-0.5 * z * z) / (m * sigma * std::sqrt(2 * M_PI));
  return std::sqrt(numerator / static_cast<double>(n)) / (moment(3) * f_v);
}

}  // namespace

TEST(PsdBasis, VolumeD10D50D90AreTheVolumeQuantilesOfTheSample) {
  // A 20-45 um powder as its data sheet gives it (laser diffraction: volume basis, the
  // default), log-symmetric (20 x 45 = 30^2) so the fit passes through all three values.
  const Psd psd = Psd::parse("lognormal:d10=20e-6,d50=30e-6,d90=45e-6");
  const auto& c = psd.components()[0];
  EXPECT_EQ(c.basis, powderbed::bed::PsdBasis::volume);
  // Hatch-Choate: the number median lies 3 sigma^2 below the volume median in ln d.
  EXPECT_NEAR(c.mu, std::log(30e-6) - 3 * c.sigma * c.sigma, 1e-12);
  const std::size_t n = 20000;  // fixed seed
  const auto radii = draw(psd, n, 41);
  for (const auto& [q, d] : {std::pair{0.1, 20e-6}, std::pair{0.5, 30e-6}, std::pair{0.9, 45e-6}}) {
    const double sample =
        powderbed::bed::sample_diameter_quantile(radii, q, powderbed::bed::PsdBasis::volume);
    // 4 sd of the weighted quantile (0.13 um at D50 here): a seed this far off happens with
    // probability 6e-5, while reading the values by number (the old behaviour) puts the volume
    // D50 at 30 exp(3 sigma^2) = 40.5 um, 80 sd away. The 5-sigma windows move the quantiles
    // by less than 1e-6 relative.
    const double sd = weighted_quantile_sd(c.mu, c.sigma, q, d, n);
    EXPECT_NEAR(sample, d, 4 * sd) << "q = " << q << ", sd = " << sd;
    EXPECT_LT(4 * sd, 0.05 * d);  // the test resolves the basis (a 3 sigma^2 = 0.30 shift in ln d)
  }
}

TEST(PsdBasis, NumberBasisIsTheOldReading) {
  const Psd psd = Psd::parse("lognormal:d10=20e-6,d50=30e-6,d90=45e-6,basis=number");
  const auto& c = psd.components()[0];
  const double z90 = 1.2815515655446004;
  EXPECT_EQ(c.mu, std::log(30e-6));  // exactly the fit of before: mu = ln d50
  EXPECT_NEAR(c.sigma, std::log(45.0 / 20.0) / (2 * z90), 1e-15);
  // The number median of a sample: sd = sqrt(q (1 - q) / N) / f_n(m) = m sigma sqrt(2 pi) /
  // (2 sqrt N) (0.14 um for N = 20000); 4 sd.
  const std::size_t n = 20000;
  const double d50 = powderbed::bed::sample_diameter_quantile(draw(psd, n, 43), 0.5,
                                                              powderbed::bed::PsdBasis::number);
  const double sd = 30e-6 * c.sigma * std::sqrt(2 * M_PI) / (2 * std::sqrt(double(n)));
  EXPECT_NEAR(d50, 30e-6, 4 * sd);
  // Forms that were number-based stay so, and an explicit basis=number changes no draw.
  for (const std::string& spec : std::vector<std::string>{
           "gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6", "lognormal:median=30e-6,gsd=1.4",
           "table:file=" + table_path, "mono:d=30e-6"}) {
    EXPECT_EQ(Psd::parse(spec).components()[0].basis, powderbed::bed::PsdBasis::number) << spec;
    EXPECT_EQ(draw(Psd::parse(spec), 100, 3), draw(Psd::parse(spec + ",basis=number"), 100, 3))
        << spec;
  }
}

TEST(PsdBasis, VolumeTableBinsBecomeNumberFractions) {
  // Two bins [10, 20] and [20, 30] um with half the volume each. Uniform by number within a
  // bin, E[d^3] = (b^4 - a^4) / (4 (b - a)): 3750 and 16250 um^3, so the number fractions are
  // 16250 : 3750, i.e. 0.8125 in the first bin.
  const std::string dir = std::filesystem::temp_directory_path() / "powderbed_psd_volume_table";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/t.csv";
  std::ofstream(path) << "edge_low,edge_high,fraction\n10e-6,20e-6,0.5\n20e-6,30e-6,0.5\n";
  const Psd psd = Psd::parse("table:file=" + path + ",basis=volume");
  EXPECT_NEAR(psd.cdf_radius(10e-6), 0.8125, 1e-12);
  std::filesystem::remove_all(dir);
}

TEST(PsdBasis, VolumeGaussIsTheVolumeDensity) {
  // gauss on the volume basis: the volume-weighted mean diameter sum d^4 / sum d^3 of a sample
  // is the mean of the (symmetric, so untruncated) normal, 30 um. Its sampling sd comes from the
  // sample itself (delta method for a ratio of means: 0.036 um here); 4 sd. Read by number
  // instead the volume-weighted mean is 31.85 um, 50 sd away.
  const Psd psd = Psd::parse("gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6,basis=volume");
  const std::size_t n = 20000;
  const auto radii = draw(psd, n, 47);
  double a = 0, b = 0;
  for (const double r : radii) {
    a += std::pow(2 * r, 4);
    b += std::pow(2 * r, 3);
  }
  const double mean = a / b;
  double var = 0;
  for (const double r : radii) {
    const double d = 2 * r;
    var += std::pow(std::pow(d, 4) - mean * std::pow(d, 3), 2);
  }
  const double sd = std::sqrt(var / double(n)) / (b / double(n)) / std::sqrt(double(n));
  EXPECT_NEAR(mean, 30e-6, 4 * sd) << "sd = " << sd;
  EXPECT_LT(4 * sd, 1e-6);
  EXPECT_EQ(psd.min_radius(), 10e-6);
  EXPECT_EQ(psd.max_radius(), 20e-6);
}

TEST(PsdBasis, UnknownBasisIsRefused) {
  try {
    Psd::parse("mono:d=30e-6,basis=mass");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("accepted: number, volume"), std::string::npos) << e.what();
  }
}
