#include "powderbed/thermal/bonding.hpp"

#include <numeric>

namespace powderbed::thermal {

namespace {

// Union–find over the particles, with path halving: the molten clusters of the contact network.
struct Clusters {
  std::vector<std::uint32_t> parent;
  explicit Clusters(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t root(std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent[root(a)] = root(b); }
};

// Whether the particle rests on solid that melted under it. Rests: its lowest point is within
// half a cell (dz/2) of the solid's top under its centre, which is as finely as the grid knows
// where that surface is (the top node stands for the half cell below it); a spread layer's
// particles often hover a fraction of a micrometre above the floor they settle on. Melted under
// it: the top node of a column of its footprint (the columns within its projected disc, where
// fusion puts its volume) reached the threshold, not only the corners under its centre: the particle shades
// the solid right under it, and the pool that melts around that shadow is what the liquid slumps
// into.
bool on_molten_solid(const bed::Bed& bed, const Sinter& sinter, std::size_t i, double threshold) {
  const SubstrateGeometry& g = sinter.grid();
  const double gap = bed.z[i] - bed.radius[i] - top_height_at(g, sinter.top_height(), bed.x[i], bed.y[i]);
  if (gap >= 0.5 * g.dz) return false;
  const auto& node_peak = sinter.substrate_peak();
  const auto& plane = sinter.top_planes();
  for (const auto& [column, weight] : top_footprint(g, bed.x[i], bed.y[i], bed.radius[i]))
    if (weight > 0 && node_peak[g.node(column, plane[column])] >= threshold) return true;
  return false;
}

}  // namespace

std::vector<std::uint8_t> bonded_melt(const bed::Bed& bed, const Sinter& sinter, double threshold) {
  const auto& peak = sinter.particle_max_temperature();
  const auto& merged = sinter.particle_merged();
  const std::vector<std::uint8_t> phase = sinter.particle_phase();
  const std::size_t n = peak.size();
  std::vector<std::uint8_t> melted(n);  // and still there: vapour carries no bond
  for (std::size_t i = 0; i < n; ++i)
    melted[i] = phase[i] != 2 && (peak[i] >= threshold || (!merged.empty() && merged[i])) ? 1 : 0;
  Clusters clusters(n);
  for (const ContactPair& p : sinter.network().pairs)
    if (melted[p.i] && melted[p.j]) clusters.join(p.i, p.j);
  std::vector<std::uint8_t> anchored(n, 0);  // per cluster root
  for (std::size_t i = 0; i < n; ++i)
    if ((!merged.empty() && merged[i]) || (melted[i] && on_molten_solid(bed, sinter, i, threshold)))
      anchored[clusters.root(static_cast<std::uint32_t>(i))] = 1;
  std::vector<std::uint8_t> bonded(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    bonded[i] = melted[i] && anchored[clusters.root(static_cast<std::uint32_t>(i))] ? 1 : 0;
  return bonded;
}

}  // namespace powderbed::thermal
