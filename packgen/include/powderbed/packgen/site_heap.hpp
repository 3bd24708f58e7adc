#pragma once
// "Lowest site first" 3-contact growth (docs/physics.md §3 3-contact, after Bennett, J. Appl. Phys. 43,
// 2727 (1972) and Visscher & Bolsterli, Nature 239, 504 (1972)): every triple of partners that
// a new particle could touch at once (particles, floor, walls) is a site; sites wait in a
// min-heap keyed by the height of the new centre and the lowest free one is filled next.
// A site stores its partners and which of the two mirror solutions it is, so it can be
// re-evaluated for any drawn radius (the [LP] rule: the size is drawn first), and the centre
// it was found for, so a drawn radius equal to that one (every draw of a monodisperse PSD)
// skips the re-evaluation.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "powderbed/packgen/contact_geometry.hpp"

namespace powderbed::packgen {

struct Site {
  double key = 0;            // height (z) of the centre when the site was found
  double x = 0, y = 0;       // the rest of that centre
  std::uint32_t tie = 0;     // random tie break, so equal heights (the floor) are taken at random
  std::int32_t a = 0;        // the first partner: always a particle
  std::int32_t b = 0, c = 0; // partner codes: >= 0 particles, < 0 walls (-1 - wall)
  std::uint8_t side = 0;     // 0: the solution on the +u side, 1: on the -u side (trilaterate)
  std::uint8_t retries = 0;  // failed re-evaluations for drawn sizes (PSD only)
  std::uint8_t found_for = 0;  // the centre is for the PSD's smallest (0) or largest (1) size
};

// A min-priority queue on (key, tie) with exact order, as lowest-site growth pushes and pops
// ~7 sites per particle. Keys (heights) are binned into slabs of a fixed width: the slab being
// emptied is a binary heap, later slabs are unsorted lists heapified when reached, and a key
// pushed below the current slab joins its heap (a slab's keys are all below the next slab's, so
// pops come out in exactly the order of one heap over all sites). Growth from the floor keeps
// the live sites within a few diameters of the front, so the heap touched per pop holds a few
// slabs' worth instead of the whole front (its live sites grow with the floor area: 2.2e4 of
// 48 bytes at 1e5 spheres, ~1e5 at 1e6, beyond the caches).
class SiteHeap {
 public:
  // Keys are expected in [lo, hi] (others go to the first or last slab); `width` > 0.
  SiteHeap(double lo = 0, double hi = 1, double width = 1)
      : lo_(lo), inv_width_(1 / width),
        slabs_(static_cast<std::size_t>(std::max(1.0, std::ceil((hi - lo) * inv_width_) + 1))) {}
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  void push(const Site& s) {
    ++size_;
    const std::size_t b = slab(s.key);
    if (b <= current_) {
      heap_.push_back(s);
      std::push_heap(heap_.begin(), heap_.end(), Later{});
    } else {
      std::vector<Site>& slab = slabs_[b];
      if (slab.capacity() == 0 && !spare_.empty()) {  // reuse a spent slab's storage
        slab.swap(spare_.back());
        spare_.pop_back();
      }
      slab.push_back(s);
    }
  }
  Site pop() {  // the lowest (key, tie); requires !empty()
    while (heap_.empty()) {  // the next non-empty slab becomes the heap
      heap_.swap(slabs_[++current_]);
      if (slabs_[current_].capacity() > 0) spare_.push_back(std::move(slabs_[current_]));
      std::make_heap(heap_.begin(), heap_.end(), Later{});
    }
    std::pop_heap(heap_.begin(), heap_.end(), Later{});
    const Site s = heap_.back();
    heap_.pop_back();
    --size_;
    return s;
  }

 private:
  // std::push_heap builds a max-heap of its `less`, so "later" gives a min-heap.
  struct Later {
    bool operator()(const Site& s, const Site& t) const {
      return s.key > t.key || (s.key == t.key && s.tie > t.tie);
    }
  };
  std::size_t slab(double key) const {
    const double f = std::floor((key - lo_) * inv_width_);
    return static_cast<std::size_t>(std::min(std::max(f, 0.0), double(slabs_.size() - 1)));
  }
  double lo_, inv_width_;
  std::vector<std::vector<Site>> slabs_;
  std::vector<Site> heap_;  // every site of slabs <= current_
  // Emptied storage of spent slabs: growth fills slab after slab of about the same size, so
  // reusing it spares the copies of vector growth (measured: most of push() at 1e6 spheres).
  std::vector<std::vector<Site>> spare_;
  std::size_t current_ = 0, size_ = 0;
};

// The centre on `side` touching a, b and c for a new particle of radius r; false when that
// solution does not exist for r (touch_three_3d's tolerances and checks).
bool site_centre(const Partner& a, const Partner& b, const Partner& c, double r,
                 std::uint8_t side, Vec3& x);

}  // namespace powderbed::packgen
