#pragma once
// The scene's normal contact law (scene.hpp ContactLaw) behind one compile-time interface, so
// that the force loop is instantiated once per law (docs/architecture.md "House style": composed at start,
// no per-contact test of the law). Each adaptor forwards to its kernel header.
#include <cmath>

#include "powderbed/dem/hertz_normal.hpp"
#include "powderbed/dem/linear_normal.hpp"
#include "powderbed/dem/mindlin_tangential.hpp"

namespace powderbed::dem::detail {

// A contact's two constants, tabulated at a neighbour-list build: Hertz a, b
// (hertz_pair_constants); linear k_n, c (linear_pair_constants).
struct NormalConstants {
  double elastic = 0;
  double damping = 0;
};

// The parameters of both laws for one kind of contact (particle–particle or particle–wall);
// the law in use reads its own.
struct NormalLawParams {
  HertzNormalParams hertz;
  LinearNormalParams linear;
};

struct HertzLaw {
  static NormalConstants constants(const NormalLawParams& p, double reduced_radius,
                                   double reduced_mass) {
    const HertzPairConstants c = hertz_pair_constants(p.hertz, reduced_radius, reduced_mass);
    return {c.elastic, c.damping};
  }
  static double elastic(double a, double delta) {
    return hertz_elastic_force(HertzPairConstants{a, 0.0}, delta);
  }
  static double damped(double a, double b, double delta, double rate) {
    return hertz_damped_force(HertzPairConstants{a, b}, delta, rate);
  }
  // |F_n| of the friction law: the Hertz force is clamped, never negative.
  static double normal_magnitude(double force) { return force; }
  // The powers of the overlap that the tangential and rolling springs and dashpots carry
  // (contact_model.hpp ContactConstants): delta^{1/2} and delta^{1/4}.
  static double root(double delta) { return std::sqrt(delta); }
  static double quarter(double root) { return std::sqrt(root); }
  // Mindlin's k_t / delta^{1/2} = 8 G* sqrt(R*) (mindlin_tangential.hpp).
  static double shear_constant(double g_star, double reduced_radius, double) {
    return mindlin_stiffness_constant(g_star, reduced_radius);
  }
  // k_n / delta^{1/2} = 2 E* sqrt(R*), 3/2 of the constant a = 4/3 E* sqrt(R*).
  static double stiffness_constant(const NormalConstants& c, double) { return 1.5 * c.elastic; }
};

struct LinearLaw {
  static NormalConstants constants(const NormalLawParams& p, double, double reduced_mass) {
    const LinearPairConstants c = linear_pair_constants(p.linear, reduced_mass);
    return {c.stiffness, c.damping};
  }
  static double elastic(double k, double delta) {
    return linear_elastic_force(LinearPairConstants{k, 0.0}, delta);
  }
  static double damped(double k, double c, double delta, double rate) {
    return linear_damped_force(LinearPairConstants{k, c}, delta, rate);
  }
  // The unclamped dashpot may pull at the end of a contact; friction takes |F_n| (as MFiX).
  static double normal_magnitude(double force) { return std::abs(force); }
  // Constant springs: the overlap's powers are 1.
  static double root(double) { return 1.0; }
  static double quarter(double) { return 1.0; }
  // k_t = 2/7 k_n: the ratio that gives a sphere's tangential and normal oscillations one
  // frequency (Schaefer, Dippel & Wolf 1996).
  static double shear_constant(double, double, double stiffness) { return 2.0 / 7.0 * stiffness; }
  static double stiffness_constant(const NormalConstants&, double stiffness) { return stiffness; }
};

}  // namespace powderbed::dem::detail
