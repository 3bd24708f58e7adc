// Bond-orientational order of docs/physics.md §2's contact network (Steinhardt, Nelson & Ronchetti,
// Phys. Rev. B 28, 784 (1983)), l = 6: tells a random packing from a crystal.
#include <boost/math/special_functions/spherical_harmonic.hpp>
#include <algorithm>
#include <cmath>
#include <complex>
#include <fmt/format.h>
#include <numbers>

#include "neighbours_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/stats.hpp"

namespace powderbed::bed {

namespace {

constexpr int kL = 6;
constexpr std::size_t kM = kL + 1;  // m = 0..6; Y_{6,-m} = (-1)^m conj(Y_6m) gives the rest

// sum_{m=-6..6} |q_m|^2 from the m >= 0 half.
double power(const std::complex<double>* q) {
  double s = std::norm(q[0]);
  for (std::size_t m = 1; m < kM; ++m) s += 2 * std::norm(q[m]);
  return s;
}

// q_l = sqrt(4 pi / (2l + 1) sum_m |q_lm|^2), q_lm = sum / bonds.
double q6(const std::complex<double>* sum, double bonds) {
  return std::sqrt(4 * std::numbers::pi / (2 * kL + 1) * power(sum) / (bonds * bonds));
}

}  // namespace

OrderStats bond_order(const Bed& bed, double tolerance, double margin) {
  if (!std::isfinite(tolerance) || !(tolerance > -1) || !std::isfinite(margin) || margin < 0) {
    throw InputError(fmt::format(
        "bond_order: tolerance {:g}, margin {:g} (accepted: tolerance finite > -1, margin finite "
        ">= 0)",
        tolerance, margin));
  }
  if (bed.domain.dimension != 3) {
    throw InputError("bond_order: a 2D bed (accepted: 3D beds; q6 is defined on the sphere)");
  }
  detail::check_pair_index_range(bed, "bond_order");
  OrderStats out;
  out.tolerance = tolerance;
  const std::size_t n = bed.n();
  if (n < 2) return out;
  const detail::PairGeometry g(bed);
  const double scale = 1.0 + tolerance;
  std::vector<std::complex<double>> sum(n * kM);
  std::vector<std::uint32_t> bonds(n, 0);
  const detail::CellList cells(g, 2.0 * detail::max_radius(bed) * std::max(scale, 1.0));
  const double* r = bed.radius.data();
  cells.for_each_candidate([&](std::uint32_t i, std::uint32_t j, double d2) {
    const double reach = (r[i] + r[j]) * scale;
    // The contact rule of contact_stats (same pre-test, same exact test), so bonds = contacts.
    if (!(d2 <= reach * reach * (1.0 + 1e-12) && std::sqrt(d2) <= reach) || d2 == 0) return;
    const double dx = g.delta(0, g.x[i], g.x[j]), dy = g.delta(1, g.y[i], g.y[j]);
    const double dz = g.delta(2, g.z[i], g.z[j]);
    const double theta = std::acos(std::clamp(dz / std::sqrt(d2), -1.0, 1.0));
    const double phi = std::atan2(dy, dx);
    // l even: Y6m(-r) = Y6m(r), so the bond adds the same terms to i and to j.
    for (std::size_t m = 0; m < kM; ++m) {
      const auto y = boost::math::spherical_harmonic(kL, static_cast<int>(m), theta, phi);
      sum[i * kM + m] += y;
      sum[j * kM + m] += y;
    }
    ++bonds[i];
    ++bonds[j];
  });
  const Domain& d = bed.domain;
  const std::vector<double>* centre[3] = {&g.x, &g.y, &g.z};
  std::complex<double> total[kM];
  double local = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (bonds[i] == 0) continue;
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      const double c = (*centre[a])[i];
      if (!d.periodic[a] && (c - d.lower[a] < margin || d.upper[a] - c < margin)) inside = false;
    }
    if (!inside) continue;
    local += q6(&sum[i * kM], bonds[i]);
    for (std::size_t m = 0; m < kM; ++m) total[m] += sum[i * kM + m];
    ++out.particles;
    out.bonds += bonds[i];
  }
  if (out.particles == 0) return out;
  out.q6_local_mean = local / static_cast<double>(out.particles);
  out.q6_global = q6(total, static_cast<double>(out.bonds));
  return out;
}

}  // namespace powderbed::bed
