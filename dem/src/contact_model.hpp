#pragma once
// The spreading engine's contact model, composed at compile time of one sub-model per role
// (docs/architecture.md "House style": chosen once at start, no per-contact test of a switch):
//
//   normal       HertzLaw | LinearLaw (normal_law.hpp), damped (effects.damping) or elastic
//   tangential   NoFriction | SlidingFriction (sliding_friction.hpp) | HistoryFriction
//                (tangential_history.hpp, Mindlin's k_t)      effects.friction, friction.model
//                | CentreSliding (sliding at the centres' velocity, particles that do not turn)
//   rolling      NoRolling | EpsdRolling (rolling_resistance.hpp)   material.rolling > 0
//
// Each sub-model's traits say what it needs: `rotation` (it reads the angular velocities or
// gives torques) and `history` (values it keeps per contact between steps); a tangential one
// also says whether it gives a force (`friction`). A contact's history
// is kContactHistory values, F_s then M_r, whichever sub-models use them: the layout of a
// spread's /restart group. choose_contact_model picks the instantiation for a scene.
#include <cstddef>

#include "normal_law.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/sliding_friction.hpp"

namespace powderbed::dem::detail {

constexpr std::size_t kContactHistory = 6;  // F_s (3 values), then M_r (3)

// What every contact of the run shares.
struct ContactCoefficients {
  double mu = 0;    // sliding friction mu_d
  double mu_r = 0;  // rolling friction
  double zeta = 0;  // damping ratio of every dashpot; 0 when the scene's damping is off
  double dt = 0;    // s, the step the history springs integrate over
  SlidingFrictionParams sliding;
};

// One contact's constants (per neighbour pair when it comes into contact; per particle for the
// walls), each the factor that multiplies a power of the overlap: for Hertz, F_n = a
// delta^{3/2} + b delta^{1/4} delta' (hertz_pair_constants), k_t = `shear` delta^{1/2} with
// shear = 8 G* sqrt(R*) (Mindlin), gamma_t = 2 zeta sqrt(m* k_t) = `shear_damping` delta^{1/4},
// k_r = `rolling` delta^{1/2} (rolling_stiffness of k_n = 2 E* sqrt(R* delta)) and C_r =
// 2 zeta sqrt(I_r k_r) = `rolling_damping` delta^{1/4}; for the linear law the same names hold
// the constants themselves (k_n, c, k_t = 2/7 k_n: the ratio that gives a sphere's tangential
// and normal oscillations one frequency, Schaefer, Dippel & Wolf 1996). Taken out once, so a
// contact needs two roots of the overlap, not eight. The dashpots' factors are 0 when the
// scene's damping is off (the normal law is then the elastic one).
struct ContactConstants {
  double reduced_radius = 0;
  double elastic = 0, damping = 0;
  double shear = 0, shear_damping = 0;
  double rolling = 0, rolling_damping = 0;
};

// What one contact gives: the force on i (the partner gets -f) and the torques on both.
struct ContactForce {
  double f[3], ti[3], tj[3];
};

// The moduli and masses a contact's constants are made from: E*, G* of the pair or of a
// particle against a wall, k_n of the linear law, R*, m* and I_r (rolling_resistance.hpp).
struct ContactPartners {
  double e_star = 0, g_star = 0, stiffness = 0;
  double reduced_radius = 0, reduced_mass = 0, rolling_inertia = 0;
};

// The contact of i with its partner (a particle or a wall) at overlap delta along the unit
// normal n from i towards the partner. dv = v_i - v_partner (a wall: the velocity of its
// surface at the contact point), w_i, w_j the angular velocities (a wall: 0), arm_i, arm_j the
// distances from the centres to the contact point. `h` is the contact's history
// (kContactHistory values); `update` advances it by one step.
using ContactFn = void (*)(const ContactCoefficients& m, const ContactConstants& k, double delta,
                           const double n[3], const double dv[3], const double wi[3],
                           const double wj[3], double arm_i, double arm_j, double* h, bool update,
                           ContactForce& out);
using ConstantsFn = ContactConstants (*)(const ContactCoefficients& m, const ContactPartners& p);
// The pair force over m contacts in contiguous arrays (contact_kernel.hpp), for a model whose
// contacts neither turn the particles nor keep a history: its pair pass is a batch that the
// compiler vectorises, not a call per contact.
using BatchFn = void (*)(std::size_t m, SlidingFrictionParams friction, const double* dx,
                         const double* dy, const double* dz, const double* reach,
                         const double* elastic, const double* damping, const double* dvx,
                         const double* dvy, const double* dvz, double* fx, double* fy, double* fz);

// The scene's contact model, instantiated once: its force and the maker of its constants.
struct ContactModel {
  ContactFn force = nullptr;
  ConstantsFn constants = nullptr;
  BatchFn batch = nullptr;  // set when the model can run batched (no rotation, no history)
  ContactCoefficients coefficients;
  bool rotation = false;  // a sub-model reads or changes the particles' rotation
  bool history = false;   // a sub-model keeps history between steps
};

// The model of `scene` (its law, damping, friction and friction model, rolling) for particles
// that turn (`rotating`) or not (friction then slides at the centres' velocity; the caller
// refuses history friction and rolling); the run sets coefficients.dt once it has chosen its
// step.
ContactModel choose_contact_model(const Scene& scene, bool rotating);

}  // namespace powderbed::dem::detail
