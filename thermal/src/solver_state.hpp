#pragma once
// The solver's state (private to libthermal): what setup computes once and the steps update.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "powderbed/thermal/beer_lambert_laser.hpp"
#include "powderbed/thermal/solver.hpp"
#include "powderbed/thermal/surface_losses.hpp"

namespace powderbed::thermal {

// The implicit integrator's matrix and solver, built on its first step (implicit_step.cpp).
struct ImplicitSystem;
struct ImplicitSystemDeleter {
  void operator()(ImplicitSystem* p) const;
};

struct Sinter::State {
  SinterScene scene;
  Material material;
  EnthalpyCurve per_kg, per_m3;  // particles: h (J/kg); nodes: e (J/m^3)
  UniformTable conductivity;
  UniformTable capacity_per_kg, capacity_per_m3;  // c(T) and rho c(T) for the implicit matrix
  SubstrateGeometry g;
  BedSurface surface;
  ConductionNetwork net;
  LaserParams laser{};
  SurfaceParams environment{};
  double beta = 0, layer_height = 0, laser_y = 0, start_x = 0, t_end = 0;
  double vaporised_temperature = 0;  // T_v + ΔT/2: beyond it a particle has left the bed

  // Particles (structure of arrays).
  std::vector<double> x, y, z, radius, mass, area, laser_factor;
  std::vector<double> h, temperature, peak, heat;  // heat: W, scratch of one step
  std::vector<std::uint8_t> gone;                  // vaporised: out of the network
  std::vector<std::uint32_t> exposed;

  // Substrate nodes.
  std::vector<double> e, node_temperature, node_k;
  std::vector<double> transmission;  // per top-face node (i + nx j): laser fraction that arrives
  std::vector<double> node_peak;  // peak T on the planes update_peak_planes keeps, else T0
  double node_max = 0;            // highest node temperature so far
  struct Source {
    std::size_t node;
    double energy;  // J over the current grid step
  };
  std::vector<Source> sources;  // laser and particle contacts into free top nodes
  std::vector<double> plane_sums;  // scratch of the boundary-flux sum, one per z plane
  double k_fixed = 0;  // conductivity of the Dirichlet nodes (at T0)

  StableSteps stable;
  double dt = 0;
  std::size_t substeps = 1;
  EnergyLedger ledger;
  double time = 0;
  std::uint64_t step = 0, particle_steps = 0;
  std::size_t implicit_iterations = 0;
  std::unique_ptr<ImplicitSystem, ImplicitSystemDeleter> implicit;

  State(const SinterScene& scene, Material material);
};

// One grid step of forward Euler (explicit_step.cpp): particles subcycle, then the grid.
void explicit_step(Sinter::State& s, double dt);
// One backward-Euler step of particles and free nodes together (implicit_step.cpp).
void implicit_step(Sinter::State& s, double dt);
// Laser centre at time t.
inline double laser_x(const Sinter::State& s, double t) { return s.start_x + s.scene.speed * t; }
// Throws NumericalError if any temperature is non-finite, naming the particle or node; the
// substrate nodes only when `grid` is set (the particles are few, the grid is not).
void check_finite(const Sinter::State& s, bool grid = true);

}  // namespace powderbed::thermal
