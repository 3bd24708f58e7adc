// The finite-difference substrate of docs/physics.md §5 against analytic conduction: with every effect
// off and a bed without particles the solver is pure substrate conduction with constant k, rho,
// c (the properties at T0), Dirichlet sides and bottom and a zero-flux top face.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "powderbed/thermal/solver.hpp"
#include "sinter_beds.hpp"

using namespace powderbed;
using std::numbers::pi;

namespace {

constexpr double kLx = 80e-6, kLy = 80e-6, kDepth = 80e-6;

// Sets every node, Dirichlet ones included, to f(x, y, z).
template <class F>
void set_field(thermal::Sinter& sinter, F f) {
  const auto& g = sinter.grid();
  for (std::size_t k = 0; k < g.nz; ++k)
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i)
        sinter.set_substrate_temperature(g.index(i, j, k), f(g.x(i), g.y(j), g.z(k)));
}

// Thermal diffusivity k / (rho c) of the constant material at T0.
double diffusivity(const thermal::Sinter& sinter, double t0) {
  const auto& m = sinter.material();
  return m.conductivity(t0) / (m.density(t0) * m.apparent_heat_capacity(t0));
}

}  // namespace

// T = 400 + G (x - x0) is harmonic with zero z-gradient: the 7-point stencil maps it to zero
// exactly and the top face's zero flux is satisfied, so it is a discrete steady state.
TEST(Substrate, LinearProfileIsSteady) {
  const bed::Bed bed = test::empty_bed(kLx, kLy, 40e-6);
  for (const auto integrator :
       {thermal::Integrator::explicit_euler, thermal::Integrator::implicit_euler}) {
    thermal::SinterScene scene = test::small_scene(0, {9, 7, 6}, kDepth);
    scene.integrator = integrator;
    scene.t_end = 5e-4;  // ~6 decay times of the slowest mode (7.7e-5 s): ~80 explicit steps
    if (integrator == thermal::Integrator::implicit_euler) scene.dt = 1e-5;
    thermal::Sinter sinter(bed, scene, test::table_316l());
    const double gradient = 1e6;  // K/m: 80 K across the box
    const auto profile = [&](double x, double, double) { return 400 + gradient * x; };
    set_field(sinter, profile);
    const auto result = sinter.run(nullptr, 0, nullptr);
    EXPECT_GT(result.steps, 10u);
    // Round-off only: each step adds differences of ~500 K values (1e-13 K) and the enthalpy
    // table of a constant capacity inverts a linear function exactly; 1e-9 K leaves a margin of
    // 1e2 over the steps and is far below any stencil or boundary error (~K).
    EXPECT_LT(test::max_free_node_error(sinter, profile), 1e-9)
        << (integrator == thermal::Integrator::explicit_euler ? "explicit" : "implicit");
  }
}

// From a uniform start the free nodes relax to the linear profile the Dirichlet nodes impose.
// Backward Euler with large steps reaches the steady state in a few hundred steps.
TEST(Substrate, ImplicitRelaxesToLinearProfile) {
  const bed::Bed bed = test::empty_bed(kLx, kLy, 40e-6);
  thermal::SinterScene scene = test::small_scene(0, {9, 7, 6}, kDepth);
  scene.integrator = thermal::Integrator::implicit_euler;
  scene.dt = 1e-4;  // 1.3 times the slowest mode's decay time 1/(kappa k^2) ~ 7.7e-5 s
  scene.t_end = 3e-2;
  thermal::Sinter sinter(bed, scene, test::table_316l());
  const double gradient = 1e6;
  const auto profile = [&](double x, double, double) { return 400 + gradient * x; };
  set_field(sinter, profile);
  const auto& g = sinter.grid();
  for (std::size_t c = 0; c < g.size(); ++c)
    if (!g.fixed(c % g.nx, (c / g.nx) % g.ny, c / (g.nx * g.ny)))
      sinter.set_substrate_temperature(c, 363.0);
  sinter.run(nullptr, 0, nullptr);
  // Each backward-Euler step damps the slowest error mode by 1 / (1 + lambda dt) ~ 1/2.3; 300
  // steps leave 2.3^-300 of the initial ~80 K: nothing. The conjugate-gradient tolerance
  // (1e-12 relative residual on ~1e3 K-scale right-hand sides) bounds what remains; 1e-8 K
  // is far above it and far below any discretisation error.
  EXPECT_LT(test::max_free_node_error(sinter, profile), 1e-8);
}

// T - T0 = A sin(pi x/Lx) sin(pi y/Ly) sin(pi (z - z_bottom)/(2 Lz)) vanishes at the Dirichlet
// sides and bottom and has zero flux at the top; it decays as exp(-kappa k^2 t). The discrete
// operator has the same eigenvector (the half-cell top is the mirror node of a symmetric
// extension) with eigenvalue lambda_h = lambda (1 - O(dx^2)): second order in space.
TEST(Substrate, FourierModeDecaysWithSecondOrderError) {
  const bed::Bed bed = test::empty_bed(kLx, kLy, 40e-6);
  const double t0 = 363, amplitude = 100;
  const double k2 = pi * pi * (1 / (kLx * kLx) + 1 / (kLy * kLy) + 0.25 / (kDepth * kDepth));
  std::vector<double> errors;
  for (const std::size_t n : {5u, 9u, 17u}) {
    thermal::SinterScene scene = test::small_scene(0, {n, n, n}, kDepth);
    // Forward Euler's error is O(dt) and dt is a fixed fraction (1/20) of the stable bound,
    // itself proportional to dx^2: so it is O(dx^2) too, and at 1/20 of the bound it is about
    // 1/20 of the spatial error, leaving the ratio of the total close to 4.
    double bound = 0, kappa = 0;
    {
      thermal::Sinter probe(bed, scene, test::table_316l());
      bound = probe.stable_steps().grid;
      kappa = diffusivity(probe, t0);
    }
    scene.dt = bound / 20;
    scene.t_end = 1 / (kappa * k2);  // one e-folding time
    thermal::Sinter sinter(bed, scene, test::table_316l());
    const double zb = -kDepth;
    const auto mode = [&](double x, double y, double z) {
      return std::sin(pi * x / kLx) * std::sin(pi * y / kLy) * std::sin(pi * (z - zb) / (2 * kDepth));
    };
    set_field(sinter, [&](double x, double y, double z) { return t0 + amplitude * mode(x, y, z); });
    sinter.run(nullptr, 0, nullptr);
    const double decay = std::exp(-kappa * k2 * scene.t_end);
    errors.push_back(test::max_free_node_error(sinter, [&](double x, double y, double z) {
      return t0 + amplitude * decay * mode(x, y, z);
    }));
  }
  // The leading error is A e^-1 (lambda - lambda_h) t = A e^-1 sum_d (k_d^2 / k^2) theta_d^2 / 12
  // (theta = pi dx / Lx, pi dz / (2 Lz)): 1.7 K at 5 nodes, 0.43 K at 9, 0.108 K at 17 (the
  // solver gives 1.54, 0.381, 0.095). Halving dx divides it by 4; the O(dx^4) remainder moves
  // the ratio by a few percent (measured 4.03, 4.01), so 3.3–4.7 accepts second order and
  // rejects first (2) or third (8).
  for (std::size_t m = 0; m + 1 < errors.size(); ++m) {
    const double ratio = errors[m] / errors[m + 1];
    EXPECT_GT(ratio, 3.3) << "grid " << m << ": errors " << errors[m] << ", " << errors[m + 1];
    EXPECT_LT(ratio, 4.7) << "grid " << m << ": errors " << errors[m] << ", " << errors[m + 1];
  }
  // The finest grid's error against that estimate: 0.108 K from space less 0.009 K from the
  // time step (forward Euler decays faster, A e^-1 lambda t lambda dt / 2) is 0.099 K; 0.11 K
  // allows 10 % for the higher-order terms. A wrong stencil, face area or top boundary gives
  // errors of kelvins.
  EXPECT_LT(errors.back(), 0.11);
}
