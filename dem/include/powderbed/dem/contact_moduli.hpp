#pragma once
// The moduli a run's contacts use: the materials' E softened by S (--young-scale) once, here,
// and the pair and particle–wall effective moduli of the Hertz law (hertz_normal.hpp) and of
// Mindlin's tangential spring (mindlin_tangential.hpp) built from them. Every part of the DEM
// that needs a contact's stiffness (the forces, the time step, the energy and wall forces of
// diagnostics) takes it from contact_moduli, so S divides E in one place.
#include "powderbed/bed/softening.hpp"
#include "powderbed/dem/hertz_normal.hpp"
#include "powderbed/dem/mindlin_tangential.hpp"
#include "powderbed/dem/scene.hpp"

namespace powderbed::dem {

struct ContactModuli {
  double young = 0, wall_young = 0;   // E / S of the particles and of the walls, Pa
  double pair = 0, wall = 0;          // E* of two particles, of a particle on a wall, Pa
  double pair_shear = 0, wall_shear = 0;  // G* of the same, Pa
};

inline ContactModuli contact_moduli(const Scene& scene, double young_scale) {
  const Material& m = scene.material;
  ContactModuli c;
  c.young = bed::softened_modulus(m.young, young_scale);
  c.wall_young = bed::softened_modulus(scene.wall.young, young_scale);
  c.pair = effective_modulus(c.young, m.poisson, c.young, m.poisson);
  c.wall = effective_modulus(c.young, m.poisson, c.wall_young, scene.wall.poisson);
  c.pair_shear = effective_shear_modulus(c.young, m.poisson, c.young, m.poisson);
  c.wall_shear = effective_shear_modulus(c.young, m.poisson, c.wall_young, scene.wall.poisson);
  return c;
}

}  // namespace powderbed::dem
