// The sub-models of contact_model.hpp and the one kernel that composes them.
#include "contact_model.hpp"

#include "contact_kernel.hpp"
#include "powderbed/bed/critical_damping.hpp"
#include "powderbed/dem/rolling_resistance.hpp"
#include "powderbed/dem/tangential_history.hpp"

namespace powderbed::dem::detail {
namespace {

inline void cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// The normal force: the law's, with its dashpot or without.
template <class LawT, bool Damped>
struct Normal {
  using Law = LawT;
  static constexpr bool damped = Damped;
  static double force(const ContactConstants& k, double delta, double rate) {
    if constexpr (Damped) {
      return Law::damped(k.elastic, k.damping, delta, rate);
    } else {
      return Law::elastic(k.elastic, delta);
    }
  }
};

// The powers of the overlap the springs carry (normal_law.hpp root, quarter) and the friction
// law's |F_n|: what the tangential and rolling sub-models read of the normal one.
struct Load {
  double root, quarter, normal;
};

struct NoFriction {
  static constexpr bool friction = false, rotation = false, history = false;
};

// Regularised Coulomb sliding at the contact point's tangential velocity.
struct SlidingFriction {
  static constexpr bool friction = true, rotation = true, history = false;
  static void force(const ContactCoefficients& m, const ContactConstants&, const Load& load,
                    const double[3], const double vt[3], double*, bool, double ft[3]) {
    sliding_friction_force(m.sliding, load.normal, vt[0], vt[1], vt[2], ft);
  }
};

// The same at the centres' relative tangential velocity, for particles that do not turn: the
// drop's friction ([GZ]'s model; its batch is contact_kernel.hpp's).
struct CentreSliding {
  static constexpr bool friction = true, rotation = false, history = false;
  static void force(const ContactCoefficients& m, const ContactConstants& k, const Load& load,
                    const double n[3], const double vt[3], double* h, bool update, double ft[3]) {
    SlidingFriction::force(m, k, load, n, vt, h, update, ft);
  }
};

// A Mindlin spring and dashpot capped at mu F_n, its elongation kept (F_s, h[0..2]).
struct HistoryFriction {
  static constexpr bool friction = true, rotation = true, history = true;
  static void force(const ContactCoefficients& m, const ContactConstants& k, const Load& load,
                    const double n[3], const double vt[3], double* h, bool update, double ft[3]) {
    rotate_onto_tangent_plane(h, n);
    const TangentialSpring spring{k.shear * load.root, k.shear_damping * load.quarter};
    tangential_history_force(spring, m.mu, load.normal, vt, m.dt, update, h, ft);
  }
};

struct NoRolling {
  static constexpr bool rotation = false, history = false;
};

// The elastic–plastic spring–dashpot rolling torque, its spring kept (M_r, h[3..5]).
struct EpsdRolling {
  static constexpr bool rotation = true, history = true;
  static void torque(const ContactCoefficients& m, const ContactConstants& k, const Load& load,
                     const double n[3], const double wr[3], double* h, bool update, double mr[3]) {
    const RollingSpring spring{k.rolling * load.root, k.rolling_damping * load.quarter};
    rolling_resistance_torque(spring, m.mu_r, k.reduced_radius, load.normal, n, wr, m.dt, update,
                              h + 3, mr);
  }
};

// contact_model.hpp ContactFn, composed.
template <class N, class T, class R>
void contact(const ContactCoefficients& m, const ContactConstants& k, double delta,
             const double n[3], const double dv[3], const double wi[3], const double wj[3],
             double arm_i, double arm_j, double* h, bool update, ContactForce& out) {
  const double rate = dv[0] * n[0] + dv[1] * n[1] + dv[2] * n[2];  // > 0 closing
  const double fn = N::force(k, delta, rate);
  for (int a = 0; a < 3; ++a) {
    out.f[a] = -fn * n[a];
    out.ti[a] = 0;
    out.tj[a] = 0;
  }
  if constexpr (!T::friction && !R::rotation) return;
  const double root = N::Law::root(delta);
  const Load load{root, N::Law::quarter(root), N::Law::normal_magnitude(fn)};
  if constexpr (T::rotation) {
    double w[3], spin[3];
    for (int a = 0; a < 3; ++a) w[a] = arm_i * wi[a] + arm_j * wj[a];
    cross(w, n, spin);
    double vt[3];
    const double vn = rate + spin[0] * n[0] + spin[1] * n[1] + spin[2] * n[2];
    for (int a = 0; a < 3; ++a) vt[a] = dv[a] + spin[a] - vn * n[a];
    double ft[3];
    T::force(m, k, load, n, vt, h, update, ft);
    double arm_n[3] = {arm_i * n[0], arm_i * n[1], arm_i * n[2]};
    cross(arm_n, ft, out.ti);
    for (int a = 0; a < 3; ++a) arm_n[a] = arm_j * n[a];
    cross(arm_n, ft, out.tj);
    for (int a = 0; a < 3; ++a) out.f[a] += ft[a];
  } else if constexpr (T::friction) {
    double vt[3], ft[3];
    for (int a = 0; a < 3; ++a) vt[a] = dv[a] - rate * n[a];
    T::force(m, k, load, n, vt, h, update, ft);
    for (int a = 0; a < 3; ++a) out.f[a] += ft[a];
  }
  if constexpr (R::rotation) {
    const double wr[3] = {wi[0] - wj[0], wi[1] - wj[1], wi[2] - wj[2]};
    double mr[3];
    R::torque(m, k, load, n, wr, h, update, mr);
    for (int a = 0; a < 3; ++a) {
      out.ti[a] += mr[a];
      out.tj[a] -= mr[a];
    }
  }
}

// contact_model.hpp ConstantsFn for a law.
template <class Law>
ContactConstants make_constants(const ContactCoefficients& m, const ContactPartners& p) {
  NormalLawParams law;
  law.hertz = {p.e_star, m.zeta};
  law.linear = {p.stiffness, m.zeta};
  const NormalConstants normal = Law::constants(law, p.reduced_radius, p.reduced_mass);
  ContactConstants c;
  c.reduced_radius = p.reduced_radius;
  c.elastic = normal.elastic;
  c.damping = normal.damping;
  c.shear = Law::shear_constant(p.g_star, p.reduced_radius, p.stiffness);
  c.shear_damping = bed::critical_damping(m.zeta, p.reduced_mass, c.shear);
  c.rolling = rolling_stiffness(m.mu_r, p.reduced_radius, Law::stiffness_constant(normal, p.stiffness));
  c.rolling_damping = bed::critical_damping(m.zeta, p.rolling_inertia, c.rolling);
  return c;
}

// The choice, one role at a time, down to the instantiation.
struct Choice {
  bool linear, damped, friction, history, rolling, rotating;
};

template <class N, class T, class R>
ContactModel instantiate() {
  ContactModel model;
  model.force = &contact<N, T, R>;
  model.constants = &make_constants<typename N::Law>;
  model.rotation = T::rotation || R::rotation;
  model.history = T::history || R::history;
  if constexpr (!(T::rotation || R::rotation || T::history || R::history)) {
    constexpr unsigned effects = (N::damped ? kDamping : 0u) | (T::friction ? kFriction : 0u);
    model.batch = &contact_kernel<effects, typename N::Law>;
  }
  return model;
}

template <class N, class T>
ContactModel with_rolling(const Choice& c) {
  return c.rolling ? instantiate<N, T, EpsdRolling>() : instantiate<N, T, NoRolling>();
}

template <class N>
ContactModel with_tangential(const Choice& c) {
  if (!c.friction) return with_rolling<N, NoFriction>(c);
  if (!c.rotating) return with_rolling<N, CentreSliding>(c);
  return c.history ? with_rolling<N, HistoryFriction>(c) : with_rolling<N, SlidingFriction>(c);
}

template <class Law>
ContactModel with_damping(const Choice& c) {
  return c.damped ? with_tangential<Normal<Law, true>>(c) : with_tangential<Normal<Law, false>>(c);
}

}  // namespace

ContactModel choose_contact_model(const Scene& scene, bool rotating) {
  const Choice c{scene.law == ContactLaw::linear, scene.has(kDamping),
                 scene.has(kFriction) && scene.material.friction > 0,
                 scene.friction_model == FrictionModel::history, scene.material.rolling > 0, rotating};
  ContactModel model = c.linear ? with_damping<LinearLaw>(c) : with_damping<HertzLaw>(c);
  ContactCoefficients& k = model.coefficients;
  k.mu = scene.material.friction;
  k.mu_r = scene.material.rolling;
  k.zeta = c.damped ? scene.material.damping : 0.0;
  k.sliding.coefficient = k.mu;
  return model;
}

}  // namespace powderbed::dem::detail
