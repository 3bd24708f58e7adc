// Rong–Horio gas-lens conductance by exact l_min part + Gauss–Legendre in ln l (gas_lens.hpp).
#include "powderbed/keff/gas_lens.hpp"

#include <array>
#include <cmath>

#include "powderbed/bed/contact_geometry.hpp"

namespace powderbed::keff {
namespace {

struct GaussLegendre {
  std::array<double, kGasLensNodes> node{}, weight{};  // on [-1, 1]
};

// Nodes by Newton on P_n from the Chebyshev guess (converges to round-off in a few steps).
GaussLegendre make_gauss_legendre() {
  GaussLegendre g;
  constexpr int n = kGasLensNodes;
  for (int k = 0; k < n; ++k) {
    double x = std::cos(M_PI * (k + 0.75) / (n + 0.5));
    double derivative = 1;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1, p1 = x;
      for (int m = 2; m <= n; ++m) {
        const double p2 = ((2 * m - 1) * x * p1 - (m - 1) * p0) / m;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    g.node[static_cast<std::size_t>(k)] = x;
    g.weight[static_cast<std::size_t>(k)] = 2 / ((1 - x * x) * derivative * derivative);
  }
  return g;
}

const GaussLegendre& gauss_legendre() {
  static const GaussLegendre g = make_gauss_legendre();
  return g;
}

// π ∫ du / max(l_min, l(u)) over [u_in, u_out] for a geometry with gap(u) increasing, its
// inverse u_of_gap(l) and du_dgap(l).
template <class Geometry>
double lens_integral(const GasLensParams& p, const Geometry& g, double u_in, double u_out) {
  if (!(u_out > u_in)) return 0;
  const double l_in = std::fmax(g.gap(u_in), 0.0), l_out = g.gap(u_out);
  if (l_out <= p.min_gap) return M_PI * (u_out - u_in) / p.min_gap;
  const double u_star = l_in < p.min_gap ? g.u_of_gap(p.min_gap) : u_in;
  double result = M_PI * (u_star - u_in) / p.min_gap;
  const double w0 = std::log(std::fmax(l_in, p.min_gap)), w1 = std::log(l_out);
  const double half = (w1 - w0) / 2, mid = (w1 + w0) / 2;
  const GaussLegendre& gl = gauss_legendre();
  double sum = 0;
  for (std::size_t k = 0; k < gl.node.size(); ++k)
    sum += gl.weight[k] * g.du_dgap(std::exp(mid + half * gl.node[k]));
  return result + M_PI * half * sum;
}

// Two spheres (A = r_i², B = r_j²) at centre distance d: l(u) = d − √(A−u) − √(B−u). With
// s = d − l the two roots p = √(A−u), q = √(B−u) satisfy p + q = s, p − q = (A−B)/s.
struct PairGeometry {
  double a, b, d;
  double gap(double u) const { return d - std::sqrt(a - u) - std::sqrt(b - u); }
  double root_i(double l) const {
    const double s = d - l;
    return (s + (a - b) / s) / 2;
  }
  double u_of_gap(double l) const {
    const double p = root_i(l);
    return a - p * p;
  }
  double du_dgap(double l) const {
    const double s = d - l;
    return root_i(l) * (1 - (a - b) / (s * s));
  }
};

// A sphere (A = r²) with its centre h from a plane: l(u) = h − √(A−u).
struct WallGeometry {
  double a, h;
  double gap(double u) const { return h - std::sqrt(a - u); }
  double u_of_gap(double l) const { return a - (h - l) * (h - l); }
  double du_dgap(double l) const { return 2 * (h - l); }
};

}  // namespace

double gas_pair_factor(const GasLensParams& p, double r_i, double r_j, double d) {
  const double f = 1 + p.lens;
  const double r_min = std::fmin(r_i, r_j), r_max = std::fmax(r_i, r_j);
  const bool both = p.region == LensRegion::both_lenses;
  const double reach = both ? f * (r_i + r_j) : f * r_max + r_min;
  if (d >= reach || d <= r_max - r_min) return 0;
  const double lens =
      both ? bed::contact_radius(f * r_i, f * r_j, d) : bed::contact_radius(f * r_max, r_min, d);
  const double solid = bed::contact_radius(r_i, r_j, d);
  const double u_out = std::fmin(lens * lens, r_min * r_min);
  return lens_integral(p, PairGeometry{r_i * r_i, r_j * r_j, d}, solid * solid, u_out);
}

double gas_wall_factor(const GasLensParams& p, double r, double h) {
  const double f = 1 + p.lens;
  if (h >= f * r || h <= 0) return 0;
  const double solid = bed::plane_contact_radius(r, h);
  const double u_out = std::fmin(f * f * r * r - h * h, r * r);
  return lens_integral(p, WallGeometry{r * r, h}, solid * solid, u_out);
}

}  // namespace powderbed::keff
