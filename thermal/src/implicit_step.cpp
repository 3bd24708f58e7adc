// Backward Euler for stiff scenes (docs/physics.md §5 "Time integration", issue: "an implicit option"):
// particles and free substrate nodes are solved together, A T* = b, with capacities and
// conductivities of the start of the step and radiation linearised about it
// (A = C/dt + conductance Laplacian; symmetric positive definite, so conjugate gradients with a
// diagonal preconditioner). The enthalpies are then advanced by the fluxes evaluated at T*
// through the same booked flux routines as the explicit step, so energy stays exactly
// conserved whatever dt is; T* is only the temperature at which the fluxes are evaluated.
//
// The assembly is composed from the scene's effects once, when the system is built
// (effect_kernels.hpp): the effects that change the work per contact, exposed particle or top
// node are template arguments of its loops; those that switch a whole loop on or off are tested
// once, before it.
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <utility>
#include <vector>

#include "effect_kernels.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/thermal/beer_lambert_laser.hpp"
#include "powderbed/thermal/contact_conduction.hpp"
#include "powderbed/thermal/surface_losses.hpp"
#include "lit_particles.hpp"
#include "solver_state.hpp"

namespace powderbed::thermal {

namespace {

using Triplet = Eigen::Triplet<double>;

// The matrix pattern is the same every step (every coupling is emitted, with conductance 0 once a
// particle has vaporised), so the first step records triplets and builds the compressed matrix,
// and later steps add each value straight into its slot: assembly stays O(nonzeros).
struct Assembler {
  bool first = true;
  std::vector<Triplet> triplets;
  std::vector<std::ptrdiff_t> slot;  // position in the matrix's value array per emitted entry
  std::size_t next = 0;
  double* values = nullptr;

  void add(std::ptrdiff_t r, std::ptrdiff_t c, double v) {
    if (first) triplets.emplace_back(r, c, v);
    else values[slot[next]] += v;
    ++next;
  }
};

}  // namespace

struct ImplicitSystem {
  std::vector<std::ptrdiff_t> unknown;  // per node: index of its unknown, -1 when fixed
  std::ptrdiff_t count = 0;
  Eigen::SparseMatrix<double> matrix;
  Assembler assembler;
  Eigen::VectorXd rhs, guess, solution;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
  // The assembly of A and b for the scene's effects, chosen when the system is built.
  void (*assemble)(Sinter::State&, ImplicitSystem&, double dt) = nullptr;

  void add(std::ptrdiff_t r, std::ptrdiff_t c, double v) { assembler.add(r, c, v); }
  // A coupling of conductance G between unknown-or-fixed a and b (fixed: -1, at t_a or t_b).
  void couple(std::ptrdiff_t a, double t_a, std::ptrdiff_t b, double t_b, double G) {
    if (a >= 0) {
      add(a, a, G);
      if (b >= 0) add(a, b, -G);
      else rhs[a] += G * t_b;
    }
    if (b >= 0) {
      add(b, b, G);
      if (a >= 0) add(b, a, -G);
      else rhs[b] += G * t_a;
    }
  }
};

void ImplicitSystemDeleter::operator()(ImplicitSystem* p) const { delete p; }

namespace {

// The effects that change the assembly's work per element: conductivities that follow
// temperature in every contact conductance, the surface losses of each exposed particle, the
// laser on each top node.
constexpr std::array kAssemblyEffects{kVariableProperties, kConvection, kRadiation,
                                      kLaserSubstrate};

void add_particle_capacities(const Sinter::State& s, ImplicitSystem& sys, double dt) {
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const auto r = static_cast<std::ptrdiff_t>(i);
    const double capacity = s.mass[i] * s.capacity_per_kg(s.temperature[i]) / dt;
    sys.add(r, r, capacity);
    sys.rhs[r] += capacity * s.temperature[i];
    sys.guess[r] = s.temperature[i];
  }
}

template <bool Variable>
void add_pair_conduction(const Sinter::State& s, ImplicitSystem& sys) {
  for (const auto& p : s.net.pairs) {
    const bool off = s.gone[p.i] || s.gone[p.j];
    const double G = off ? 0.0
                         : path_conductance(conductivity_at<Variable>(s, s.temperature[p.i]),
                                            conductivity_at<Variable>(s, s.temperature[p.j]),
                                            p.shape);
    sys.couple(p.i, s.temperature[p.i], p.j, s.temperature[p.j], G);
  }
}

// Weight w of a contact conducts to each of the four top nodes around it, by that node's own
// difference (as the explicit step): couplings of the particle to each node alone, so the
// matrix stays an M-matrix and no node is driven below its neighbours.
template <bool Variable>
void add_substrate_contacts(const Sinter::State& s, ImplicitSystem& sys) {
  for (const auto& c : s.net.substrate) {
    const double ti = s.temperature[c.particle];
    for (int a = 0; a < 4; ++a) {
      const std::size_t node = top_node(s, c.stencil.column[a]);
      const double ta = s.node_temperature[node];
      const double G = s.gone[c.particle]
                           ? 0.0
                           : c.stencil.weight[a] *
                                 path_conductance(conductivity_at<Variable>(s, ti),
                                                  conductivity_at<Variable>(s, ta), c.shape);
      sys.couple(static_cast<std::ptrdiff_t>(c.particle), ti, sys.unknown[node], ta, G);
    }
  }
}

// Convection and radiation (linearised about T) of the exposed particles.
template <bool Convection, bool Radiation>
void add_surface_losses(const Sinter::State& s, ImplicitSystem& sys) {
  for (const auto i : s.exposed) {
    const auto r = static_cast<std::ptrdiff_t>(i);
    const double on = s.gone[i] ? 0.0 : 1.0;
    if constexpr (Convection) {
      sys.add(r, r, on * s.environment.convection * s.area[i]);
      sys.rhs[r] += on * s.environment.convection * s.area[i] * s.environment.environment;
    }
    if constexpr (Radiation) {
      const double G = on * radiation_conductance(s.environment, s.temperature[i], s.area[i]);
      sys.add(r, r, G);
      sys.rhs[r] += on * radiation_gain(s.environment, s.temperature[i], s.area[i]) +
                    G * s.temperature[i];
    }
  }
}

void add_particle_laser(const Sinter::State& s, ImplicitSystem& sys, const LaserParams& laser,
                        const ScanSchedule::Beam& beam) {
  for_each_lit_particle(s, beam.x, beam.y, peak_intensity(laser), [&](std::size_t i, double f) {
    sys.rhs[static_cast<std::ptrdiff_t>(i)] += f;
  });
}

// The free nodes: capacities, the faces towards +x, +y, +z once each (and towards fixed nodes on
// the -x/-y/-z side), and with LaserSubstrate the beam that reaches the top nodes.
template <bool LaserSubstrate>
void add_grid(const Sinter::State& s, ImplicitSystem& sys, double dt, const LaserParams& laser,
              const ScanSchedule::Beam& beam) {
  const SubstrateGeometry& g = s.g;
  const std::vector<std::ptrdiff_t>& unknown = sys.unknown;
  const double gx = g.dy * g.dz / g.dx, gy = g.dx * g.dz / g.dy, gz = g.dx * g.dy / g.dz;
  for (std::size_t k = 1; k < g.nz; ++k) {
    const double half = k + 1 == g.nz ? 0.5 : 1.0;
    for (std::size_t j = 1; j + 1 < g.ny; ++j) {
      for (std::size_t i = 1; i + 1 < g.nx; ++i) {
        const std::size_t c = g.index(i, j, k);
        const std::ptrdiff_t u = unknown[c];
        const double tc = s.node_temperature[c];
        const double capacity = g.cell_volume() * half * s.capacity_per_m3(tc) / dt;
        sys.add(u, u, capacity);
        sys.rhs[u] += capacity * tc;
        sys.guess[u] = tc;
        const auto face = [&](std::size_t nb, double shape) {
          const double G = path_conductance(s.node_k[c], s.node_k[nb], shape);
          sys.couple(u, tc, unknown[nb], s.node_temperature[nb], G);
        };
        face(c + 1, gx * half);
        face(c + g.nx, gy * half);
        if (k + 1 < g.nz) face(c + g.nx * g.ny, gz);
        if (i == 1) face(c - 1, gx * half);
        if (j == 1) face(c - g.nx, gy * half);
        if (k == 1) face(c - g.nx * g.ny, gz);
        if constexpr (LaserSubstrate) {
          if (k + 1 == g.nz) {
            const double dx = g.x(i) - beam.x, dy = g.y(j) - beam.y;
            sys.rhs[u] += node_laser_power(laser, dx * dx + dy * dy, s.transmission[i + g.nx * j],
                                           g.dx, g.dy);
          }
        }
      }
    }
  }
}

// A and b of the step from t: every term, in the order the matrix pattern was recorded.
template <unsigned Effects>
void assemble(Sinter::State& s, ImplicitSystem& sys, double dt) {
  constexpr bool variable = (Effects & kVariableProperties) != 0;
  add_particle_capacities(s, sys, dt);
  if (s.scene.has(kConduction)) add_pair_conduction<variable>(s, sys);
  if (s.scene.has(kSubstrateContact)) add_substrate_contacts<variable>(s, sys);
  add_surface_losses<(Effects & kConvection) != 0, (Effects & kRadiation) != 0>(s, sys);
  const ScanSchedule::Beam beam = beam_at(s, s.time);
  const LaserParams laser = laser_with_power(s, beam.power);  // power 0 while the laser is off
  if (s.scene.has(kLaser)) add_particle_laser(s, sys, laser, beam);
  add_grid<(Effects & kLaserSubstrate) != 0>(s, sys, dt, laser, beam);
}

using AssemblyKernel = void (*)(Sinter::State&, ImplicitSystem&, double);

template <std::size_t... I>
constexpr std::array<AssemblyKernel, sizeof...(I)> assembly_kernels(std::index_sequence<I...>) {
  return {&assemble<effects_of_index(kAssemblyEffects, I)>...};
}
constexpr auto kAssemblyKernels =
    assembly_kernels(std::make_index_sequence<std::size_t{1} << kAssemblyEffects.size()>{});

// The unknowns (particles first, then the free nodes in index order) and the scene's assembly.
std::unique_ptr<ImplicitSystem, ImplicitSystemDeleter> make_system(const Sinter::State& s) {
  const SubstrateGeometry& g = s.g;
  std::unique_ptr<ImplicitSystem, ImplicitSystemDeleter> sys(new ImplicitSystem);
  sys->unknown.assign(g.size(), -1);
  auto count = static_cast<std::ptrdiff_t>(s.x.size());
  for (std::size_t k = 1; k < g.nz; ++k)
    for (std::size_t j = 1; j + 1 < g.ny; ++j)
      for (std::size_t i = 1; i + 1 < g.nx; ++i) sys->unknown[g.index(i, j, k)] = count++;
  sys->count = count;
  sys->rhs.resize(count);
  sys->guess.resize(count);
  sys->solution.resize(count);
  sys->assemble = kAssemblyKernels[index_of_effects(kAssemblyEffects, s.scene.effects)];
  return sys;
}

// b to zero and, after the first step, A's values (its pattern stays).
void clear(ImplicitSystem& sys) {
  sys.rhs.setZero();
  sys.assembler.next = 0;
  if (sys.assembler.first) return;
  std::fill(sys.matrix.valuePtr(), sys.matrix.valuePtr() + sys.matrix.nonZeros(), 0.0);
  sys.assembler.values = sys.matrix.valuePtr();
}

// After the first assembly: the compressed matrix and the slot of each emitted entry, its (row,
// column) in the compressed column's row indices; the solver's pattern analysis.
void build_pattern(ImplicitSystem& sys) {
  Assembler& assembler = sys.assembler;
  sys.matrix.resize(sys.count, sys.count);
  sys.matrix.setFromTriplets(assembler.triplets.begin(), assembler.triplets.end());
  sys.matrix.makeCompressed();
  assembler.slot.resize(assembler.triplets.size());
  const auto* outer = sys.matrix.outerIndexPtr();
  const auto* inner = sys.matrix.innerIndexPtr();
  for (std::size_t q = 0; q < assembler.triplets.size(); ++q) {
    const auto& entry = assembler.triplets[q];
    const auto* begin = inner + outer[entry.col()];
    const auto* end = inner + outer[entry.col() + 1];
    assembler.slot[q] = std::lower_bound(begin, end, static_cast<int>(entry.row())) - inner;
  }
  assembler.triplets = {};
  assembler.first = false;
  sys.cg.setTolerance(1e-12);
  sys.cg.analyzePattern(sys.matrix);
}

// T* = A⁻¹ b, from the temperatures of the start of the step.
void solve(Sinter::State& s, ImplicitSystem& sys) {
  auto& cg = sys.cg;
  cg.factorize(sys.matrix);
  sys.solution = cg.solveWithGuess(sys.rhs, sys.guess);
  if (cg.info() != Eigen::Success) {
    throw NumericalError(
        fmt::format("implicit step {}: conjugate gradients did not converge ({} iterations)",
                    s.step, cg.iterations()));
  }
  s.implicit_iterations += static_cast<std::size_t>(cg.iterations());
}

}  // namespace

void implicit_step(Sinter::State& s, double dt) {
  if (!s.implicit) s.implicit = make_system(s);
  ImplicitSystem& sys = *s.implicit;
  clear(sys);
  sys.assemble(s, sys, dt);
  if (sys.assembler.first) build_pattern(sys);
  solve(s, sys);
  // Fluxes at T*: set the temperatures and let the booked explicit routines advance the
  // enthalpies with one step of dt (substeps is 1 for the implicit integrator).
  const Eigen::VectorXd& solution = sys.solution;
  for (std::size_t i = 0; i < s.x.size(); ++i)
    if (!s.gone[i]) s.temperature[i] = solution[static_cast<std::ptrdiff_t>(i)];
  for (std::size_t c = 0; c < s.g.size(); ++c)
    if (sys.unknown[c] >= 0) s.node_temperature[c] = solution[sys.unknown[c]];
  explicit_step(s, dt);
}

}  // namespace powderbed::thermal
