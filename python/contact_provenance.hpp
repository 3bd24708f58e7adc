#pragma once
// The contact law a DEM run made a bed with, recorded in its provenance as deposit records it
// (apps/deposit.cpp record_provenance): keff's Hertz correction reads it from the bed.
#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"

namespace powderbed::python {

inline void record_contact(bed::Provenance& p, const dem::Scene& scene, double young_scale) {
  bed::ContactProvenance& made = p.contact;
  made = {};
  made.law = dem::contact_law_name(scene.law);
  made.young = scene.material.young;
  made.poisson = scene.material.poisson;
  made.wall_young = scene.wall.young;
  made.wall_poisson = scene.wall.poisson;
  made.young_scale = young_scale;
  made.stiffness = scene.stiffness;
  if (scene.fines.scaling == dem::FinesScaling::stiffness)
    made.fines_stiffness_radius = scene.fines.radius;
}

}  // namespace powderbed::python
