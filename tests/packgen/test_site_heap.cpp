// The site queue of lowest-site growth (site_heap.hpp): its slabs must not change the order,
// so every pop is the lowest (key, tie) of all sites pushed so far, as one binary heap gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <queue>
#include <vector>

#include "powderbed/bed/random.hpp"
#include "powderbed/packgen/site_heap.hpp"

namespace {

using namespace powderbed;
using namespace powderbed::packgen;

struct Later {
  bool operator()(const Site& s, const Site& t) const {
    return s.key > t.key || (s.key == t.key && s.tie > t.tie);
  }
};

TEST(SiteHeap, PopsInExactKeyAndTieOrder) {
  // Keys in [0, 10] with slabs of 0.1 (a front sweeping upwards, as in growth), some below
  // the lowest key popped so far (a new site beside a high particle), some outside [0, 10]
  // (first / last slab), many equal (the floor: ties decide), pushes and pops interleaved.
  SiteHeap heap(0, 10, 0.1);
  std::priority_queue<Site, std::vector<Site>, Later> reference;
  bed::Rng rng(3);
  double front = 0;
  std::int32_t id = 0;
  for (int step = 0; step < 20000; ++step) {
    if (reference.empty() || bed::uniform01(rng) < 0.55) {
      const double u = bed::uniform01(rng);
      Site s;
      s.key = u < 0.1 ? 0.0 : u < 0.15 ? -1.0 : u < 0.2 ? 12.0 : front + bed::uniform(rng, -0.3, 1.0);
      s.tie = static_cast<std::uint32_t>(rng() >> 32);
      s.a = id++;
      heap.push(s);
      reference.push(s);
    } else {
      const Site s = heap.pop();
      EXPECT_EQ(s.a, reference.top().a);
      EXPECT_EQ(s.key, reference.top().key);
      reference.pop();
      front = std::max(front, s.key);
    }
    EXPECT_EQ(heap.size(), reference.size());
  }
  while (!reference.empty()) {
    EXPECT_EQ(heap.pop().a, reference.top().a);
    reference.pop();
  }
  EXPECT_TRUE(heap.empty());
}

}  // namespace
