#pragma once
// The contact law a DEM run made a bed with, as its provenance records it: keff's Hertz
// correction of the contact radii reads it back from the bed (docs/keff.md).
#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"

namespace powderbed::dem {

inline bed::ContactProvenance contact_provenance(const Scene& scene, double young_scale) {
  bed::ContactProvenance made;
  made.law = contact_law_name(scene.law);
  made.young = scene.material.young;
  made.poisson = scene.material.poisson;
  made.wall_young = scene.wall.young;
  made.wall_poisson = scene.wall.poisson;
  made.young_scale = young_scale;
  made.stiffness = scene.stiffness;
  if (scene.fines.scaling == FinesScaling::stiffness) made.fines_stiffness_radius = scene.fines.radius;
  return made;
}

}  // namespace powderbed::dem
