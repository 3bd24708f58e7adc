// The spread's pruned neighbour list (dem/src/neighbour_list.hpp): whatever the particles do
// between builds, the hot entries hold every pair in contact, so a force loop over them alone
// misses none.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>

#include "box.hpp"
#include "neighbour_list.hpp"

using powderbed::dem::detail::Box;
using powderbed::dem::detail::NeighbourList;
using powderbed::dem::detail::ParticleView;

namespace {

struct Gas {
  std::vector<double> x, y, z, r;
  ParticleView view() const { return {x.data(), y.data(), z.data(), r.data(), x.size()}; }
};

Box periodic_box(double length) {
  Box b;
  for (int a = 0; a < 3; ++a) {
    b.upper[a] = b.length[a] = length;
    b.periodic[a] = a < 2;  // x, y periodic; z walled, as a spread's strip
  }
  return b;
}

using Pairs = std::set<std::pair<std::size_t, std::size_t>>;

bool touch(const Box& box, const Gas& g, std::size_t i, std::size_t j) {
  const double ex = box.image(0, g.x[j] - g.x[i]), ey = box.image(1, g.y[j] - g.y[i]),
               ez = box.image(2, g.z[j] - g.z[i]);
  const double reach = g.r[i] + g.r[j];
  return ex * ex + ey * ey + ez * ez < reach * reach;
}

Pairs contacts_by_brute_force(const Box& box, const Gas& g) {
  Pairs out;
  for (std::size_t i = 0; i < g.x.size(); ++i)
    for (std::size_t j = i + 1; j < g.x.size(); ++j)
      if (touch(box, g, i, j)) out.insert({i, j});
  return out;
}

Pairs contacts_in_hot_entries(const Box& box, const Gas& g, const NeighbourList& list) {
  Pairs out;
  for (std::size_t q = 0; q < list.hot_entries(); ++q) {
    const std::size_t k = list.hot()[q];
    const std::size_t i = list.owners()[k], j = list.partners()[k];
    if (touch(box, g, i, j)) out.insert({std::min(i, j), std::max(i, j)});
  }
  return out;
}

}  // namespace

// 300 spheres of radius 10-15 (arbitrary unit) at random in a 150-wide box, each drifting 0.1 a
// step in its own direction with a jitter of 0.01: all reach half the margin together, so pairs
// closing head-on close by nearly the whole margin between prunes. 1000 steps of builds
// and prunes as NeighbourList::stale asks, the contacts among the hot entries compared with all
// pairs' at every step. Fails if a prune leaves out an entry that comes into contact before the
// next prune or build: a hot list cut at half the margin fails by step 50.
TEST(NeighbourList, HotEntriesHoldEveryContactBetweenBuildsAndPrunes) {
  const double length = 150, r_max = 15, skin = 0.5 * r_max, margin = 0.05 * r_max;
  const Box box = periodic_box(length);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto signed_unit = [&] { return 2.0 * unit(random) - 1.0; };
  Gas g;
  std::vector<double> v;  // per particle, x y z: the drift per step
  for (int p = 0; p < 300; ++p) {
    g.x.push_back(length * unit(random));
    g.y.push_back(length * unit(random));
    g.z.push_back(length * unit(random));
    g.r.push_back(10.0 + 5.0 * unit(random));
    double d[3], norm = 0;  // a random direction
    do {
      for (double& c : d) c = signed_unit();
      norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    } while (norm > 1.0 || norm < 1e-3);
    for (const double c : d) v.push_back(0.1 * c / norm);
  }
  NeighbourList list;
  list.configure(box, r_max, skin, g.x.size());
  list.build(g.view(), 1);
  list.prune(g.view(), margin);
  int builds = 0, prunes = 0;
  std::size_t contacts = 0;
  for (int step = 0; step < 1000; ++step) {
    for (std::size_t i = 0; i < g.x.size(); ++i) {
      const double jitter = 0.01;
      g.x[i] = box.wrap(0, g.x[i] + v[3 * i] + jitter * signed_unit());
      g.y[i] = box.wrap(1, g.y[i] + v[3 * i + 1] + jitter * signed_unit());
      g.z[i] = std::clamp(g.z[i] + v[3 * i + 2] + jitter * signed_unit(), 0.0, length);
    }
    switch (list.stale(g.view())) {
      case NeighbourList::Stale::build:
        list.build(g.view(), 1);
        list.prune(g.view(), margin);
        ++builds;
        break;
      case NeighbourList::Stale::prune:
        list.prune(g.view(), margin);
        ++prunes;
        break;
      case NeighbourList::Stale::no:
        break;
    }
    const Pairs all = contacts_by_brute_force(box, g);
    ASSERT_EQ(contacts_in_hot_entries(box, g, list), all) << "step " << step;
    contacts += all.size();
    ASSERT_LT(list.hot_entries(), list.pair_entries());  // the prune leaves entries out
  }
  EXPECT_GE(builds, 10);
  EXPECT_GT(prunes, 3 * builds);  // most intervals end in a prune, not a build
  EXPECT_GT(contacts, 1000u);     // the comparison saw contacts at every step on average
}

// A few particles in a box narrow along a periodic axis (a spread's strip after its overflow
// went): the cells widened for a sparse box stay narrow enough for 3 along that axis, and the
// list still finds every contact. The box refused is one narrower than 3 least widths.
TEST(NeighbourList, FewParticlesInANarrowPeriodicBoxKeepThreeCells) {
  Box box;
  const double length[3] = {1500, 300, 600};
  for (int a = 0; a < 3; ++a) {
    box.upper[a] = box.length[a] = length[a];
    box.periodic[a] = a == 1;
  }
  Gas g;
  for (int k = 0; k < 10; ++k) {  // touching pairs across the periodic y boundary
    g.x.push_back(200.0 * (k / 2) + 50);
    g.y.push_back(k % 2 == 0 ? 10.0 : 290.0);
    g.z.push_back(100.0);
    g.r.push_back(15.0);
  }
  NeighbourList list;
  ASSERT_NO_THROW(list.configure(box, 15.0, 7.5, g.x.size()));
  list.build(g.view(), 1);
  list.prune(g.view(), 1.0);
  EXPECT_EQ(contacts_in_hot_entries(box, g, list), contacts_by_brute_force(box, g));
  EXPECT_EQ(contacts_by_brute_force(box, g).size(), 5u);
  box.upper[1] = box.length[1] = 3 * 37.5 * 0.99;
  EXPECT_ANY_THROW(list.configure(box, 15.0, 7.5, g.x.size()));
}
