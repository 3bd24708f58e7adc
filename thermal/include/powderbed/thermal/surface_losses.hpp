#pragma once
// Losses of an exposed top particle (docs/physics.md §5) over its projected area A = π r^2:
//   convection h (T_env - T) A,  radiation eps sigma (T_env^4 - T^4) A.
#include "powderbed/bed/contact_geometry.hpp"
#include "powderbed/bed/radiative_exchange.hpp"

namespace powderbed::thermal {

using bed::kStefanBoltzmann;  // W/m^2K^4, shared with keff

struct SurfaceParams {
  double convection;   // h, W/m^2K
  double emissivity;   // eps
  double environment;  // T_env, K
};

// Heat into the particle (W; negative when it loses heat).
inline double convection_gain(const SurfaceParams& p, double t, double area) {
  return p.convection * (p.environment - t) * area;
}
inline double radiation_gain(const SurfaceParams& p, double t, double area) {
  return bed::radiative_exchange(p.emissivity, p.environment, t) * area;
}
// d(loss)/dT: the conductance that bounds the stable step (and linearises the implicit step).
inline double radiation_conductance(const SurfaceParams& p, double t, double area) {
  return bed::radiative_conductance(p.emissivity, t) * area;
}

}  // namespace powderbed::thermal
