#pragma once
// Lowest-site growth (docs/physics.md §3 3-contact, "lowest site first"; site_heap.hpp: after
// Bennett 1972 and Visscher & Bolsterli 1972): every particle placed adds the free 3-contact
// sites of its partner pairs to a queue ordered by height (find_sites, the on-placed hook), and
// a drawn size fills the lowest site that takes it, or is dropped onto the floor while the floor
// has room. O(N), and denser than random 3-contact tries.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <tuple>
#include <vector>

#include "placement_core.hpp"
#include "powderbed/bed/random.hpp"
#include "powderbed/packgen/contact_geometry.hpp"
#include "powderbed/packgen/site_heap.hpp"

namespace powderbed::packgen::detail {

// With a PSD, a site refused for the drawn size but free for the smallest size is put back at
// most this many times (each re-evaluation costs one fit test, so a site costs O(1) over the
// run; a hole that only the smallest ~7 % of a PSD fit is found by one of 32 draws with
// probability ~0.9).
constexpr std::uint8_t kSiteRetries = 32;

// Sites of a new particle come from pairs of its partners in reach; with a wide PSD a small
// particle can have hundreds in reach of the largest size, so only the kSitePartners with the
// smallest gaps are paired (O(N) for any PSD). A monodisperse bed has ~19 partners in reach on
// average (measured), so the cap rarely bites there; sites lost are those bridging distant
// partners, which only the largest sizes could take.
constexpr std::size_t kSitePartners = 32;

// A partner's circle of sites is tested for being covered by one neighbour (circle_covered)
// against the kCoverTests nearest neighbours only: a circle is covered, if at all, mostly by a
// contact of the new particle, and these come first (callgrind, 1e4 monodisperse spheres:
// testing 2 / 3 / 4 / 8 / all neighbours cost 5.4 / 5.1 / 5.1 / 5.2 / 5.5e4 instructions per
// sphere in the whole placement). Testing fewer only skips fewer triples, so the sites found
// are the same for any value.
constexpr std::size_t kCoverTests = 4;

// Slab width of the site queue (site_heap.hpp) in units of the smallest radius, and the most
// slabs a tall domain gets. The queue's order, and so the bed, is the same for any width; 1e6
// monodisperse spheres on a loaded 2-core machine (user CPU, 2 runs each): 2 r 12.1 / 13.7 s,
// r / 2 14.1 / 11.7 s, r / 8 12.3 / 11.6 s, r / 32 11.4 / 10.7 s.
constexpr double kSiteSlab = 1.0 / 32;
constexpr std::size_t kMaxSiteSlabs = std::size_t{1} << 20;

template <class Backend>
class LowestSiteGrowth {
 public:
  explicit LowestSiteGrowth(PlacementCore<Backend>& core)
      : core_(core),
        o_(core.options()),
        radii_{core.r_min(), core.r_max()},
        sizes_(core.r_max() > core.r_min() ? 2 : 1),
        sites_(core.domain().lower[2], core.domain().upper[2],
               std::max(kSiteSlab * core.r_min(),
                        core.domain().length(2) / double(kMaxSiteSlabs))) {}

  // The on-placed hook: the free sites of the new particle i join the queue.
  void placed(std::uint32_t i) { find_sites(i); }

  // Places a particle of the drawn radius r at the lowest site that takes it, else on the floor.
  bool try_size(double r);

 private:
  static constexpr double kPi = std::numbers::pi;

  // find_sites' new particle i, passed to its steps: its centre and radius, itself as a partner
  // at the origin (the geometry is relative to c_i), how many of its partners are paired, and
  // per size the box the new centre must lie in, relative to c_i (inside() widened to its
  // largest tolerance over the domain, so it never refuses what inside() accepts).
  struct NewParticle {
    std::uint32_t i = 0;
    Vec3 c;
    double r = 0;
    Partner origin;
    std::size_t paired = 0;
    std::array<std::array<double, 6>, 2> box{};
  };
  // A partner of the new particle relative to c_i, its gap and code (wall_code).
  struct SiteNear {
    Partner partner;
    double gap = 0;
    std::int64_t code = 0;
  };
  struct LivePartner {  // a partner with an open circle: centre and reach (< 0: a wall)
    Vec3 centre;
    double reach = 0;
    std::size_t index = 0;  // into near_site_
  };

  enum class SiteOutcome { placed, refused, covered };
  SiteOutcome try_site(Site s, double r);
  bool floor_sweep(double r);
  bool try_floor(double r);
  // find_sites and its steps, in order.
  void find_sites(std::uint32_t i);
  void gather_site_partners(const NewParticle& n);
  void load_free_test();
  void prepare_sizes(NewParticle& n);
  void collect_live(const NewParticle& n);
  bool live_in_reach(const LivePartner& pu, const LivePartner& pv) const;
  void pair_sites(const NewParticle& n, const LivePartner& pu, const LivePartner& pv);
  static bool in_box(const Vec3& x, const std::array<double, 6>& b) {
    return x.x >= b[0] && x.x <= b[1] && x.y >= b[2] && x.y <= b[3] && x.z >= b[4] && x.z <= b[5];
  }
  bool circle_covered(const PairPlane& plane, double rho, double r) const;
  bool free_locally(const Vec3& c, double r);

  PlacementCore<Backend>& core_;
  const PackOptions& o_;
  const double radii_[2];  // the sizes sites are found for: the smallest and the largest
  const int sizes_;        // 1 for a monodisperse PSD
  SiteHeap sites_;
  std::vector<Site> retry_;
  double floor_covered_ = 0;  // area of the particles dropped onto the floor
  // The smallest radius for which a whole sweep of n_T floor drops failed (floor_sweep); sizes
  // from it up skip the floor from then on (+inf: the floor is open).
  double floor_closed_from_ = std::numeric_limits<double>::infinity();
  // find_sites scratch for the new particle: its partners (nearest surface first), their pair
  // planes per size, the open circles, the live partners, and the particle partners for the
  // free test (relative to c_i: lx_ .. lr_; absolute: gx_ .. gz_).
  std::vector<SiteNear> near_site_, sorted_site_;
  std::vector<std::tuple<double, std::int64_t, std::size_t>> order_site_;
  std::vector<PairPlane> planes_;
  std::vector<char> open_;  // per size and partner: !circle_covered
  std::vector<LivePartner> live_;
  std::vector<double> lx_, ly_, lz_, lr_;
  std::vector<double> gx_, gy_, gz_;
  std::size_t last_blocker_ = 0;
  // A site's three partners, for touches_all: a member, as a local array made pair_sites' stack
  // frame too large for GCC to inline it into find_sites (1.3 % more instructions, 1e4 spheres).
  Partner abc_[3];
};

// Lowest-site growth for a drawn radius r: pop the lowest sites, re-solve each for r and place
// at the first that fits (up to n_T sites that are still free for the smallest size). Until the
// floor seed is laid, and whenever no site is known or none takes r, r is dropped at a random
// spot onto the floor instead.
template <class Backend>
bool LowestSiteGrowth<Backend>::try_size(double r) {
  const bed::Domain& d = core_.domain();
  if (sites_.empty() || floor_covered_ < o_.floor_seed * d.length(0) * d.length(1)) {
    if (floor_sweep(r)) return true;
  }
  retry_.clear();
  bool placed = false;
  // A covered site is refuse left behind by the growth (each is popped once and dropped), not a
  // try of r: counting it, a size failed when n_T covered sites lay at the bottom of the queue
  // (a full floor layer in a 1e6 mono run: 11 such failures within 20 draws), which made
  // failures, and so the stop rules, depend on the queue's refuse instead of on the bed.
  for (int t = 0; t < o_.tries && !placed && !sites_.empty();) {
    ++core_.result().tries;
    const SiteOutcome k = try_site(sites_.pop(), r);
    placed = k == SiteOutcome::placed;
    t += k != SiteOutcome::covered;
  }
  for (const Site& s : retry_) sites_.push(s);
  if (placed) return true;
  // No known site takes r: a free spot on the floor, if any, is the lowest of all.
  return floor_sweep(r);
}

// One popped site for r: the centre it stores when r is the size it was found for, else
// re-solved for r; put back for a later size when it is free for the smallest (kSiteRetries).
// `covered`: not free even for the smallest size, so it never will be (sites are only covered).
template <class Backend>
typename LowestSiteGrowth<Backend>::SiteOutcome LowestSiteGrowth<Backend>::try_site(Site s,
                                                                                    double r) {
  const double r_min = core_.r_min();
  const bool stored = r == (s.found_for == 0 ? r_min : core_.r_max());
  if (stored) {
    // find_sites tested the stored centre against every particle up to its finder s.a (all
    // that can reach it), so only the particles placed since can cover it now.
    if (core_.accept({s.x, s.y, s.key}, r, s.a)) return SiteOutcome::placed;
    if (r == r_min) return SiteOutcome::covered;
  }
  const Partner a = core_.partner(s.a), b = core_.partner(s.b), c = core_.partner(s.c);
  Vec3 x;
  if (!stored && site_centre(a, b, c, r, s.side, x) && core_.accept(x, r)) {
    return SiteOutcome::placed;
  }
  if (!(r > r_min)) return SiteOutcome::covered;
  if (s.retries >= kSiteRetries) return SiteOutcome::refused;  // free or not: dropped
  if (!(site_centre(a, b, c, r_min, s.side, x) && core_.inside(x, r_min) &&
        core_.backend().fits(x.x, x.y, x.z, r_min))) {
    return SiteOutcome::covered;
  }
  ++s.retries;
  retry_.push_back(s);
  return SiteOutcome::refused;
}

// Up to n_T random drops of r onto the floor. Once a sweep fails for r, the floor is closed to
// r and every larger size for the rest of the run: n_T failed uniform drops bound the free
// fraction of the floor (for that size) below 3 / n_T at 95 % confidence, and the floor only
// fills up. Without this, every failed size of a full bed paid n_T floor attempts, most of a
// default run's attempts (GenGeo scene, docs/results/packgen-speed.md: 1.2 of 1.6 M). Below
// kMinSweep drops a failed sweep bounds nothing worth closing on (n_T = 10: a third of the
// floor could still be free), so small --tries keep the floor open.
template <class Backend>
bool LowestSiteGrowth<Backend>::floor_sweep(double r) {
  constexpr int kMinSweep = 100;  // 3 / n_T <= 3 % of the floor
  if (r >= floor_closed_from_) return false;
  for (int t = 0; t < o_.tries; ++t) {
    if (try_floor(r)) return true;
  }
  if (o_.tries >= kMinSweep) floor_closed_from_ = r;
  return false;
}

template <class Backend>
bool LowestSiteGrowth<Backend>::try_floor(double r) {
  ++core_.result().tries;
  const bed::Domain& d = core_.domain();
  bed::Rng& rng = core_.rng();
  const Vec3 c{bed::uniform(rng, d.lower[0] + r, d.upper[0] - r),
               bed::uniform(rng, d.lower[1] + r, d.upper[1] - r), d.lower[2] + r};
  if (!core_.accept(c, r)) return false;
  floor_covered_ += kPi * r * r;
  return true;
}

// The free sites of a new particle i: every pair (q1, q2) of its partners in reach of each
// other, both mirror solutions of the trilateration (docs/physics.md §3 3-contact). A site is
// kept when it is inside and free for the smallest size, or failing that the largest. Any
// particle overlapping a centre at r_i + r from i lies within r_i + r_j + 2 r of i, i.e. in the
// partner list, so the filter is exact without the grid; sites are only ever covered later,
// never freed, and are checked again when popped (against the particles placed since only).
// Hot loop (1e5 monodisperse spheres, per particle: 19 partners, 12 with an open circle, 50
// triples trilaterated, 90 points tested free, 7 sites): the geometry is relative to c_i, each
// partner's pair plane (i, q) is computed once per size and shared by all its triples, pairs
// are formed among the partners whose circle of sites no single neighbour covers
// (circle_covered) and in reach of each other before any trilateration, and the partners are
// sorted by gap so the free test meets the likeliest blocker (a contact of i) first.
template <class Backend>
void LowestSiteGrowth<Backend>::find_sites(std::uint32_t i) {
  const Particles& p = core_.particles();
  NewParticle n{i, {p.x[i], p.y[i], p.z[i]}, p.r[i], Partner::particle({0, 0, 0}, p.r[i])};
  abc_[0] = n.origin;
  gather_site_partners(n);
  load_free_test();
  n.paired = std::min(near_site_.size(), kSitePartners);
  prepare_sizes(n);
  collect_live(n);
  for (std::size_t lu = 0; lu < live_.size(); ++lu) {
    for (std::size_t lv = lu + 1; lv < live_.size(); ++lv) {
      if (live_in_reach(live_[lu], live_[lv])) pair_sites(n, live_[lu], live_[lv]);
    }
  }
}

// The partners of the new particle (docs/physics.md §3 2-contact reach for the largest size),
// relative to c_i, with their gaps; sorted by gap through a light (gap, code, index) key.
template <class Backend>
void LowestSiteGrowth<Backend>::gather_site_partners(const NewParticle& n) {
  const Particles& p = core_.particles();
  const Vec3 ci = n.c;
  const double ri = n.r, r_max = core_.r_max();
  near_site_.clear();
  core_.partners().for_each_within(ci.x, ci.y, ci.z, ri + 2 * r_max, [&](std::uint32_t j) {
    if (j == n.i) return false;
    const Vec3 d{p.x[j] - ci.x, p.y[j] - ci.y, p.z[j] - ci.z};
    near_site_.push_back({Partner::particle(d, p.r[j]), norm(d) - ri - p.r[j], j});
    return false;
  });
  for (int wall = 0; wall < 6; ++wall) {
    const double gap = core_.wall_distance(wall, ci) - ri;
    if (gap > 2 * r_max) continue;
    const Partner w = core_.partner(wall_code(wall));
    near_site_.push_back(
        {Partner::plane(w.normal, w.offset - dot(w.normal, ci)), gap, wall_code(wall)});
  }
  order_site_.clear();
  for (std::size_t k = 0; k < near_site_.size(); ++k) {
    order_site_.push_back({near_site_[k].gap, near_site_[k].code, k});
  }
  std::sort(order_site_.begin(), order_site_.end());
  sorted_site_.clear();
  for (const auto& key : order_site_) sorted_site_.push_back(near_site_[std::get<2>(key)]);
  near_site_.swap(sorted_site_);
}

// The free test (free_locally, circle_covered) sees every particle partner, nearest first:
// their centres relative to c_i and absolute, and their radii.
template <class Backend>
void LowestSiteGrowth<Backend>::load_free_test() {
  const Particles& p = core_.particles();
  const std::size_t nf = static_cast<std::size_t>(
      std::count_if(near_site_.begin(), near_site_.end(),
                    [](const SiteNear& t) { return !t.partner.is_plane; }));
  for (auto* v : {&lx_, &ly_, &lz_, &lr_, &gx_, &gy_, &gz_}) v->resize(nf);
  std::size_t f = 0;
  for (const SiteNear& t : near_site_) {
    if (t.partner.is_plane) continue;
    lx_[f] = t.partner.centre.x;
    ly_[f] = t.partner.centre.y;
    lz_[f] = t.partner.centre.z;
    lr_[f] = t.partner.radius;
    const auto j = static_cast<std::size_t>(t.code);
    gx_[f] = p.x[j];
    gy_[f] = p.y[j];
    gz_[f] = p.z[j];
    ++f;
  }
}

// Per size: the pair plane of each paired partner (only the kSitePartners nearest are paired)
// and whether its circle of sites is open, and the box the new centre must lie in.
template <class Backend>
void LowestSiteGrowth<Backend>::prepare_sizes(NewParticle& n) {
  const std::size_t m = n.paired;
  planes_.resize(2 * m);
  open_.resize(2 * m);
  const bed::Domain& d = core_.domain();
  for (int k = 0; k < sizes_; ++k) {
    const double r = radii_[k];
    const auto row = static_cast<std::size_t>(k) * m;
    for (std::size_t u = 0; u < m; ++u) {
      planes_[row + u] = pair_plane(n.origin, near_site_[u].partner, r);
      open_[row + u] = !circle_covered(planes_[row + u], n.r + r, r);
    }
    const double c[3] = {n.c.x, n.c.y, n.c.z};
    for (int a = 0; a < 3; ++a) {
      const double tol =
          kInsideTolerance * (r + std::max(std::abs(d.lower[a]), std::abs(d.upper[a])));
      n.box[k][2 * a] = d.lower[a] + r - tol - c[a];
      n.box[k][2 * a + 1] = d.upper[a] - r + tol - c[a];
    }
  }
}

// Only partners with an open circle for some size can give a site; they keep the order of all
// partners, so the pairs, and so the sites and their tie draws, come in the same order.
template <class Backend>
void LowestSiteGrowth<Backend>::collect_live(const NewParticle& n) {
  const std::size_t m = n.paired;
  live_.clear();
  for (std::size_t u = 0; u < m; ++u) {
    if (open_[u] || (sizes_ == 2 && open_[m + u])) {
      const Partner& q = near_site_[u].partner;
      live_.push_back({q.centre, q.is_plane ? -1.0 : q.radius + core_.r_max(), u});
    }
  }
}

// in_reach for the largest size; for two particle partners with their reaches cached, as the
// sum (r_u + r_max) + (r_v + r_max).
template <class Backend>
bool LowestSiteGrowth<Backend>::live_in_reach(const LivePartner& pu,
                                              const LivePartner& pv) const {
  if (pu.reach < 0 || pv.reach < 0) {
    return in_reach(near_site_[pu.index].partner, near_site_[pv.index].partner, core_.r_max());
  }
  const Vec3 d = pv.centre - pu.centre;
  const double s = pu.reach + pv.reach;
  return dot(d, d) <= s * s;
}

// The sites of the new particle with partners u and v: per size the two trilaterated points
// (y[0] on the +u side, y[1] on the -u side), each side kept for the first size it is free for.
template <class Backend>
void LowestSiteGrowth<Backend>::pair_sites(const NewParticle& n, const LivePartner& pu,
                                           const LivePartner& pv) {
  const SiteNear& su = near_site_[pu.index];
  const SiteNear& sv = near_site_[pv.index];
  bool found[2] = {false, false};
  for (int k = 0; k < sizes_; ++k) {
    const double r = radii_[k];
    const auto row = static_cast<std::size_t>(k) * n.paired;
    const std::size_t u = row + pu.index, v = row + pv.index;
    if (!open_[u] || !open_[v]) continue;
    std::array<Vec3, 2> y;
    if (trilaterate(planes_[u], planes_[v], n.r + r, y) == 0) continue;
    for (std::size_t side = 0; side < 2; ++side) {
      const Vec3& x = y[side];
      if (found[side] || !in_box(x, n.box[k])) continue;
      const Vec3 c = n.c + x;  // the centre the site stores
      if (!free_locally(c, r)) continue;
      abc_[1] = su.partner;
      abc_[2] = sv.partner;
      if (!touches_all(abc_, 3, x, r)) continue;
      found[side] = true;
      ++core_.result().sites;
      sites_.push({c.z, c.x, c.y, static_cast<std::uint32_t>(core_.rng()() >> 32),
                   static_cast<std::int32_t>(n.i), static_cast<std::int32_t>(su.code),
                   static_cast<std::int32_t>(sv.code), static_cast<std::uint8_t>(side), 0,
                   static_cast<std::uint8_t>(k)});
    }
  }
}

// Whether the circle of centres touching i (at the origin, rho = r_i + r) and one partner
// (its pair plane) lies wholly inside one neighbour's exclusion sphere |y - c_w| < r_w + r:
// then every trilateration on it gives a blocked point and the partner's triples are skipped
// (find_sites). A trilaterated point lies in the pair plane within a + sqrt(kClampTolerance) rho
// of the circle's centre o (a: the circle's radius; near-tangent solutions are clamped), so the
// disc of that radius is tested: its farthest point from c_w is at distance^2
// |c_w - o|^2 + 2 a q + a^2, q the distance of c_w from the plane's normal through o. Covered
// when that is below (r_w + r)^2 (1 - kCoverMargin): the margin keeps the skip exact, as a point
// computed with ~1e-15 rounding is then still refused by the 1e-12 overlap test.
template <class Backend>
bool LowestSiteGrowth<Backend>::circle_covered(const PairPlane& plane, double rho,
                                               double r) const {
  constexpr double kCoverMargin = 1e-9;
  const Vec3 o = (plane.e / plane.nn) * plane.n;
  const double a2 = rho * rho - dot(o, o);
  if (!(a2 > 0)) return false;  // a point or no circle: left to trilaterate
  const double a = std::sqrt(a2) + std::sqrt(kClampTolerance) * rho;
  const Vec3 axis = (1.0 / std::sqrt(plane.nn)) * plane.n;
  const std::size_t n = std::min(lr_.size(), kCoverTests);
  for (std::size_t j = 0; j < n; ++j) {
    const Vec3 d{lx_[j] - o.x, ly_[j] - o.y, lz_[j] - o.z};
    const double s2 = (lr_[j] + r) * (lr_[j] + r) * (1 - kCoverMargin);
    const double d2 = dot(d, d);
    if (d2 + a * a >= s2) continue;  // the farthest point is at least this far
    const double h = dot(axis, d);
    const double q = std::sqrt(std::max(d2 - h * h, 0.0));
    if (d2 + 2 * a * q + a * a < s2) return true;
  }
  return false;
}

// Whether the centre c (absolute, as the site stores it) overlaps none of the particle partners
// of find_sites' particle i. The test is the collision back-ends' own, on the same absolute
// differences, so a site stored as free is free to them too for every particle up to i, and
// try_site tests only the particles placed since (beds touch at the tolerance: in a 1e4 run
// stored centres within rounding of the 1e-12 overlap bound appeared after ~3000 spheres, and
// there a test relative to c_i answered otherwise). The candidates of one particle are mostly
// blocked by the same few neighbours (its contacts), so the neighbour that blocked the previous
// candidate is tested first; the rest go nearest surface first. The partners c was solved to
// touch pass the overlap test (they touch to ~1e-15, the test allows 1e-12), so they need no
// special case.
template <class Backend>
bool LowestSiteGrowth<Backend>::free_locally(const Vec3& c, double r) {
  const std::size_t n = lr_.size();
  const auto blocks = [&](std::size_t j) {
    return overlaps(gx_[j] - c.x, gy_[j] - c.y, gz_[j] - c.z, lr_[j] + r);
  };
  if (last_blocker_ < n && blocks(last_blocker_)) return false;
  for (std::size_t j = 0; j < n; ++j) {
    if (blocks(j)) {
      last_blocker_ = j;
      return false;
    }
  }
  return true;
}

}  // namespace powderbed::packgen::detail
