// Backward Euler for stiff scenes (SPEC.md §5 "Time integration", issue: "an implicit option"):
// particles and free substrate nodes are solved together, A T* = b, with capacities and
// conductivities of the start of the step and radiation linearised about it
// (A = C/dt + conductance Laplacian; symmetric positive definite, so conjugate gradients with a
// diagonal preconditioner). The enthalpies are then advanced by the fluxes evaluated at T*
// through the same booked flux routines as the explicit step, so energy stays exactly
// conserved whatever dt is; T* is only the temperature at which the fluxes are evaluated.
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <cmath>
#include <vector>

#include "powderbed/bed/errors.hpp"
#include "powderbed/thermal/beer_lambert_laser.hpp"
#include "powderbed/thermal/surface_losses.hpp"
#include "solver_state.hpp"

namespace powderbed::thermal {

namespace {

using Triplet = Eigen::Triplet<double>;

struct System {
  std::vector<Triplet> entries;
  Eigen::VectorXd rhs, guess;
};

}  // namespace

void implicit_step(Sinter::State& s, double dt) {
  const SubstrateGeometry& g = s.g;
  const std::size_t n = s.x.size();
  const bool variable = s.scene.has(kVariableProperties);
  const auto k_of = [&](double t) { return variable ? s.conductivity(t) : s.k_fixed; };

  // Unknowns: particles first, then free nodes in index order.
  std::vector<std::ptrdiff_t> unknown(g.size(), -1);
  std::ptrdiff_t count = static_cast<std::ptrdiff_t>(n);
  for (std::size_t k = 1; k < g.nz; ++k)
    for (std::size_t j = 1; j + 1 < g.ny; ++j)
      for (std::size_t i = 1; i + 1 < g.nx; ++i) unknown[g.index(i, j, k)] = count++;

  System sys;
  sys.rhs = Eigen::VectorXd::Zero(count);
  sys.guess.resize(count);
  sys.entries.reserve(static_cast<std::size_t>(count) * 7 + s.net.pairs.size() * 4 +
                      s.net.substrate.size() * 25);
  const auto add = [&](std::ptrdiff_t r, std::ptrdiff_t c, double v) {
    sys.entries.emplace_back(r, c, v);
  };
  // A coupling of conductance G between unknown-or-fixed a and b.
  const auto couple = [&](std::ptrdiff_t a, double t_a, std::ptrdiff_t b, double t_b, double G) {
    if (a >= 0) {
      add(a, a, G);
      if (b >= 0) add(a, b, -G);
      else sys.rhs[a] += G * t_b;
    }
    if (b >= 0) {
      add(b, b, G);
      if (a >= 0) add(b, a, -G);
      else sys.rhs[b] += G * t_a;
    }
  };

  const double t = s.time;
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = static_cast<std::ptrdiff_t>(i);
    const double capacity = s.mass[i] * s.per_kg.capacity(s.temperature[i]) / dt;
    add(r, r, capacity);
    sys.rhs[r] += capacity * s.temperature[i];
    sys.guess[r] = s.temperature[i];
  }
  if (s.scene.has(kConduction)) {
    for (const auto& p : s.net.pairs) {
      if (s.gone[p.i] || s.gone[p.j]) continue;
      const double G = 0.5 * (k_of(s.temperature[p.i]) + k_of(s.temperature[p.j])) * p.shape;
      couple(p.i, s.temperature[p.i], p.j, s.temperature[p.j], G);
    }
  }
  if (s.scene.has(kSubstrateContact)) {
    for (const auto& c : s.net.substrate) {
      if (s.gone[c.particle]) continue;
      double ts = 0;
      for (int w = 0; w < 4; ++w) ts += c.stencil.weight[w] * s.node_temperature[c.stencil.node[w]];
      const double G = 0.5 * (k_of(s.temperature[c.particle]) + k_of(ts)) * c.shape;
      // Q = G (Σ w_l T_l - T_i) into the particle, w_k Q out of node k: symmetric in (i, nodes).
      const auto pi = static_cast<std::ptrdiff_t>(c.particle);
      add(pi, pi, G);
      for (int a = 0; a < 4; ++a) {
        const double wa = c.stencil.weight[a];
        const std::ptrdiff_t ua = unknown[c.stencil.node[a]];
        const double ta = s.node_temperature[c.stencil.node[a]];
        if (ua >= 0) add(pi, ua, -G * wa);
        else sys.rhs[pi] += G * wa * ta;
        if (ua < 0) continue;
        add(ua, pi, -G * wa);
        for (int b = 0; b < 4; ++b) {
          const double wb = c.stencil.weight[b];
          const std::ptrdiff_t ub = unknown[c.stencil.node[b]];
          if (ub >= 0) add(ua, ub, G * wa * wb);
          else sys.rhs[ua] -= G * wa * wb * s.node_temperature[c.stencil.node[b]];
        }
      }
    }
  }
  for (const auto i : s.exposed) {
    if (s.gone[i]) continue;
    const auto r = static_cast<std::ptrdiff_t>(i);
    if (s.scene.has(kConvection)) {
      add(r, r, s.environment.convection * s.area[i]);
      sys.rhs[r] += s.environment.convection * s.area[i] * s.environment.environment;
    }
    if (s.scene.has(kRadiation)) {
      const double G = radiation_conductance(s.environment, s.temperature[i], s.area[i]);
      add(r, r, G);
      sys.rhs[r] += radiation_gain(s.environment, s.temperature[i], s.area[i]) +
                    G * s.temperature[i];
    }
  }
  if (s.scene.has(kLaser)) {
    const double xl = laser_x(s, t), w2 = s.laser.spot_radius * s.laser.spot_radius;
    for (std::size_t i = 0; i < n; ++i) {
      if (s.gone[i]) continue;
      const double dx = s.x[i] - xl, dy = s.y[i] - s.laser_y;
      sys.rhs[static_cast<std::ptrdiff_t>(i)] +=
          s.laser_factor[i] * peak_intensity(s.laser) * std::exp(-2 * (dx * dx + dy * dy) / w2);
    }
  }
  const double gx = g.dy * g.dz / g.dx, gy = g.dx * g.dz / g.dy, gz = g.dx * g.dy / g.dz;
  const double xl = laser_x(s, t);
  for (std::size_t k = 1; k < g.nz; ++k) {
    const double half = k + 1 == g.nz ? 0.5 : 1.0;
    for (std::size_t j = 1; j + 1 < g.ny; ++j) {
      for (std::size_t i = 1; i + 1 < g.nx; ++i) {
        const std::size_t c = g.index(i, j, k);
        const std::ptrdiff_t u = unknown[c];
        const double tc = s.node_temperature[c];
        const double capacity = g.volume(k) * s.per_m3.capacity(tc) / dt;
        add(u, u, capacity);
        sys.rhs[u] += capacity * tc;
        sys.guess[u] = tc;
        // Faces towards +x, +y, +z once each (and towards fixed nodes on the -x/-y/-z side).
        const auto face = [&](std::size_t nb, double shape) {
          const double G = 0.5 * (s.node_k[c] + s.node_k[nb]) * shape;
          couple(u, tc, unknown[nb], s.node_temperature[nb], G);
        };
        face(c + 1, gx * half);
        face(c + g.nx, gy * half);
        if (k + 1 < g.nz) face(c + g.nx * g.ny, gz);
        if (i == 1) face(c - 1, gx * half);
        if (j == 1) face(c - g.nx, gy * half);
        if (k == 1) face(c - g.nx * g.ny, gz);
        if (k + 1 == g.nz && s.scene.has(kLaserSubstrate)) {
          const double dx = g.x(i) - xl, dy = g.y(j) - s.laser_y;
          sys.rhs[u] += absorbed_flux(s.laser, dx * dx + dy * dy, 0.0) *
                        s.transmission[i + g.nx * j] * g.dx * g.dy;
        }
      }
    }
  }
  // The `couple` lambda adds a fixed node's side only once; entries towards fixed nodes on the
  // +x/+y sides were handled by face(c + 1 ...) when that neighbour is fixed.

  Eigen::SparseMatrix<double> a(count, count);
  a.setFromTriplets(sys.entries.begin(), sys.entries.end());
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
  cg.setTolerance(1e-12);
  cg.compute(a);
  const Eigen::VectorXd solution = cg.solveWithGuess(sys.rhs, sys.guess);
  if (cg.info() != Eigen::Success) {
    throw NumericalError("implicit step " + std::to_string(s.step) +
                         ": conjugate gradients did not converge (" +
                         std::to_string(cg.iterations()) + " iterations)");
  }
  s.implicit_iterations += static_cast<std::size_t>(cg.iterations());

  // Fluxes at T*: set the temperatures and let the booked explicit routines advance the
  // enthalpies with one step of dt (substeps is 1 for the implicit integrator).
  for (std::size_t i = 0; i < n; ++i)
    if (!s.gone[i]) s.temperature[i] = solution[static_cast<std::ptrdiff_t>(i)];
  for (std::size_t c = 0; c < g.size(); ++c)
    if (unknown[c] >= 0) s.node_temperature[c] = solution[unknown[c]];
  explicit_step(s, dt);
}

}  // namespace powderbed::thermal
