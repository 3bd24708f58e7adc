#pragma once
// Grey-body radiative exchange, q = sigma G (T_a^4 - T_b^4), and its slope dq/dT_a =
// 4 sigma G T_a^3, with G the exchange factor: eps per unit area for an exposed particle and its
// surroundings (docs/physics.md §5, thermal's surface_losses.hpp), the radiative conductance
// (m^2) of a view-factor link or of the walls' direct exchange (docs/physics.md §6, keff).
// Here once, in bed/, because keff does not depend on thermal.
#include "powderbed/bed/contact_geometry.hpp"  // kStefanBoltzmann

namespace powderbed::bed {

// Heat from a at T_a to b at T_b, W (W/m^2 for G = eps).
inline double radiative_exchange(double factor, double t_a, double t_b) {
  const double a2 = t_a * t_a, b2 = t_b * t_b;
  return kStefanBoltzmann * factor * (a2 * a2 - b2 * b2);
}

// d(radiative_exchange)/dT_a = 4 sigma G T_a^3: the conductance that bounds a stable explicit
// step and linearises an implicit or Newton one.
inline double radiative_conductance(double factor, double t_a) {
  return 4 * kStefanBoltzmann * factor * t_a * t_a * t_a;
}

// radiative_exchange / (T_a - T_b) = sigma G (T_a^2 + T_b^2)(T_a + T_b): the secant
// conductance between two temperatures, which makes the exchange a linear link (keff's first,
// linear solve between the walls' temperatures).
inline double radiative_secant(double factor, double t_a, double t_b) {
  return kStefanBoltzmann * factor * (t_a * t_a + t_b * t_b) * (t_a + t_b);
}

}  // namespace powderbed::bed
