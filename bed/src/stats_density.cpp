// Packing densities of docs/physics.md §2: exact spherical caps / circular segments, and the volume of
// a sphere inside a box.
//
// Sphere ∩ box: a sphere cut on at most one axis is exact (two caps). A sphere cut on two or
// three axes (box edges and corners) is integrated along one cut axis t of the closed-form area
// of the disk cross-section ∩ rectangle. That area is analytic in t between the heights where
// the disk becomes tangent to a rectangle side or passes a rectangle corner; the integral is
// split there and each piece done by tanh-sinh quadrature (Boost.Math), which is insensitive to
// the algebraic endpoint behaviour at those breakpoints. With the requested relative tolerance
// 1e-12 the error is at the level of double rounding (tests compare with exact octant cases at
// 1e-12). Periodic axes are never cut: the rest of a particle is its image on the other side.
#include <algorithm>
#include <array>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/bed/stats.hpp"
#include "powderbed/bed/stats_layer.hpp"

namespace powderbed::bed {

namespace {

constexpr double pi = std::numbers::pi;

// pi * integral_0^t (r^2 - s^2) ds: the volume of the sphere slice 0 <= z <= t (|t| <= r).
double cap_primitive(double r, double t) { return pi * (r * r * t - t * t * t / 3.0); }

// integral_0^x 2 sqrt(r^2 - s^2) ds: the area of the disk strip 0 <= y <= x (|x| <= r).
double segment_primitive(double r, double x) {
  return x * std::sqrt(std::max(r * r - x * x, 0.0)) + r * r * std::asin(std::clamp(x / r, -1.0, 1.0));
}

void check_radius(double r, const char* what) {
  if (!(r > 0) || !std::isfinite(r)) {
    throw InputError(fmt::format("{}: radius {:g} (accepted: > 0, finite)", what, r));
  }
}

void check_interval(double lo, double hi, const char* what) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi >= lo)) {
    throw InputError(fmt::format("{}: interval [{:g}, {:g}] (accepted: finite, lower <= upper)",
                                 what, lo, hi));
  }
}

// Area of disk(rho) ∩ [0, a] x [0, b] for a, b >= 0.
double quadrant_rect_area(double rho, double a, double b) {
  a = std::min(a, rho);
  b = std::min(b, rho);
  const double rho2 = rho * rho;
  if (a * a + b * b <= rho2) return a * b;
  // The circle is at height b at x = xs < a: rectangle up to xs, disk strip after.
  const double xs = std::sqrt(std::max(rho2 - b * b, 0.0));
  return b * xs + 0.5 * (segment_primitive(rho, a) - segment_primitive(rho, xs));
}

// Signed area of disk(rho) ∩ [0, u] x [0, v] (signs as for an oriented integral).
double corner_area(double rho, double u, double v) {
  const double a = quadrant_rect_area(rho, std::abs(u), std::abs(v));
  return (u < 0) != (v < 0) ? -a : a;
}

// Area of disk(rho) centred at the origin ∩ [u0, u1] x [v0, v1] (u0 <= u1, v0 <= v1).
double disk_rect_area(double rho, double u0, double u1, double v0, double v1) {
  if (!(rho > 0)) return 0.0;
  return corner_area(rho, u1, v1) - corner_area(rho, u0, v1) - corner_area(rho, u1, v0) +
         corner_area(rho, u0, v0);
}

// An axis-aligned box; +-infinity for an unbounded side.
struct Box {
  std::array<double, 3> lo, hi;
};

// integral over t in [t0, t1] of area(disk(sqrt(r^2 - t^2)) ∩ [u0, u1] x [v0, v1]), all bounds
// relative to the centre and within [-r, r].
double integrate_sections(double r, double t0, double t1, double u0, double u1, double v0,
                          double v1) {
  // integrate() is not const in Boost 1.74; one integrator per thread.
  thread_local boost::math::quadrature::tanh_sinh<double> quadrature;
  const double r2 = r * r;
  double breaks[16];  // 4 sides and 4 corners, two heights each, kept sorted
  int count = 0;
  auto add = [&](double t) {
    if (!(t > t0 && t < t1)) return;
    int k = count++;
    for (; k > 0 && breaks[k - 1] > t; --k) breaks[k] = breaks[k - 1];
    breaks[k] = t;
  };
  const double sides[4] = {u0, u1, v0, v1};
  for (const double s : sides) {
    if (std::abs(s) < r) {
      const double t = std::sqrt(r2 - s * s);
      add(t);
      add(-t);
    }
  }
  for (const double u : {u0, u1}) {
    for (const double v : {v0, v1}) {
      if (std::abs(u) < r && std::abs(v) < r && u * u + v * v < r2) {
        const double t = std::sqrt(r2 - u * u - v * v);
        add(t);
        add(-t);
      }
    }
  }
  auto section = [&](double t) {
    return disk_rect_area(std::sqrt(std::max(r2 - t * t, 0.0)), u0, u1, v0, v1);
  };
  double sum = 0, from = t0;
  for (int k = 0; k <= count; ++k) {
    const double to = k < count ? breaks[k] : t1;
    // A piece where the disk misses the rectangle is empty throughout (the intersection's
    // shape only changes at breakpoints). Pieces shorter than 1e-9 r (breakpoints that
    // coincide up to rounding) take the midpoint rule: error < r^3 (1e-9)^1.5 ~ 3e-14 r^3.
    // Neither can be left to tanh-sinh, which cannot meet a relative tolerance on ~0.
    const double mid = section(0.5 * (from + to));
    if (to - from < 1e-9 * r) {
      sum += mid * std::max(to - from, 0.0);
    } else if (mid > 0) {
      sum += quadrature.integrate(section, from, to, 1e-12);
    }
    from = to;
  }
  return sum;
}

// Volume (3D) or area (2D) of the ball (centre c, radius r) inside the box.
double ball_box_measure(int dim, const std::array<double, 3>& c, double r, const Box& box) {
  std::array<double, 3> lo{}, hi{};
  int cuts = 0, first_cut = -1;
  for (int a = 0; a < dim; ++a) {
    lo[a] = std::max(box.lo[a] - c[a], -r);
    hi[a] = std::min(box.hi[a] - c[a], r);
    if (!(hi[a] > lo[a])) return 0.0;
    if (lo[a] > -r || hi[a] < r) {
      if (first_cut < 0) first_cut = a;
      ++cuts;
    }
  }
  if (dim == 2) return disk_rect_area(r, lo[0], hi[0], lo[1], hi[1]);
  if (cuts == 0) return sphere_volume(r);
  if (cuts == 1) return cap_primitive(r, hi[first_cut]) - cap_primitive(r, lo[first_cut]);
  const int u = (first_cut + 1) % 3, v = (first_cut + 2) % 3;
  return integrate_sections(r, lo[first_cut], hi[first_cut], lo[u], hi[u], lo[v], hi[v]);
}

// The domain box with periodic (and unused) axes unbounded.
Box domain_box(const Domain& d) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box box{{-inf, -inf, -inf}, {inf, inf, inf}};
  for (int a = 0; a < d.dimension; ++a) {
    if (d.periodic[a]) continue;
    box.lo[a] = d.lower[a];
    box.hi[a] = d.upper[a];
  }
  return box;
}

// Calls f(shift) for each image of a particle along the layer axis that may reach [z0, z1]:
// the particle itself, plus whole-period shifts when that axis is periodic.
template <class F>
void for_each_layer_image(const Domain& d, int axis, double c, double r, double z0, double z1,
                          F&& f) {
  if (!d.periodic[axis]) {
    f(0.0);
    return;
  }
  const double period = d.length(axis);
  const double k0 = std::ceil((z0 - c - r) / period), k1 = std::floor((z1 - c + r) / period);
  for (double k = k0; k <= k1; k += 1.0) f(k * period);
}

void check_bed(const Bed& bed, const char* what) {
  bed.domain.validate(what);
  const std::size_t n = bed.n();
  if (bed.x.size() != n || bed.y.size() != n || bed.z.size() != n) {
    throw InputError(fmt::format(
        "{}: position arrays have {}, {}, {} entries for {} radii (accepted: one per particle)",
        what, bed.x.size(), bed.y.size(), bed.z.size(), n));
  }
}

}  // namespace

// docs/physics.md §2: exact spherical-cap volume of the slice z0 <= z <= z1.
double sphere_slab_volume(double r, double zc, double z0, double z1) {
  check_radius(r, "sphere_slab_volume");
  check_interval(z0, z1, "sphere_slab_volume");
  const double a = std::max(z0 - zc, -r), b = std::min(z1 - zc, r);
  return b > a ? cap_primitive(r, b) - cap_primitive(r, a) : 0.0;
}

// docs/physics.md §2 (2D): exact circular-segment area of the strip y0 <= y <= y1.
double disk_strip_area(double r, double yc, double y0, double y1) {
  check_radius(r, "disk_strip_area");
  check_interval(y0, y1, "disk_strip_area");
  const double a = std::max(y0 - yc, -r), b = std::min(y1 - yc, r);
  return b > a ? segment_primitive(r, b) - segment_primitive(r, a) : 0.0;
}

// docs/physics.md §2: phi = (particle volume inside the domain box) / (box volume).
double packing_density(const Bed& bed) {
  check_bed(bed, "packing_density");
  const Box box = domain_box(bed.domain);
  const int dim = bed.domain.dimension;
  double sum = 0;
  for (std::size_t i = 0; i < bed.n(); ++i) {
    sum += ball_box_measure(dim, {bed.x[i], bed.y[i], bed.z[i]}, bed.radius[i], box);
  }
  return sum / bed.domain.measure();
}

// docs/physics.md §2 ([GZ] bottom-layer density): particle volume in the layer / layer volume.
double layer_density(const Bed& bed, double z0, double z1) {
  check_bed(bed, "layer_density");
  if (!std::isfinite(z0) || !std::isfinite(z1) || !(z1 > z0)) {
    throw InputError(
        fmt::format("layer_density: layer [{:g}, {:g}] (accepted: finite, z0 < z1)", z0, z1));
  }
  const Domain& d = bed.domain;
  const int dim = d.dimension, axis = dim - 1;
  Box box = domain_box(d);
  box.lo[axis] = z0;
  box.hi[axis] = z1;
  const std::vector<double>& height = dim == 3 ? bed.z : bed.y;
  double sum = 0;
  for (std::size_t i = 0; i < bed.n(); ++i) {
    std::array<double, 3> c{bed.x[i], bed.y[i], bed.z[i]};
    for_each_layer_image(d, axis, height[i], bed.radius[i], z0, z1, [&](double shift) {
      c[axis] = height[i] + shift;
      sum += ball_box_measure(dim, c, bed.radius[i], box);
    });
  }
  return sum / (d.measure() / d.length(axis) * (z1 - z0));
}

// docs/physics.md §2 height profile: layer densities over `bins` equal layers of the domain height.
Series density_profile(const Bed& bed, std::size_t bins) {
  check_bed(bed, "density_profile");
  if (bins == 0) throw InputError("density_profile: bins is 0 (accepted: >= 1)");
  const Domain& d = bed.domain;
  const int dim = d.dimension, axis = dim - 1;
  const double lower = d.lower[axis], upper = d.upper[axis];
  const double step = (upper - lower) / static_cast<double>(bins);
  auto edge = [&](std::size_t k) {
    return k == bins ? upper : lower + static_cast<double>(k) * step;
  };
  Series out;
  out.x.resize(bins);
  out.y.assign(bins, 0.0);
  for (std::size_t k = 0; k < bins; ++k) out.x[k] = 0.5 * (edge(k) + edge(k + 1));
  Box box = domain_box(d);
  const std::vector<double>& height = dim == 3 ? bed.z : bed.y;
  const double last = static_cast<double>(bins - 1);
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const double r = bed.radius[i];
    std::array<double, 3> c{bed.x[i], bed.y[i], bed.z[i]};
    for_each_layer_image(d, axis, height[i], r, lower, upper, [&](double shift) {
      c[axis] = height[i] + shift;
      const double k0 = std::clamp(std::floor((c[axis] - r - lower) / step), 0.0, last);
      const double k1 = std::clamp(std::floor((c[axis] + r - lower) / step), 0.0, last);
      for (auto k = static_cast<std::size_t>(k0); k <= static_cast<std::size_t>(k1); ++k) {
        box.lo[axis] = edge(k);
        box.hi[axis] = edge(k + 1);
        out.y[k] += ball_box_measure(dim, c, r, box);
      }
    });
  }
  const double layer = d.measure() / d.length(axis) * step;
  for (double& y : out.y) y /= layer;
  return out;
}

// Spread-layer density (docs/spread-layer.md): the solid inside a box, every sphere cut exactly
// by the box faces. On a periodic axis the box is either unbounded (each sphere counts whole: the
// rest of a wrapped particle is its image) or bounded, and then every image reaching it counts.
double solid_volume_in_box(const Bed& bed, const std::array<double, 3>& lo,
                           const std::array<double, 3>& hi) {
  check_bed(bed, "solid_volume_in_box");
  const Domain& d = bed.domain;
  if (d.dimension != 3) throw InputError("solid_volume_in_box: a 2D bed (accepted: 3D beds)");
  const Box box{lo, hi};
  double sum = 0;
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const double r = bed.radius[i];
    const std::array<double, 3> c{bed.x[i], bed.y[i], bed.z[i]};
    std::array<double, 3> k0{}, k1{};  // image shifts, in periods, along each axis
    for (int a = 0; a < 3; ++a) {
      if (d.periodic[a] && std::isfinite(lo[a]) && std::isfinite(hi[a])) {
        k0[a] = std::ceil((lo[a] - c[a] - r) / d.length(a));
        k1[a] = std::floor((hi[a] - c[a] + r) / d.length(a));
      }
    }
    for (double kx = k0[0]; kx <= k1[0]; kx += 1.0) {
      for (double ky = k0[1]; ky <= k1[1]; ky += 1.0) {
        for (double kz = k0[2]; kz <= k1[2]; kz += 1.0) {
          const std::array<double, 3> image{c[0] + kx * d.length(0), c[1] + ky * d.length(1),
                                            c[2] + kz * d.length(2)};
          sum += ball_box_measure(3, image, r, box);
        }
      }
    }
  }
  return sum;
}

}  // namespace powderbed::bed
