#pragma once
// What packgen's two placement algorithms share (docs/physics.md §3): the particles placed so
// far, the exact partner grid, the collision back-end, the random stream and the run's counters;
// the test of a candidate centre (inside the domain, overlapping nothing) and the placement of
// one that passes. After each placement the on-placed hook lets the algorithms keep their own
// state: the contact approaches' partner list (contact_approaches.hpp), lowest-site growth's
// free sites (lowest_site_growth.hpp).
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <utility>

#include "powderbed/bed/domain.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/random.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/packgen/cell_grid.hpp"
#include "powderbed/packgen/contact_geometry.hpp"
#include "powderbed/packgen/pack.hpp"
#include "powderbed/packgen/particles.hpp"

namespace powderbed::packgen::detail {

// Containment tolerance (docs/physics.md §3 "every particle lies fully inside"): 1e-12 relative
// to the radius and the coordinate, so centres computed to touch a wall are not refused for
// rounding.
constexpr double kInsideTolerance = 1e-12;

// Partner codes: >= 0 a particle's index, < 0 a wall as -1 - wall, walls 0..2 dim - 1 being
// lower x, upper x, lower y, ...
inline constexpr std::int64_t wall_code(int wall) { return -1 - wall; }

template <class Backend>
class PlacementCore {
 public:
  PlacementCore(const bed::Domain& domain, const bed::Psd& psd, const PackOptions& options,
                std::uint64_t seed, Particles& particles, CellGrid& partners, Backend& backend)
      : domain_(domain),
        o_(options),
        rng_(seed),
        p_(particles),
        partners_(partners),
        backend_(backend),
        dim_(domain.dimension),
        r_max_(psd.max_radius()),
        r_min_(psd.min_radius()) {
    if (o_.count > 0) {  // no regrowth of the particle arrays in a --count run
      for (auto* v : {&p_.x, &p_.y, &p_.z, &p_.r}) v->reserve(o_.count);
    }
  }

  // The hook called with the index of every particle placed, after it is in the back-ends.
  void on_placed(std::function<void(std::uint32_t)> hook) { on_placed_ = std::move(hook); }

  const bed::Domain& domain() const { return domain_; }
  const PackOptions& options() const { return o_; }
  bed::Rng& rng() { return rng_; }
  const Particles& particles() const { return p_; }
  const CellGrid& partners() const { return partners_; }
  const Backend& backend() const { return backend_; }
  int dim() const { return dim_; }
  double r_min() const { return r_min_; }
  double r_max() const { return r_max_; }
  PackResult& result() { return result_; }
  const PackResult& result() const { return result_; }
  double density() const { return volume_ / domain_.measure(); }

  bool size_fits(double r) const;
  // inside() and partner() run for every candidate centre and every partner of a 3-contact try;
  // with the algorithms in classes of their own GCC 12 stopped inlining them (its unit growth
  // limit), which cost 1.7 % more instructions on the README's 2D scene and 6 % on 3D random
  // 3-contact tries (callgrind), so they are forced inline.
  [[gnu::always_inline]] inline bool inside(const Vec3& c, double r) const;
  bool accept(const Vec3& c, double r, std::int64_t after = -1);
  [[gnu::always_inline]] inline Partner partner(std::int64_t code) const;
  double wall_distance(int wall, const Vec3& c) const;

 private:
  void place(const Vec3& c, double r);

  const bed::Domain& domain_;
  const PackOptions& o_;
  bed::Rng rng_;
  Particles& p_;
  CellGrid& partners_;
  Backend& backend_;
  int dim_;
  double r_max_, r_min_;
  double volume_ = 0;
  PackResult result_;
  std::function<void(std::uint32_t)> on_placed_;
};

// Whether a particle of radius r fits the domain at all (its diameter within every length).
template <class Backend>
bool PlacementCore<Backend>::size_fits(double r) const {
  for (int a = 0; a < dim_; ++a) {
    if (2 * r > domain_.length(a) * (1 + kInsideTolerance)) return false;
  }
  return true;
}

template <class Backend>
bool PlacementCore<Backend>::inside(const Vec3& c, double r) const {
  const double v[3] = {c.x, c.y, c.z};
  for (int a = 0; a < dim_; ++a) {
    const double tol = kInsideTolerance * (r + std::abs(v[a]));
    if (!(v[a] - r >= domain_.lower[a] - tol && v[a] + r <= domain_.upper[a] + tol)) return false;
  }
  return true;
}

// Places a particle of radius r at c when it is inside and fits; `after`: the particles
// 0..after are known not to overlap c (Backend::fits).
template <class Backend>
bool PlacementCore<Backend>::accept(const Vec3& c, double r, std::int64_t after) {
  ++result_.attempts;
  if (!inside(c, r)) return false;
  const bool ok = backend_.fits(c.x, c.y, c.z, r, after);
  if constexpr (Backend::approximate) {
    const bool exact = partners_.fits(c.x, c.y, c.z, r);
    result_.refused_valid += !ok && exact;
    result_.accepted_overlapping += ok && !exact;
  }
  if (ok) place(c, r);
  return ok;
}

// The partner of a code (wall_code); wall normals point into the domain.
template <class Backend>
Partner PlacementCore<Backend>::partner(std::int64_t code) const {
  if (code >= 0) {
    const auto j = static_cast<std::size_t>(code);
    return Partner::particle({p_.x[j], p_.y[j], p_.z[j]}, p_.r[j]);
  }
  const int wall = static_cast<int>(-1 - code), axis = wall / 2;
  Vec3 n;
  (axis == 0 ? n.x : axis == 1 ? n.y : n.z) = wall % 2 == 0 ? 1.0 : -1.0;
  return Partner::plane(n, wall % 2 == 0 ? domain_.lower[axis] : -domain_.upper[axis]);
}

template <class Backend>
double PlacementCore<Backend>::wall_distance(int wall, const Vec3& c) const {
  const int axis = wall / 2;
  const double v = axis == 0 ? c.x : axis == 1 ? c.y : c.z;
  return wall % 2 == 0 ? v - domain_.lower[axis] : domain_.upper[axis] - v;
}

template <class Backend>
void PlacementCore<Backend>::place(const Vec3& c, double r) {
  constexpr double kPi = std::numbers::pi;
  const std::uint32_t i = p_.size();
  p_.x.push_back(c.x);
  p_.y.push_back(c.y);
  p_.z.push_back(dim_ == 3 ? c.z : 0.0);
  p_.r.push_back(r);
  partners_.insert(i);
  backend_.insert(i);
  volume_ += dim_ == 3 ? bed::sphere_volume(r) : kPi * r * r;
  if (on_placed_) on_placed_(i);
}

}  // namespace powderbed::packgen::detail
