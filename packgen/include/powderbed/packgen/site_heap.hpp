#pragma once
// "Lowest site first" 3-contact growth (SPEC.md §3 3-contact, after Bennett, J. Appl. Phys. 43,
// 2727 (1972) and Visscher & Bolsterli, Nature 239, 504 (1972)): every triple of partners that
// a new particle could touch at once (particles, floor, walls) is a site; sites wait in a
// min-heap keyed by the height of the new centre and the lowest free one is filled next.
// A site stores its partners and which of the two mirror solutions it is, so it can be
// re-evaluated for any drawn radius (the [LP] rule: the size is drawn first), and the centre
// it was found for, so a drawn radius equal to that one (every draw of a monodisperse PSD)
// skips the re-evaluation.
#include <algorithm>
#include <array>
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

// A binary min-heap on (key, tie); inline, as lowest-site growth pushes and pops ~7 sites per
// particle. (A 4-ary heap of 16-byte entries over a pool of sites measured no faster at 1e6.)
class SiteHeap {
 public:
  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  void push(const Site& s) {
    heap_.push_back(s);
    std::push_heap(heap_.begin(), heap_.end(), Later{});
  }
  Site pop() {  // the lowest (key, tie); requires !empty()
    std::pop_heap(heap_.begin(), heap_.end(), Later{});
    const Site s = heap_.back();
    heap_.pop_back();
    return s;
  }

 private:
  // std::push_heap builds a max-heap of its `less`, so "later" gives a min-heap.
  struct Later {
    bool operator()(const Site& s, const Site& t) const {
      return s.key > t.key || (s.key == t.key && s.tie > t.tie);
    }
  };
  std::vector<Site> heap_;
};

// The centre on `side` touching a, b and c for a new particle of radius r; false when that
// solution does not exist for r (touch_three_3d's tolerances and checks).
bool site_centre(const Partner& a, const Partner& b, const Partner& c, double r,
                 std::uint8_t side, Vec3& x);

}  // namespace powderbed::packgen
