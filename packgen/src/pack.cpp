// The placement loop of docs/physics.md §3: sizes from the PSD, n_T tries per size, 0/1/2/3-contact
// candidates, one collision back-end. The loop is a template over the back-end, dispatched
// once in pack(), so no test in the hot loop goes through a virtual call.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include "powderbed/packgen/cell_grid.hpp"
#include "powderbed/packgen/contact_geometry.hpp"
#include "powderbed/packgen/kdtree_index.hpp"
#include "powderbed/packgen/pack.hpp"
#include "powderbed/packgen/raster_grid.hpp"
#include "powderbed/packgen/site_heap.hpp"

namespace powderbed::packgen {

namespace {

using bed::Rng;
using bed::uniform;
using bed::uniform01;
using bed::uniform_index;
constexpr double kPi = std::numbers::pi;

// Lowest-site growth with a PSD: a site refused for the drawn size but free for the smallest
// size is put back at most this many times (each re-evaluation costs one fit test, so a site
// costs O(1) over the run; a hole that only the smallest ~7 % of a PSD fit is found by
// one of 32 draws with probability ~0.9).
constexpr std::uint8_t kSiteRetries = 32;

// Lowest-site growth: sites of a new particle come from pairs of its partners in reach; with a
// wide PSD a small particle can have hundreds in reach of the largest size, so only the
// kSitePartners with the smallest gaps are paired (O(N) for any PSD). A monodisperse bed has
// ~19 partners in reach on average (measured), so the cap rarely bites there; sites lost are
// those bridging distant partners, which only the largest sizes could take.
constexpr std::size_t kSitePartners = 32;

// Lowest-site growth: a partner's circle of sites is tested for being covered by one
// neighbour (circle_covered) against the kCoverTests nearest neighbours only: a circle is
// covered, if at all, mostly by a contact of the new particle, and these come first
// (callgrind, 1e4 monodisperse spheres: testing 2 / 3 / 4 / 8 / all neighbours cost 5.4 / 5.1 /
// 5.1 / 5.2 / 5.5e4 instructions per sphere in the whole placement). Testing fewer only skips
// fewer triples, so the sites found are the same for any value.
constexpr std::size_t kCoverTests = 4;

// Lowest-site growth: slab width of the site queue (site_heap.hpp) in units of the smallest
// radius, and the most slabs a tall domain gets. The queue's order, and so the bed, is the same
// for any width; 1e6 monodisperse spheres on a loaded 2-core machine (user CPU, 2 runs each):
// 2 r 12.1 / 13.7 s, r / 2 14.1 / 11.7 s, r / 8 12.3 / 11.6 s, r / 32 11.4 / 10.7 s.
constexpr double kSiteSlab = 1.0 / 32;
constexpr std::size_t kMaxSiteSlabs = std::size_t{1} << 20;

// Containment tolerance (docs/physics.md §3 "every particle lies fully inside"): 1e-12 relative to the
// radius and the coordinate, so centres computed to touch a wall are not refused for rounding.
constexpr double kInsideTolerance = 1e-12;

inline double component(const Vec3& c, int axis) {
  return axis == 0 ? c.x : axis == 1 ? c.y : c.z;
}

// Whether a new particle of radius r can touch both partners at once (partners relative to
// any common origin): particles within r_a + r_b + 2r, a particle within r_a + 2r of a wall,
// walls on different axes (axis-aligned normals: dot 0).
inline bool in_reach(const Partner& a, const Partner& b, double r) {
  if (a.is_plane && b.is_plane) return dot(a.normal, b.normal) == 0;
  if (a.is_plane || b.is_plane) {
    const Partner& w = a.is_plane ? a : b;
    const Partner& q = a.is_plane ? b : a;
    return dot(w.normal, q.centre) - w.offset <= q.radius + 2 * r;
  }
  const Vec3 d = b.centre - a.centre;
  const double s = a.radius + b.radius + 2 * r;
  return dot(d, d) <= s * s;
}

// The back-ends behind one small interface: insert(i), fits(x, y, z, r, after), `approximate`.
// `after`: the exact back-ends test only particles with a larger index (-1: all), the raster
// tests its whole status grid (its answer is not the exact one the skipped particles passed).
struct GridBackend {  // the exact partner grid doubles as the collision grid
  static constexpr bool approximate = false;
  const CellGrid& grid;
  void insert(std::uint32_t) {}
  bool fits(double x, double y, double z, double r, std::int64_t after = -1) const {
    return grid.fits(x, y, z, r, after);
  }
};
struct KdTreeBackend {
  static constexpr bool approximate = false;
  KdTreeIndex index;
  void insert(std::uint32_t i) { index.insert(i); }
  bool fits(double x, double y, double z, double r, std::int64_t after = -1) const {
    return index.fits(x, y, z, r, after);
  }
};
struct RasterBackend {
  static constexpr bool approximate = true;
  RasterGrid raster;
  void insert(std::uint32_t i) { raster.insert(i); }
  bool fits(double x, double y, double z, double r, std::int64_t = -1) const {
    return raster.fits(x, y, z, r);
  }
};

template <class Backend>
class Packer {
 public:
  Packer(const bed::Domain& domain, const bed::Psd& psd, const PackOptions& options,
         std::uint64_t seed, Particles& particles, CellGrid& partners, Backend& backend)
      : domain_(domain),
        o_(options),
        rng_(seed),
        p_(particles),
        partners_(partners),
        backend_(backend),
        dim_(domain.dimension),
        r_max_(psd.max_radius()),
        r_min_(psd.min_radius()),
        sizes_(psd, options.size_sampling, rng_),
        sites_(domain.lower[2], domain.upper[2],
               std::max(kSiteSlab * r_min_, domain.length(2) / double(kMaxSiteSlabs))) {
    order_.resize(static_cast<std::size_t>(o_.directions));
    if (o_.count > 0) {  // no regrowth of the per-particle arrays in a --count run
      for (auto* v : {&p_.x, &p_.y, &p_.z, &p_.r}) v->reserve(o_.count);
      slot_.reserve(o_.count);
      active_.reserve(o_.count);
      fails_.reserve(o_.count);
    }
    for (const Phase& ph : o_.phases) {
      lowest_ = lowest_ || (dim_ == 3 && ph.approach == 3 && o_.site_order == SiteOrder::lowest);
    }
  }

  PackResult run();

 private:
  double density() const { return volume_ / domain_.measure(); }
  bool exhausted(int approach) const { return approach > 0 && p_.size() > 0 && active_.empty(); }
  bool size_fits(double r) const;
  bool inside(const Vec3& c, double r) const;
  bool accept(const Vec3& c, double r, std::int64_t after = -1);
  void place(const Vec3& c, double r);
  void retire(std::uint32_t s);
  void shuffle_order();
  Partner partner(std::int64_t code) const;
  double wall_distance(int wall, const Vec3& c) const;
  bool compatible(std::int64_t a, std::int64_t b, double r) const;
  void gather_partners(std::uint32_t s, double r);

  bool try_once(int approach, double r);
  bool try_random(double r);
  bool try_one(std::uint32_t s, double r);
  bool try_two(std::uint32_t s, double r);
  bool try_three(std::uint32_t s, double r);
  bool touch_two(std::uint32_t s, std::int64_t q, double r);
  bool accept_mirror(const std::array<Vec3, 2>& x, int m, double r);
  bool try_lowest(double r);
  bool try_floor(double r);
  bool floor_sweep(double r);
  void find_sites(std::uint32_t i);
  bool free_locally(const Vec3& c, double r);
  bool circle_covered(const PairPlane& plane, double rho, double r) const;

  const bed::Domain& domain_;
  const PackOptions& o_;
  Rng rng_;
  Particles& p_;
  CellGrid& partners_;
  Backend& backend_;
  int dim_;
  double r_max_, r_min_;
  SizeSampler sizes_;
  double volume_ = 0;
  // Lowest-site growth (site_heap.hpp): on when a phase is 3D approach 3 with SiteOrder::lowest.
  bool lowest_ = false;
  SiteHeap sites_;
  std::vector<Site> retry_;
  // find_sites scratch for a new particle i, relative to c_i: its partners (nearest surface
  // first), their pair planes per size, and the particle partners for the free test.
  struct SiteNear {
    Partner partner;
    double gap = 0;
    std::int64_t code = 0;
  };
  std::vector<SiteNear> near_site_, sorted_site_;
  std::vector<std::tuple<double, std::int64_t, std::size_t>> order_site_;
  std::vector<PairPlane> planes_;
  std::vector<char> open_;  // per size and partner: !circle_covered
  struct LivePartner {  // a partner with an open circle: centre and reach (< 0: a wall)
    Vec3 centre;
    double reach = 0;
    std::size_t index = 0;  // into near_site_
  };
  std::vector<LivePartner> live_;
  std::vector<double> lx_, ly_, lz_, lr_;  // relative to c_i
  std::vector<double> gx_, gy_, gz_;       // the same centres, absolute

  std::size_t last_blocker_ = 0;
  double floor_covered_ = 0;               // area of the particles dropped onto the floor
  // Lowest-site growth: the smallest radius for which a whole sweep of n_T floor drops failed
  // (floor_sweep); sizes from it up skip the floor from then on (+inf: the floor is open).
  double floor_closed_from_ = std::numeric_limits<double>::infinity();
  PackResult result_;
  // Front-advancing partner list: active_ holds particles that may still have free surface.
  std::vector<std::uint32_t> active_, slot_;
  std::vector<int> fails_;
  // Scratch, reused so the hot loop does not allocate: partner codes (>= 0 particles,
  // < 0 walls as -1 - wall) and a shuffled order of directions.
  std::vector<std::int64_t> near_, near2_;
  std::vector<int> order_;
};

template <class Backend>
bool Packer<Backend>::size_fits(double r) const {
  for (int a = 0; a < dim_; ++a) {
    if (2 * r > domain_.length(a) * (1 + kInsideTolerance)) return false;
  }
  return true;
}

template <class Backend>
bool Packer<Backend>::inside(const Vec3& c, double r) const {
  const double v[3] = {c.x, c.y, c.z};
  for (int a = 0; a < dim_; ++a) {
    const double tol = kInsideTolerance * (r + std::abs(v[a]));
    if (!(v[a] - r >= domain_.lower[a] - tol && v[a] + r <= domain_.upper[a] + tol)) return false;
  }
  return true;
}

// `after`: the particles 0..after are known not to overlap c (Backend::fits).
template <class Backend>
bool Packer<Backend>::accept(const Vec3& c, double r, std::int64_t after) {
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

template <class Backend>
void Packer<Backend>::place(const Vec3& c, double r) {
  const std::uint32_t i = p_.size();
  p_.x.push_back(c.x);
  p_.y.push_back(c.y);
  p_.z.push_back(dim_ == 3 ? c.z : 0.0);
  p_.r.push_back(r);
  partners_.insert(i);
  backend_.insert(i);
  slot_.push_back(static_cast<std::uint32_t>(active_.size()));
  active_.push_back(i);
  fails_.push_back(0);
  volume_ += dim_ == 3 ? 4.0 / 3.0 * kPi * r * r * r : kPi * r * r;
  if (lowest_) find_sites(i);
}

// The free sites of a new particle i: every pair (q1, q2) of its partners in reach of each
// other, both mirror solutions of the trilateration (docs/physics.md §3 3-contact). A site is kept when
// it is inside and free for the smallest size, or failing that the largest. Any particle
// overlapping a centre at r_i + r from i lies within r_i + r_j + 2 r of i, i.e. in the
// partner list, so the filter is exact without the grid; sites are only ever covered later,
// never freed, and are checked again when popped (against the particles placed since only).
// Hot loop (1e5 monodisperse spheres, per particle: 19 partners, 12 with an open circle, 50
// triples trilaterated, 90 points tested free, 7 sites): the geometry is relative to c_i, each
// partner's pair plane (i, q) is computed once per size and shared by all its triples, pairs
// are formed among the partners whose circle of sites no single neighbour covers
// (circle_covered) and in reach of each other before any trilateration, and the partners are
// sorted by gap so the free test meets the likeliest blocker (a contact of i) first.
template <class Backend>
void Packer<Backend>::find_sites(std::uint32_t i) {
  // Partners (docs/physics.md §3 2-contact reach for the largest size), relative to c_i, with their gaps;
  // sorted by gap through a light (gap, code, index) key.
  const Vec3 ci{p_.x[i], p_.y[i], p_.z[i]};
  const double ri = p_.r[i];
  near_site_.clear();
  partners_.for_each_within(ci.x, ci.y, ci.z, ri + 2 * r_max_, [&](std::uint32_t j) {
    if (j == i) return false;
    const Vec3 d{p_.x[j] - ci.x, p_.y[j] - ci.y, p_.z[j] - ci.z};
    near_site_.push_back({Partner::particle(d, p_.r[j]), norm(d) - ri - p_.r[j], j});
    return false;
  });
  for (int wall = 0; wall < 6; ++wall) {
    const double gap = wall_distance(wall, ci) - ri;
    if (gap > 2 * r_max_) continue;
    const Partner w = partner(-1 - wall);
    near_site_.push_back({Partner::plane(w.normal, w.offset - dot(w.normal, ci)), gap, -1 - wall});
  }
  order_site_.clear();
  for (std::size_t k = 0; k < near_site_.size(); ++k) {
    order_site_.push_back({near_site_[k].gap, near_site_[k].code, k});
  }
  std::sort(order_site_.begin(), order_site_.end());
  sorted_site_.clear();
  for (const auto& key : order_site_) sorted_site_.push_back(near_site_[std::get<2>(key)]);
  near_site_.swap(sorted_site_);
  // The free test sees every particle partner; only the kSitePartners nearest are paired.
  const std::size_t nf = static_cast<std::size_t>(std::count_if(
      near_site_.begin(), near_site_.end(), [](const SiteNear& t) { return !t.partner.is_plane; }));
  lx_.resize(nf);
  ly_.resize(nf);
  lz_.resize(nf);
  lr_.resize(nf);
  gx_.resize(nf);
  gy_.resize(nf);
  gz_.resize(nf);
  std::size_t f = 0;
  for (const SiteNear& t : near_site_) {
    if (t.partner.is_plane) continue;
    lx_[f] = t.partner.centre.x;
    ly_[f] = t.partner.centre.y;
    lz_[f] = t.partner.centre.z;
    lr_[f] = t.partner.radius;
    const auto j = static_cast<std::size_t>(t.code);
    gx_[f] = p_.x[j];
    gy_[f] = p_.y[j];
    gz_[f] = p_.z[j];
    ++f;
  }
  const std::size_t m = std::min(near_site_.size(), kSitePartners);
  const Partner origin = Partner::particle({0, 0, 0}, ri);
  const double radii[2] = {r_min_, r_max_};
  const int sizes = r_max_ > r_min_ ? 2 : 1;
  // Per size: the pair planes, and the box the new centre must lie in (inside() widened to its
  // largest tolerance over the domain, so it never refuses what inside() accepts).
  planes_.resize(2 * m);
  open_.resize(2 * m);
  std::array<std::array<double, 6>, 2> box{};
  for (int k = 0; k < sizes; ++k) {
    const auto row = static_cast<std::size_t>(k) * m;
    for (std::size_t u = 0; u < m; ++u) {
      planes_[row + u] = pair_plane(origin, near_site_[u].partner, radii[k]);
      open_[row + u] = !circle_covered(planes_[row + u], ri + radii[k], radii[k]);
    }
    for (int a = 0; a < 3; ++a) {
      const double tol = kInsideTolerance * (radii[k] + std::max(std::abs(domain_.lower[a]),
                                                                 std::abs(domain_.upper[a])));
      box[k][2 * a] = domain_.lower[a] + radii[k] - tol - component(ci, a);
      box[k][2 * a + 1] = domain_.upper[a] - radii[k] + tol - component(ci, a);
    }
  }
  // Only partners with an open circle for some size can give a site; the pairs are walked in
  // the same (u, v) order as over all partners, so the sites and their tie draws are the same.
  // Reach of two particle partners as one sum, (r_u + r_max) + (r_v + r_max) (in_reach).
  live_.clear();
  for (std::size_t u = 0; u < m; ++u) {
    if (open_[u] || (sizes == 2 && open_[m + u])) {
      const Partner& q = near_site_[u].partner;
      live_.push_back({q.centre, q.is_plane ? -1.0 : q.radius + r_max_, u});
    }
  }
  for (std::size_t lu = 0; lu < live_.size(); ++lu) {
    const LivePartner& pu = live_[lu];
    const SiteNear& su = near_site_[pu.index];
    for (std::size_t lv = lu + 1; lv < live_.size(); ++lv) {
      const LivePartner& pv = live_[lv];
      const SiteNear& sv = near_site_[pv.index];
      if (pu.reach < 0 || pv.reach < 0) {
        if (!in_reach(su.partner, sv.partner, r_max_)) continue;
      } else {
        const Vec3 d = pv.centre - pu.centre;
        const double s = pu.reach + pv.reach;
        if (dot(d, d) > s * s) continue;
      }
      bool found[2] = {false, false};
      for (int k = 0; k < sizes; ++k) {
        const double r = radii[k];
        const auto row = static_cast<std::size_t>(k) * m;
        const std::size_t u = row + pu.index, v = row + pv.index;
        if (!open_[u] || !open_[v]) continue;
        std::array<Vec3, 2> y;
        if (trilaterate(planes_[u], planes_[v], ri + r, y) == 0) continue;
        const std::array<double, 6>& b = box[k];
        for (std::size_t side = 0; side < 2; ++side) {  // y[0] on the +u side, y[1] on the -u side
          const Vec3& x = y[side];
          if (found[side] || !(x.x >= b[0] && x.x <= b[1] && x.y >= b[2] && x.y <= b[3] &&
                               x.z >= b[4] && x.z <= b[5])) {
            continue;
          }
          const Vec3 c = ci + x;  // the centre the site stores
          if (!free_locally(c, r)) continue;
          const Partner abc[3] = {origin, su.partner, sv.partner};
          if (!touches_all(abc, 3, x, r)) continue;
          found[side] = true;
          ++result_.sites;
          sites_.push({c.z, c.x, c.y, static_cast<std::uint32_t>(rng_() >> 32),
                       static_cast<std::int32_t>(i), static_cast<std::int32_t>(su.code),
                       static_cast<std::int32_t>(sv.code), static_cast<std::uint8_t>(side), 0,
                       static_cast<std::uint8_t>(k)});
        }
      }
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
bool Packer<Backend>::circle_covered(const PairPlane& plane, double rho, double r) const {
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
// try_lowest tests only the particles placed since (beds touch at the tolerance: in a 1e4 run
// stored centres within rounding of the 1e-12 overlap bound appeared after ~3000 spheres, and
// there a test relative to c_i answered otherwise). The candidates of one particle are mostly
// blocked by the same few neighbours (its contacts), so the neighbour that blocked the previous
// candidate is tested first; the rest go nearest surface first. The partners c was solved to touch pass the
// overlap test (they touch to ~1e-15, the test allows 1e-12), so they need no special case.
template <class Backend>
bool Packer<Backend>::free_locally(const Vec3& c, double r) {
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

// Lowest-site growth for a drawn radius r: pop the lowest sites, re-solve each for r and place
// at the first that fits (up to n_T sites). Until the floor seed is laid, and whenever no site
// is known or none takes r, r is dropped at a random spot onto the floor instead.
template <class Backend>
bool Packer<Backend>::try_lowest(double r) {
  if (sites_.empty() || floor_covered_ < o_.floor_seed * domain_.length(0) * domain_.length(1)) {
    if (floor_sweep(r)) return true;
  }
  retry_.clear();
  bool placed = false;
  for (int t = 0; t < o_.tries && !placed && !sites_.empty(); ++t) {
    ++result_.tries;
    Site s = sites_.pop();
    const bool stored = r == (s.found_for == 0 ? r_min_ : r_max_);
    if (stored) {
      // find_sites tested the stored centre against every particle up to its finder s.a (all
      // that can reach it), so only the particles placed since can cover it now.
      placed = accept({s.x, s.y, s.key}, r, s.a);
      if (placed || r == r_min_) continue;
    }
    const Partner a = partner(s.a), b = partner(s.b), c = partner(s.c);
    Vec3 x;
    placed = !stored && site_centre(a, b, c, r, s.side, x) && accept(x, r);
    if (!placed && r > r_min_ && s.retries < kSiteRetries &&
        site_centre(a, b, c, r_min_, s.side, x) && inside(x, r_min_) &&
        backend_.fits(x.x, x.y, x.z, r_min_)) {
      ++s.retries;
      retry_.push_back(s);
    }
  }
  for (const Site& s : retry_) sites_.push(s);
  if (placed) return true;
  // No known site takes r: a free spot on the floor, if any, is the lowest of all.
  return floor_sweep(r);
}

// Up to n_T random drops of r onto the floor. Once a sweep fails for r, the floor is closed to
// r and every larger size for the rest of the run: n_T failed uniform drops bound the free
// fraction of the floor (for that size) below 3 / n_T at 95 % confidence, and the floor only
// fills up. Without this, every failed size of a full bed paid n_T floor attempts, most of a
// default run's attempts (GenGeo scene, docs/results/packgen-speed.md: 1.2 of 1.6 M). Below
// kMinSweep drops a failed sweep bounds nothing worth closing on (n_T = 10: a third of the floor
// could still be free), so small --tries keep the floor open.
template <class Backend>
bool Packer<Backend>::floor_sweep(double r) {
  constexpr int kMinSweep = 100;  // 3 / n_T <= 3 % of the floor
  if (r >= floor_closed_from_) return false;
  for (int t = 0; t < o_.tries; ++t) {
    if (try_floor(r)) return true;
  }
  if (o_.tries >= kMinSweep) floor_closed_from_ = r;
  return false;
}

template <class Backend>
bool Packer<Backend>::try_floor(double r) {
  ++result_.tries;
  const Vec3 c{uniform(rng_, domain_.lower[0] + r, domain_.upper[0] - r),
               uniform(rng_, domain_.lower[1] + r, domain_.upper[1] - r), domain_.lower[2] + r};
  if (!accept(c, r)) return false;
  floor_covered_ += kPi * r * r;
  return true;
}

template <class Backend>
void Packer<Backend>::retire(std::uint32_t s) {
  const std::uint32_t at = slot_[s], last = active_.back();
  active_[at] = last;
  slot_[last] = at;
  active_.pop_back();
  ++result_.retired;
}

// Fisher–Yates over 0..K-1 (docs/physics.md §3: "evenly spaced angles shuffled").
template <class Backend>
void Packer<Backend>::shuffle_order() {
  for (std::size_t k = 0; k < order_.size(); ++k) order_[k] = static_cast<int>(k);
  for (std::size_t k = order_.size(); k > 1; --k) {
    std::swap(order_[k - 1], order_[uniform_index(rng_, k)]);
  }
}

// Walls 0..2 dim - 1: lower x, upper x, lower y, ... ; normals point into the domain.
template <class Backend>
Partner Packer<Backend>::partner(std::int64_t code) const {
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
double Packer<Backend>::wall_distance(int wall, const Vec3& c) const {
  const int axis = wall / 2;
  const double v = axis == 0 ? c.x : axis == 1 ? c.y : c.z;
  return wall % 2 == 0 ? v - domain_.lower[axis] : domain_.upper[axis] - v;
}

// Whether a new particle of radius r can touch both partners at once.
template <class Backend>
bool Packer<Backend>::compatible(std::int64_t a, std::int64_t b, double r) const {
  if (a < 0 && b < 0) return (-1 - a) / 2 != (-1 - b) / 2;  // walls on different axes
  if (a < 0) std::swap(a, b);
  const auto i = static_cast<std::size_t>(a);
  const Vec3 c{p_.x[i], p_.y[i], p_.z[i]};
  if (b < 0) return wall_distance(static_cast<int>(-1 - b), c) <= p_.r[i] + 2 * r;
  const auto j = static_cast<std::size_t>(b);
  const double dx = p_.x[j] - c.x, dy = p_.y[j] - c.y, dz = p_.z[j] - c.z;
  const double s = p_.r[i] + p_.r[j] + 2 * r;
  return dx * dx + dy * dy + dz * dz <= s * s;
}

// Partners of s for a new particle of radius r: particles with centre distance <= r_s + r_j + 2r
// (docs/physics.md §3 2-contact) and walls within r_s + 2r, found through the exact grid.
template <class Backend>
void Packer<Backend>::gather_partners(std::uint32_t s, double r) {
  near_.clear();
  const Vec3 c{p_.x[s], p_.y[s], p_.z[s]};
  partners_.for_each_within(c.x, c.y, c.z, p_.r[s] + 2 * r, [&](std::uint32_t j) {
    if (j != s) near_.push_back(j);
    return false;
  });
  for (int wall = 0; wall < 2 * dim_; ++wall) {
    if (wall_distance(wall, c) <= p_.r[s] + 2 * r) near_.push_back(-1 - wall);
  }
}

// 0-contact: centre uniform in the domain inset by r; with probability edge_fraction one axis
// is redrawn within one largest diameter of a random wall ([LP] extra boundary sampling).
template <class Backend>
bool Packer<Backend>::try_random(double r) {
  double v[3] = {0, 0, 0};
  for (int a = 0; a < dim_; ++a) v[a] = uniform(rng_, domain_.lower[a] + r, domain_.upper[a] - r);
  if (o_.edge_fraction > 0 && uniform01(rng_) < o_.edge_fraction) {
    const auto wall = static_cast<int>(uniform_index(rng_, static_cast<std::uint64_t>(2 * dim_)));
    const int axis = wall / 2;
    const double lo = domain_.lower[axis] + r, hi = domain_.upper[axis] - r;
    const double band = 2 * r_max_;
    v[axis] = wall % 2 == 0 ? uniform(rng_, lo, std::min(lo + band, hi))
                            : uniform(rng_, std::max(hi - band, lo), hi);
  }
  return accept({v[0], v[1], v[2]}, r);
}

// 1-contact: on the circle/sphere of radius r_s + r around s; 2D: K evenly spaced angles with
// a random offset in shuffled order; 3D: K uniform directions on the sphere.
template <class Backend>
bool Packer<Backend>::try_one(std::uint32_t s, double r) {
  const Vec3 c{p_.x[s], p_.y[s], p_.z[s]};
  const double rho = p_.r[s] + r;
  const int k_max = o_.directions;
  if (dim_ == 2) {
    const double step = 2 * kPi / k_max;
    const double offset = uniform(rng_, 0, step);
    shuffle_order();
    for (int k = 0; k < k_max; ++k) {
      const double angle = offset + step * order_[static_cast<std::size_t>(k)];
      if (accept({c.x + rho * std::cos(angle), c.y + rho * std::sin(angle), 0}, r)) return true;
    }
    return false;
  }
  for (int k = 0; k < k_max; ++k) {
    const double cz = uniform(rng_, -1, 1), phi = uniform(rng_, 0, 2 * kPi);
    const double sz = std::sqrt(std::max(0.0, 1 - cz * cz));
    if (accept({c.x + rho * sz * std::cos(phi), c.y + rho * sz * std::sin(phi), c.z + rho * cz},
               r)) {
      return true;
    }
  }
  return false;
}

// 2-contact: touch s and a partner (particle or wall) chosen uniformly among those in reach.
// With no partner in reach, s is tried with 1 contact (an approach uses at most its contacts).
template <class Backend>
bool Packer<Backend>::try_two(std::uint32_t s, double r) {
  gather_partners(s, r);
  if (near_.empty()) return try_one(s, r);
  return touch_two(s, near_[uniform_index(rng_, near_.size())], r);
}

template <class Backend>
bool Packer<Backend>::touch_two(std::uint32_t s, std::int64_t q, double r) {
  const Partner a = partner(s), b = partner(q);
  if (dim_ == 2) {
    std::array<Vec3, 2> x;
    return accept_mirror(x, touch_two_2d(a, b, r, x), r);
  }
  Circle circle;
  if (!touch_two_3d(a, b, r, circle)) return false;
  const double step = 2 * kPi / o_.directions;
  const double offset = uniform(rng_, 0, step);
  shuffle_order();
  for (int k = 0; k < o_.directions; ++k) {
    if (accept(circle.at(offset + step * order_[static_cast<std::size_t>(k)]), r)) return true;
  }
  return false;
}

// The (up to) two solutions of a closed form, in random order.
template <class Backend>
bool Packer<Backend>::accept_mirror(const std::array<Vec3, 2>& x, int m, double r) {
  const std::size_t first = m == 2 ? uniform_index(rng_, 2) : 0;
  for (int k = 0; k < m; ++k) {
    if (accept(x[(first + static_cast<std::size_t>(k)) % 2], r)) return true;
  }
  return false;
}

// 3-contact (3D): touch s and two partners in reach of s and of each other; two mirror points.
// With fewer partners in reach it falls back to 2 and then 1 contact.
template <class Backend>
bool Packer<Backend>::try_three(std::uint32_t s, double r) {
  gather_partners(s, r);
  if (near_.empty()) return try_one(s, r);
  const std::int64_t q1 = near_[uniform_index(rng_, near_.size())];
  near2_.clear();
  for (const std::int64_t q : near_) {
    if (q != q1 && compatible(q1, q, r)) near2_.push_back(q);
  }
  if (near2_.empty()) return touch_two(s, q1, r);
  const std::int64_t q2 = near2_[uniform_index(rng_, near2_.size())];
  std::array<Vec3, 2> x;
  return accept_mirror(x, touch_three_3d(partner(s), partner(q1), partner(q2), r, x), r);
}

template <class Backend>
bool Packer<Backend>::try_once(int approach, double r) {
  ++result_.tries;
  if (approach == 0 || p_.size() == 0) return try_random(r);  // the first particle: 0-contact
  const std::uint32_t s = active_[uniform_index(rng_, active_.size())];
  const bool ok = approach == 1 ? try_one(s, r) : approach == 2 ? try_two(s, r) : try_three(s, r);
  if (ok) {
    fails_[s] = 0;
  } else if (o_.retire_after > 0 && ++fails_[s] >= o_.retire_after) {
    retire(s);
  }
  return ok;
}

template <class Backend>
PackResult Packer<Backend>::run() {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto last_report = start;
  std::size_t phase = 0;
  for (std::size_t loop = 0;; ++loop) {
    if (o_.count > 0 && p_.size() >= o_.count) {
      result_.stop_reason = "count";
      break;
    }
    if (o_.target_density > 0 && density() >= o_.target_density) {
      result_.stop_reason = "target density";
      break;
    }
    if (result_.failures_in_a_row >= o_.max_failures) {
      result_.stop_reason = "max failures";
      result_.target_reached = o_.count == 0 && o_.target_density == 0;
      break;
    }
    while (phase + 1 < o_.phases.size() && density() >= o_.phases[phase].until_density) ++phase;
    const int approach = o_.phases[phase].approach;
    const double r = sizes_.next(rng_);
    bool placed = false;
    if (size_fits(r) && approach == 3 && lowest_) {
      placed = try_lowest(r);
    } else if (size_fits(r)) {
      // A partner-based approach with every particle retired has nowhere left to try.
      for (int t = 0; t < o_.tries && !placed && !exhausted(approach); ++t) {
        placed = try_once(approach, r);
      }
    }
    if (placed) {
      result_.failures_in_a_row = 0;
    } else {
      ++result_.failed_placements;
      ++result_.failures_in_a_row;
    }
    if (o_.progress && loop % 256 == 0) {
      const auto now = Clock::now();
      if (now - last_report > std::chrono::milliseconds(250)) {
        last_report = now;
        PackProgress pr;
        pr.n = p_.size();
        pr.density = density();
        pr.elapsed = std::chrono::duration<double>(now - start).count();
        pr.fraction_done =
            o_.count > 0            ? double(p_.size()) / double(o_.count)
            : o_.target_density > 0 ? density() / o_.target_density
                                    : double(result_.failures_in_a_row) / double(o_.max_failures);
        o_.progress(pr);
      }
    }
  }
  result_.wall_time = std::chrono::duration<double>(Clock::now() - start).count();
  bed::Bed& bed = result_.bed;
  bed.domain = domain_;
  bed.x = p_.x;
  bed.y = p_.y;
  bed.z = p_.z;
  bed.radius = p_.r;
  bed.id.resize(p_.size());
  for (std::size_t i = 0; i < bed.id.size(); ++i) bed.id[i] = i;
  return std::move(result_);
}

}  // namespace

PackResult pack(const bed::Domain& domain, const bed::Psd& psd, const PackOptions& options,
                std::uint64_t seed) {
  validate(domain, psd, options);
  Particles particles;
  CellGrid partners(domain, psd.min_radius(), psd.max_radius(), particles);
  switch (options.collision) {
    case Collision::raster: {
      RasterBackend backend{RasterGrid(domain, options.raster_spacing, particles,
                                       options.raster_max_bytes)};
      return Packer<RasterBackend>(domain, psd, options, seed, particles, partners, backend).run();
    }
    case Collision::kdtree: {
      KdTreeBackend backend{KdTreeIndex(domain.dimension, psd.max_radius(), particles)};
      return Packer<KdTreeBackend>(domain, psd, options, seed, particles, partners, backend).run();
    }
    case Collision::grid:
      break;
  }
  GridBackend backend{partners};
  return Packer<GridBackend>(domain, psd, options, seed, particles, partners, backend).run();
}

}  // namespace powderbed::packgen
