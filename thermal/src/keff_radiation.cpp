#include "powderbed/thermal/keff_radiation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace powderbed::thermal {

std::vector<KeffLink> radiation_links(const bed::Bed& bed, const KeffScene& scene,
                                      const ViewFactors& vf) {
  const auto area = [&](std::uint32_t p) {
    return 4 * std::numbers::pi * bed.radius[p] * bed.radius[p];
  };
  const double eps = scene.emissivity, eps_w = scene.wall_emissivity;
  std::vector<KeffLink> links;
  // Pair halves keyed by (min, max): A_i F_ij from each side.
  struct Half {
    std::uint32_t a, b;
    double exchange;
  };
  std::vector<Half> halves;
  for (const ViewFactorEntry& e : vf.entries) {
    const double exchange = area(e.i) * e.f;
    if (e.j == kHotWall || e.j == kColdWall)
      links.push_back(
          {e.i, e.j, grey_exchange_area(eps, area(e.i), exchange, eps_w, area(e.i)),
           HeatPath::radiation});
    else if (e.j != e.i)
      halves.push_back({std::min(e.i, e.j), std::max(e.i, e.j), exchange});
  }
  std::sort(halves.begin(), halves.end(), [](const Half& x, const Half& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  });
  for (std::size_t k = 0; k < halves.size();) {
    double sum = halves[k].exchange;
    std::size_t next = k + 1;
    if (next < halves.size() && halves[next].a == halves[k].a && halves[next].b == halves[k].b)
      sum += halves[next++].exchange;
    // A pair seen from one side only has A F = 0 from the other: the mean is half the sum.
    const std::uint32_t a = halves[k].a, b = halves[k].b;
    links.push_back(
        {a, b, grey_exchange_area(eps, area(a), sum / 2, eps, area(b)), HeatPath::radiation});
    k = next;
  }
  return links;
}

}  // namespace powderbed::thermal
