#pragma once
// The 0/1/2/3-contact approaches of docs/physics.md §3 ([LP], extended to 3D): a try picks a
// particle s from the partner list and places the new particle touching s (1 contact), s and a
// partner in reach (2), or s and two partners in reach of s and of each other (3); 0-contact
// draws the centre at random. The partner list advances with the front: a particle is dropped
// from it after o.retire_after failed tries in a row around it (O(N) packing).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include "placement_core.hpp"
#include "powderbed/bed/random.hpp"
#include "powderbed/packgen/contact_geometry.hpp"

namespace powderbed::packgen::detail {

template <class Backend>
class ContactApproaches {
 public:
  explicit ContactApproaches(PlacementCore<Backend>& core)
      : core_(core), o_(core.options()), directions_(directions_for(o_, core.dim())) {
    order_.resize(static_cast<std::size_t>(directions_));
    if (o_.count > 0) {  // no regrowth of the per-particle arrays in a --count run
      slot_.reserve(o_.count);
      active_.reserve(o_.count);
      fails_.reserve(o_.count);
    }
  }

  // The on-placed hook: particle i joins the partner list.
  void placed(std::uint32_t i) {
    slot_.push_back(static_cast<std::uint32_t>(active_.size()));
    active_.push_back(i);
    fails_.push_back(0);
  }

  // A partner-based approach with every particle retired has nowhere left to try.
  bool exhausted(int approach) const {
    return approach > 0 && core_.particles().size() > 0 && active_.empty();
  }

  bool try_once(int approach, double r);

 private:
  static constexpr double kPi = std::numbers::pi;

  Vec3 centre(std::uint32_t s) const {
    const Particles& p = core_.particles();
    return {p.x[s], p.y[s], p.z[s]};
  }

  void retire(std::uint32_t s);
  void shuffle_order();
  void gather_partners(std::uint32_t s, double r);
  bool try_random(double r);
  bool try_one(std::uint32_t s, double r);
  bool try_two(std::uint32_t s, double r);
  bool touch_two(std::uint32_t s, std::int64_t q, double r);
  bool accept_mirror(const std::array<Vec3, 2>& x, int m, double r);
  bool try_three(std::uint32_t s, double r);

  PlacementCore<Backend>& core_;
  const PackOptions& o_;
  const int directions_;  // K
  // The partner list: active_ holds the particles that may still have free surface, slot_ each
  // one's place in it, fails_ its failed tries in a row.
  std::vector<std::uint32_t> active_, slot_;
  std::vector<int> fails_;
  // Scratch, reused so the hot loop does not allocate: partner codes (wall_code) and a shuffled
  // order of directions.
  std::vector<std::int64_t> near_, near2_;
  std::vector<int> order_;
};

// One try of `approach` for a particle of radius r; the first particle takes 0 contacts.
template <class Backend>
bool ContactApproaches<Backend>::try_once(int approach, double r) {
  ++core_.result().tries;
  if (approach == 0 || core_.particles().size() == 0) return try_random(r);
  const std::uint32_t s = active_[bed::uniform_index(core_.rng(), active_.size())];
  const bool ok =
      approach == 1 ? try_one(s, r) : approach == 2 ? try_two(s, r) : try_three(s, r);
  if (ok) {
    fails_[s] = 0;
  } else if (o_.retire_after > 0 && ++fails_[s] >= o_.retire_after) {
    retire(s);
  }
  return ok;
}

template <class Backend>
void ContactApproaches<Backend>::retire(std::uint32_t s) {
  const std::uint32_t at = slot_[s], last = active_.back();
  active_[at] = last;
  slot_[last] = at;
  active_.pop_back();
  ++core_.result().retired;
}

// Fisher–Yates over 0..K-1 (docs/physics.md §3: "evenly spaced angles shuffled").
template <class Backend>
void ContactApproaches<Backend>::shuffle_order() {
  for (std::size_t k = 0; k < order_.size(); ++k) order_[k] = static_cast<int>(k);
  for (std::size_t k = order_.size(); k > 1; --k) {
    std::swap(order_[k - 1], order_[bed::uniform_index(core_.rng(), k)]);
  }
}

// Partners of s for a new particle of radius r: particles with centre distance
// <= r_s + r_j + 2r (docs/physics.md §3 2-contact) and walls within r_s + 2r, found through
// the exact grid.
template <class Backend>
void ContactApproaches<Backend>::gather_partners(std::uint32_t s, double r) {
  near_.clear();
  const Vec3 c = centre(s);
  const double reach = core_.particles().r[s] + 2 * r;
  core_.partners().for_each_within(c.x, c.y, c.z, reach, [&](std::uint32_t j) {
    if (j != s) near_.push_back(j);
    return false;
  });
  for (int wall = 0; wall < 2 * core_.dim(); ++wall) {
    if (core_.wall_distance(wall, c) <= reach) near_.push_back(wall_code(wall));
  }
}

// 0-contact: centre uniform in the domain inset by r; with probability edge_fraction one axis
// is redrawn within one largest diameter of a random wall ([LP] extra boundary sampling).
template <class Backend>
bool ContactApproaches<Backend>::try_random(double r) {
  const bed::Domain& d = core_.domain();
  bed::Rng& rng = core_.rng();
  const int dim = core_.dim();
  double v[3] = {0, 0, 0};
  for (int a = 0; a < dim; ++a) v[a] = bed::uniform(rng, d.lower[a] + r, d.upper[a] - r);
  if (o_.edge_fraction > 0 && bed::uniform01(rng) < o_.edge_fraction) {
    const auto walls = static_cast<std::uint64_t>(2 * dim);
    const auto wall = static_cast<int>(bed::uniform_index(rng, walls));
    const int axis = wall / 2;
    const double lo = d.lower[axis] + r, hi = d.upper[axis] - r;
    const double band = 2 * core_.r_max();
    v[axis] = wall % 2 == 0 ? bed::uniform(rng, lo, std::min(lo + band, hi))
                            : bed::uniform(rng, std::max(hi - band, lo), hi);
  }
  return core_.accept({v[0], v[1], v[2]}, r);
}

// 1-contact: on the circle/sphere of radius r_s + r around s; 2D: K evenly spaced angles with
// a random offset in shuffled order; 3D: K uniform directions on the sphere.
template <class Backend>
bool ContactApproaches<Backend>::try_one(std::uint32_t s, double r) {
  const Vec3 c = centre(s);
  const double rho = core_.particles().r[s] + r;
  const int k_max = directions_;
  bed::Rng& rng = core_.rng();
  if (core_.dim() == 2) {
    const double step = 2 * kPi / k_max;
    const double offset = bed::uniform(rng, 0, step);
    shuffle_order();
    for (int k = 0; k < k_max; ++k) {
      const double angle = offset + step * order_[static_cast<std::size_t>(k)];
      if (core_.accept({c.x + rho * std::cos(angle), c.y + rho * std::sin(angle), 0}, r)) {
        return true;
      }
    }
    return false;
  }
  for (int k = 0; k < k_max; ++k) {
    const double cz = bed::uniform(rng, -1, 1), phi = bed::uniform(rng, 0, 2 * kPi);
    const double sz = std::sqrt(std::max(0.0, 1 - cz * cz));
    const Vec3 x{c.x + rho * sz * std::cos(phi), c.y + rho * sz * std::sin(phi), c.z + rho * cz};
    if (core_.accept(x, r)) return true;
  }
  return false;
}

// 2-contact: touch s and a partner (particle or wall) chosen uniformly among those in reach.
// With no partner in reach, s is tried with 1 contact (an approach uses at most its contacts).
template <class Backend>
bool ContactApproaches<Backend>::try_two(std::uint32_t s, double r) {
  gather_partners(s, r);
  if (near_.empty()) return try_one(s, r);
  return touch_two(s, near_[bed::uniform_index(core_.rng(), near_.size())], r);
}

template <class Backend>
bool ContactApproaches<Backend>::touch_two(std::uint32_t s, std::int64_t q, double r) {
  const Partner a = core_.partner(s), b = core_.partner(q);
  if (core_.dim() == 2) {
    std::array<Vec3, 2> x;
    return accept_mirror(x, touch_two_2d(a, b, r, x), r);
  }
  Circle circle;
  if (!touch_two_3d(a, b, r, circle)) return false;
  const double step = 2 * kPi / directions_;
  const double offset = bed::uniform(core_.rng(), 0, step);
  shuffle_order();
  for (int k = 0; k < directions_; ++k) {
    if (core_.accept(circle.at(offset + step * order_[static_cast<std::size_t>(k)]), r)) {
      return true;
    }
  }
  return false;
}

// The (up to) two solutions of a closed form, in random order.
template <class Backend>
bool ContactApproaches<Backend>::accept_mirror(const std::array<Vec3, 2>& x, int m, double r) {
  const std::size_t first = m == 2 ? bed::uniform_index(core_.rng(), 2) : 0;
  for (int k = 0; k < m; ++k) {
    if (core_.accept(x[(first + static_cast<std::size_t>(k)) % 2], r)) return true;
  }
  return false;
}

// 3-contact (3D): touch s and two partners in reach of s and of each other (in_reach); two
// mirror points. With fewer partners in reach it falls back to 2 and then 1 contact.
template <class Backend>
bool ContactApproaches<Backend>::try_three(std::uint32_t s, double r) {
  gather_partners(s, r);
  if (near_.empty()) return try_one(s, r);
  const std::int64_t q1 = near_[bed::uniform_index(core_.rng(), near_.size())];
  const Partner p1 = core_.partner(q1);
  near2_.clear();
  for (const std::int64_t q : near_) {
    if (q != q1 && in_reach(p1, core_.partner(q), r)) near2_.push_back(q);
  }
  if (near2_.empty()) return touch_two(s, q1, r);
  const std::int64_t q2 = near2_[bed::uniform_index(core_.rng(), near2_.size())];
  std::array<Vec3, 2> x;
  const int m = touch_three_3d(core_.partner(s), p1, core_.partner(q2), r, x);
  return accept_mirror(x, m, r);
}

}  // namespace powderbed::packgen::detail
