#pragma once
// "Lowest site first" 3-contact growth (SPEC.md §3 3-contact, after Bennett, J. Appl. Phys. 43,
// 2727 (1972) and Visscher & Bolsterli, Nature 239, 504 (1972)): every triple of partners that
// a new particle could touch at once (particles, floor, walls) is a site; sites wait in a
// min-heap keyed by the height of the new centre and the lowest free one is filled next.
// A site stores its partners and which of the two mirror solutions it is, so it can be
// re-evaluated for any drawn radius (the [LP] rule: the size is drawn first).
#include <array>
#include <cstdint>
#include <vector>

#include "powderbed/packgen/contact_geometry.hpp"

namespace powderbed::packgen {

struct Site {
  double key = 0;            // height (z) of the centre when the site was found
  std::uint32_t tie = 0;     // random tie break, so equal heights (the floor) are taken at random
  std::int32_t a = 0;        // the first partner: always a particle
  std::int32_t b = 0, c = 0; // partner codes: >= 0 particles, < 0 walls (-1 - wall)
  std::uint8_t side = 0;     // 0: the solution on the +u side, 1: on the -u side (trilaterate)
  std::uint8_t retries = 0;  // failed re-evaluations for drawn sizes (PSD only)
};

class SiteHeap {
 public:
  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  void push(const Site& s);
  Site pop();  // the lowest (key, tie); requires !empty()

 private:
  std::vector<Site> heap_;
};

// The centre on `side` touching a, b and c for a new particle of radius r; false when that
// solution does not exist for r (touch_three_3d's tolerances and checks).
bool site_centre(const Partner& a, const Partner& b, const Partner& c, double r,
                 std::uint8_t side, Vec3& x);

}  // namespace powderbed::packgen
