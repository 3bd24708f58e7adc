#pragma once
// Small beds and scenes built in code for the thermal tests: a few dozen particles on a
// substrate of a few thousand nodes, so that a whole laser pass takes milliseconds.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/thermal/material.hpp"
#include "powderbed/thermal/scene.hpp"
#include "powderbed/thermal/solver.hpp"

namespace powderbed::test {

inline thermal::MaterialTable table_316l() {
  return thermal::read_material_table(POWDERBED_SOURCE_DIR "/data/materials/316L.csv");
}

// A 3D bed domain [0, lx] x [0, ly] x [0, lz] with no particles: its floor z = 0 is the
// substrate's top face.
inline bed::Bed empty_bed(double lx, double ly, double lz) {
  bed::Bed b;
  b.domain.dimension = 3;
  b.domain.upper = {lx, ly, lz};
  return b;
}

// Centre height of a sphere of radius r resting on the floor z = 0: it overlaps the floor by
// 1e-4 r, so it has a (small) contact with the substrate and passes Sinter's resting check.
inline double resting_z(double r) { return r * (1 - 1e-4); }

// Two layers of equal spheres of radius r: an nx x ny square lattice on the floor, then one
// sphere in each hollow of it. Neighbours overlap by 2 % of r (centre distances 1.98 r), so the
// network is connected and every contact has a finite area. The domain just holds layer one.
inline bed::Bed lattice_bed(std::size_t nx, std::size_t ny, double r) {
  const double s = 1.98 * r;
  const auto at = [&](double k) { return r + k * s; };
  bed::Bed b = empty_bed(at(static_cast<double>(nx - 1)) + r, at(static_cast<double>(ny - 1)) + r,
                         6 * r);
  const double z0 = resting_z(r);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i)
      b.add(at(static_cast<double>(i)), at(static_cast<double>(j)), z0, r);
  // A hollow sphere sits at horizontal distance s/sqrt(2) from its four supports, so a rise of
  // s/sqrt(2) puts it at distance s from each: the same overlap as in layer one.
  const double rise = s / std::sqrt(2.0);
  for (std::size_t j = 0; j + 1 < ny; ++j)
    for (std::size_t i = 0; i + 1 < nx; ++i)
      b.add(at(static_cast<double>(i) + 0.5), at(static_cast<double>(j) + 0.5), z0 + rise, r);
  return b;
}

// Bimodal: 4 x 2 spheres of r = 20 µm on the floor (centre distances 1.98 r), each with two of
// r = 2 µm: one on the floor at +x (in the gap before the next column, 27 µm from the next
// big sphere's axis) and one on its top, each overlapping the big one by `overlap` of its
// radius. Particles come in triplets (big, tiny on the floor, tiny on top).
inline bed::Bed bimodal_bed(double overlap) {
  const double big = 20e-6, tiny = 2e-6, s = 1.98 * big;
  bed::Bed b = empty_bed(big + 3 * s + big + 10e-6, big + s + big + 10e-6, 100e-6);
  const double zb = resting_z(big), zt = resting_z(tiny);
  const double d = big + tiny - overlap * tiny;  // centre distance of a tiny–big contact
  const double beside = std::sqrt(d * d - (zb - zt) * (zb - zt));
  for (std::size_t j = 0; j < 2; ++j)
    for (std::size_t i = 0; i < 4; ++i) {
      const double x = big + static_cast<double>(i) * s, y = big + static_cast<double>(j) * s;
      b.add(x, y, zb, big);
      b.add(x + beside, y, zt, tiny);
      b.add(x, y, zb + d, tiny);
    }
  return b;
}

// A scene with only `effects` on, the laser of [GZ] Table 2 otherwise, on a small grid.
inline thermal::SinterScene small_scene(unsigned effects, std::array<std::size_t, 3> nodes,
                                        double depth) {
  thermal::SinterScene scene;
  scene.effects = effects;
  // These scenes test [GZ]'s model, whose laser is Beer–Lambert's (the ray tracer has its own
  // tests: test_ray_traced_laser.cpp).
  scene.absorption = thermal::LaserAbsorption::beer_lambert;
  scene.nodes = nodes;
  scene.substrate_depth = depth;
  return scene;
}

// max over free substrate nodes of |T - expected(x, y, z)|.
template <class F>
double max_free_node_error(const thermal::Sinter& sinter, F expected) {
  const auto& g = sinter.grid();
  const auto& t = sinter.substrate_temperature();
  double worst = 0;
  for (std::size_t k = 0; k < g.nz; ++k)
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i) {
        if (g.fixed(i, j, k)) continue;
        const double e = std::abs(t[g.index(i, j, k)] - expected(g.x(i), g.y(j), g.z(k)));
        worst = std::max(worst, e);
      }
  return worst;
}

}  // namespace powderbed::test
