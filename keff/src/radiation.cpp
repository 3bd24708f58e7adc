#include "powderbed/keff/radiation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace powderbed::keff {
namespace {

// A = 4π r², the emitting surface of particle p.
double area(const bed::Bed& bed, std::size_t p) {
  return bed::sphere_area(bed.radius[p]);
}

// A pair's exchange area S_ij = (A_i F_ij + A_j F_ji) / 2, and each particle's with the walls.
struct Exchange {
  std::uint32_t a, b;  // a < b: particles; or a particle and kHotWall / kColdWall
  double area;         // m²
};

std::vector<Exchange> exchange_areas(const bed::Bed& bed, const ViewFactors& vf,
                                     double& reciprocity_error) {
  std::vector<Exchange> walls, halves;
  for (const ViewFactorEntry& e : vf.entries) {
    const double s = area(bed, e.i) * e.f;
    if (e.j == kHotWall || e.j == kColdWall)
      walls.push_back({e.i, e.j, s});
    else if (e.j != e.i)
      halves.push_back({std::min(e.i, e.j), std::max(e.i, e.j), s});
  }
  std::sort(halves.begin(), halves.end(), [](const Exchange& x, const Exchange& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  });
  std::vector<Exchange> out = std::move(walls);
  double mismatch = 0, scale = 0;
  for (std::size_t k = 0; k < halves.size();) {
    double sum = halves[k].area, other = 0;
    std::size_t next = k + 1;
    if (next < halves.size() && halves[next].a == halves[k].a && halves[next].b == halves[k].b)
      sum += other = halves[next++].area;
    mismatch += (sum - 2 * other) * (sum - 2 * other);  // (A_i F_ij − A_j F_ji)²
    scale += sum * sum / 4;
    // A pair seen from one side only has A F = 0 from the other: the mean is half the sum.
    out.push_back({halves[k].a, halves[k].b, sum / 2});
    k = next;
  }
  reciprocity_error = scale > 0 ? std::sqrt(mismatch / scale) : 0;
  return out;
}

void add_pair_links(const bed::Bed& bed, const KeffScene& scene,
                    const std::vector<Exchange>& exchanges, double wall_area, double f_wall,
                    KeffNetwork& net) {
  const double eps = scene.emissivity, eps_w = scene.wall_emissivity;
  for (const Exchange& x : exchanges) {
    const bool wall = x.b == kHotWall || x.b == kColdWall;
    const double a = area(bed, x.a);  // a wall's patch takes the particle's area (header)
    const double g = wall ? grey_exchange_area(eps, a, x.area, eps_w, a)
                          : grey_exchange_area(eps, a, x.area, eps, area(bed, x.b));
    net.links.push_back({x.a, x.b, g, HeatPath::radiation});
  }
  if (f_wall > 0)
    net.wall_exchange =
        grey_exchange_area(eps_w, wall_area, wall_area * f_wall, eps_w, wall_area);
}

void add_radiosity_links(const bed::Bed& bed, const KeffScene& scene,
                         const std::vector<Exchange>& exchanges, double wall_area, double f_wall,
                         KeffNetwork& net) {
  const std::size_t n = bed.n();
  const double eps = scene.emissivity, eps_w = scene.wall_emissivity;
  // Radiosity node of each particle (itself when black) and of each wall.
  const auto next_node = [&] { return static_cast<std::uint32_t>(net.node_count++); };
  std::vector<std::uint32_t> j_node(n);
  for (std::size_t p = 0; p < n; ++p) {
    const auto i = static_cast<std::uint32_t>(p);
    j_node[p] = i;
    if (eps == 1) continue;
    j_node[p] = next_node();
    net.links.push_back({j_node[p], i, eps * area(bed, p) / (1 - eps), HeatPath::radiation});
  }
  std::uint32_t j_hot = kHotWall, j_cold = kColdWall;
  if (eps_w < 1) {
    j_hot = next_node();
    j_cold = next_node();
    const double g = eps_w * wall_area / (1 - eps_w);
    net.links.push_back({j_hot, kHotWall, g, HeatPath::radiation});
    net.links.push_back({j_cold, kColdWall, g, HeatPath::radiation});
  }
  for (const Exchange& x : exchanges) {
    const std::uint32_t other =
        x.b == kHotWall ? j_hot : x.b == kColdWall ? j_cold : j_node[x.b];
    net.links.push_back({j_node[x.a], other, x.area, HeatPath::radiation});
  }
  if (f_wall <= 0) return;
  if (eps_w < 1)
    net.links.push_back({j_hot, j_cold, wall_area * f_wall, HeatPath::radiation});
  else
    net.wall_exchange = wall_area * f_wall;  // black walls: a link between the fixed walls
}

}  // namespace

void add_radiation_links(const bed::Bed& bed, const KeffScene& scene, const ViewFactors& vf,
                         KeffNetwork& net) {
  const std::vector<Exchange> exchanges = exchange_areas(bed, vf, net.reciprocity_error);
  if (scene.radiation_model == RadiationModel::pair)
    add_pair_links(bed, scene, exchanges, net.wall_area, vf.wall_to_wall, net);
  else
    add_radiosity_links(bed, scene, exchanges, net.wall_area, vf.wall_to_wall, net);
}

}  // namespace powderbed::keff
