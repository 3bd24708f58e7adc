#include "powderbed/keff/network.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <string>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/neighbours.hpp"
#include "powderbed/keff/radiation.hpp"
#include "powderbed/keff/view_factors.hpp"

namespace powderbed::keff {
namespace {

const char* const kAxisName[3] = {"x", "y", "z"};

void check(const bed::Bed& bed, int axis) {
  if (bed.domain.dimension != 3)
    throw InputError(std::string("axis: ") + kAxisName[axis] +
                     " in a 2D bed (accepted: a 3D bed of spheres, whose axes are x, y and z)");
  if (bed.domain.periodic[static_cast<std::size_t>(axis)])
    throw InputError(std::string("axis: ") + kAxisName[axis] +
                     " is periodic in the bed (accepted: an axis with walls at both faces)");
  const auto a = static_cast<std::size_t>(axis);
  const std::vector<double>& centre = axis == 0 ? bed.x : axis == 1 ? bed.y : bed.z;
  for (std::size_t p = 0; p < bed.n(); ++p)
    if (!(centre[p] > bed.domain.lower[a] && centre[p] < bed.domain.upper[a]))
      // {:f}: the six decimals std::to_string gave these doubles.
      throw InputError(fmt::format(
          "bed: particle {} has its centre at {} = {:f} m, outside the walls (accepted: between "
          "{:f} and {:f} m)",
          bed.id[p], kAxisName[axis], centre[p], bed.domain.lower[a], bed.domain.upper[a]));
}

}  // namespace

KeffNetwork build_keff_network(const bed::Bed& bed, const KeffScene& scene,
                               const std::function<void(double)>& progress) {
  scene.validate();
  check(bed, scene.axis);
  const auto a = static_cast<std::size_t>(scene.axis);
  KeffNetwork net;
  net.node_count = bed.n();
  net.height = bed.domain.length(scene.axis);
  net.wall_area = bed.domain.length(static_cast<int>((a + 1) % 3)) *
                  bed.domain.length(static_cast<int>((a + 2) % 3));
  const double k_g = scene.gas_path ? scene.gas_conductivity_used() : 0;
  const bool gas = k_g > 0;
  net.gas_reference = k_g;
  net.gas_follows_temperature = gas && scene.gas_model == GasModel::air;
  const auto add = [&](std::uint32_t i, std::uint32_t j, double g, HeatPath path) {
    if (g > 0) net.links.push_back({i, j, g, path});
  };

  // Lenses of radius (1 + lens) r overlap up to d = (1 + lens)(r_i + r_j).
  const double r_max = bed.n() ? *std::max_element(bed.radius.begin(), bed.radius.end()) : 0;
  const double gap = gas ? 2 * scene.lens.lens * r_max : 0;
  for (const bed::NeighbourPair& pr : bed::neighbour_pairs_cell_list(bed, gap)) {
    const double r_i = bed.radius[pr.i], r_j = bed.radius[pr.j];
    if (scene.contact_path)
      add(pr.i, pr.j,
          contact_conductance(scene.solid_conductivity, scene.calibration,
                              pair_contact_radius(scene.contact, r_i, r_j, pr.distance)),
          HeatPath::contact);
    if (gas)
      add(pr.i, pr.j, k_g * gas_pair_factor(scene.lens, r_i, r_j, pr.distance), HeatPath::gas);
  }

  const std::vector<double>& centre = a == 0 ? bed.x : a == 1 ? bed.y : bed.z;
  for (std::size_t p = 0; p < bed.n(); ++p) {
    const auto i = static_cast<std::uint32_t>(p);
    const double r = bed.radius[p];
    const double h_hot = bed.domain.upper[a] - centre[p], h_cold = centre[p] - bed.domain.lower[a];
    for (const auto& [wall, h] : {std::pair{kHotWall, h_hot}, std::pair{kColdWall, h_cold}}) {
      if (scene.contact_path)
        add(i, wall,
            contact_conductance(scene.solid_conductivity, scene.calibration,
                                wall_contact_radius(scene.contact, r, h)),
            HeatPath::contact);
      if (gas) add(i, wall, k_g * gas_wall_factor(scene.lens, r, h), HeatPath::gas);
    }
  }
  if (scene.radiation_path) {
    const ViewFactors vf = view_factors(bed, {scene.rays, scene.seed, scene.axis, progress});
    net.lost_rays = vf.lost_rays;
    add_radiation_links(bed, scene, vf, net);
  }
  return net;
}

}  // namespace powderbed::keff
