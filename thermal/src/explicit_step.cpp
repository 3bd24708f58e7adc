// Forward Euler on enthalpies (docs/physics.md §5 "Time integration"), the effects composed once:
// a particle kernel instantiated for each combination of the particle effects (effect_kernels.hpp)
// and a grid kernel for constant or temperature-dependent conductivity, chosen through a table of
// function pointers, so an effect that is off is absent from the loop (docs/architecture.md
// "Effects a scene calls for").
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "effect_kernels.hpp"
#include "powderbed/thermal/beer_lambert_laser.hpp"
#include "powderbed/thermal/contact_conduction.hpp"
#include "powderbed/thermal/surface_losses.hpp"
#include "solver_state.hpp"

namespace powderbed::thermal {

namespace {

// The effects that shape the particle kernel (effect_kernels.hpp).
constexpr std::array kParticleEffects{kConduction, kSubstrateContact, kConvection, kRadiation,
                                      kLaser, kVariableProperties};

// Grids below this many nodes run their loops on one thread: a step's work is then tens of
// microseconds, less than a team's fork and barrier, and on a loaded machine a barrier that
// waits for a descheduled thread costs milliseconds (the small-grid tests ran 40-150x slower
// with two threads than with one).
constexpr std::size_t kParallelNodes = 1u << 16;

template <unsigned Effects>
void particle_step(Sinter::State& s, double t, double dt) {
  const std::size_t n = s.x.size();
  auto& q = s.heat;
  std::fill(q.begin(), q.end(), 0.0);
  const double k_const = s.k_fixed;
  const auto k_of = [&](double temp) {
    if constexpr ((Effects & kVariableProperties) != 0) return s.conductivity(temp);
    else return k_const;
  };
  if constexpr ((Effects & kConduction) != 0) {
    for (const auto& p : s.net.pairs) {
      if (s.gone[p.i] || s.gone[p.j]) continue;
      const double ti = s.temperature[p.i], tj = s.temperature[p.j];
      const double f = conduction_flow(k_of(ti), k_of(tj), p.shape, tj - ti);
      q[p.i] += f;
      q[p.j] -= f;
    }
  }
  if constexpr ((Effects & kSubstrateContact) != 0) {
    for (const auto& c : s.net.substrate) {
      if (s.gone[c.particle]) continue;
      // The contact meets the top face between four nodes: weight w of it conducts to each, by
      // that node's own difference (one flow from their interpolated mean, shared out by w,
      // would draw heat from a node colder than the particle and swing it below T0).
      const double ti = s.temperature[c.particle], ki = k_of(ti);
      for (int w = 0; w < 4; ++w) {
        const std::size_t column = c.stencil.column[w], node = top_node(s, column);
        const double tq = s.node_temperature[node];
        const double f = c.stencil.weight[w] * conduction_flow(ki, k_of(tq), c.shape, tq - ti);
        q[c.particle] += f;
        if (s.g.fixed_column(column)) s.ledger.boundary -= f * dt;  // from the reservoir
        else s.sources.push_back({node, -f * dt});
      }
    }
  }
  if constexpr ((Effects & (kConvection | kRadiation)) != 0) {
    double convection = 0, radiation = 0;
    for (const auto i : s.exposed) {
      if (s.gone[i]) continue;
      if constexpr ((Effects & kConvection) != 0) {
        const double f = convection_gain(s.environment, s.temperature[i], s.area[i]);
        q[i] += f;
        convection += f;
      }
      if constexpr ((Effects & kRadiation) != 0) {
        const double f = radiation_gain(s.environment, s.temperature[i], s.area[i]);
        q[i] += f;
        radiation += f;
      }
    }
    s.ledger.convection += convection * dt;
    s.ledger.radiation += radiation * dt;
  }
  if constexpr ((Effects & kLaser) != 0) {
    auto& lit = s.laser_power;  // kept apart: evaporation reads the lit surface from it
    std::fill(lit.begin(), lit.end(), 0.0);
    s.ledger.laser_particles += s.particle_laser(s, t, lit) * dt;
    for (std::size_t i = 0; i < n; ++i) q[i] += lit[i];
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (s.gone[i]) continue;
    s.h[i] += dt * q[i] / s.mass[i];
    particle_enthalpy_changed(s, i);
  }
}

using ParticleKernel = void (*)(Sinter::State&, double, double);

template <std::size_t... I>
constexpr std::array<ParticleKernel, sizeof...(I)> particle_kernels(std::index_sequence<I...>) {
  return {&particle_step<effects_of_index(kParticleEffects, I)>...};
}
constexpr auto kParticleKernels =
    particle_kernels(std::make_index_sequence<std::size_t{1} << kParticleEffects.size()>{});

// Heat from the free nodes into the Dirichlet sides and bottom over dt, with the face fluxes
// the grid step uses (a side face as tall as the thinner of its two nodes). A periodic seam is
// no side: what crosses it stays in the grid.
void boundary_outflow(Sinter::State& s, double dt) {
  const SubstrateGeometry& g = s.g;
  const auto& t = s.node_temperature;
  const auto& k = s.node_k;
  const double gx = g.dy * g.dz / g.dx, gy = g.dx * g.dz / g.dy, gz = g.dx * g.dy / g.dz;
  const auto flux = [&](std::size_t free, std::size_t fixed, double shape) {
    return conduction_flow(k[fixed], k[free], shape, t[free] - t[fixed]);
  };
  std::vector<double>& plane = s.plane_sums;  // reused: no allocation per step
  plane.assign(g.nz, 0.0);
  const std::size_t k_end = s.highest_plane + 1;
#pragma omp parallel for schedule(static) if (g.size() >= kParallelNodes)
  for (std::size_t kk = 1; kk < k_end; ++kk) {
    const auto side = [&](std::size_t a, std::size_t b, double shape) {
      const double w = std::min(node_thickness(s, a), node_thickness(s, b));
      return w > 0 ? flux(a, b, shape * w) : 0.0;
    };
    double sum = 0;
    for (std::size_t j = g.first_row(); j + 1 < g.ny; ++j) {
      sum += side(g.index(1, j, kk), g.index(0, j, kk), gx);
      sum += side(g.index(g.nx - 2, j, kk), g.index(g.nx - 1, j, kk), gx);
    }
    for (std::size_t i = 1; i + 1 < g.nx && !g.periodic_y; ++i) {
      sum += side(g.index(i, 1, kk), g.index(i, 0, kk), gy);
      sum += side(g.index(i, g.ny - 2, kk), g.index(i, g.ny - 1, kk), gy);
    }
    if (kk == 1) {
      for (std::size_t j = g.first_row(); j + 1 < g.ny; ++j)
        for (std::size_t i = 1; i + 1 < g.nx; ++i)
          sum += flux(g.index(i, j, 1), g.index(i, j, 0), gz);
    }
    plane[kk] = sum;
  }
  double total = 0;
  for (const double p : plane) total += p;  // fixed order: the same sum for any thread count
  s.ledger.boundary += total * dt;
}

// The planes from the plate's top up over a raised top (fusion): a node is as thick as
// node_thickness says; a side face is as tall as the thinner of its two nodes (none to an empty
// node), the face above exists while the column's solid goes on. Row 0 of a periodic seam
// meets row ny - 2 across it.
template <bool Variable>
void raised_planes(Sinter::State& s, double dt) {
  const SubstrateGeometry& g = s.g;
  const double gx = g.dy * g.dz / g.dx, gy = g.dx * g.dz / g.dy, gz = g.dx * g.dy / g.dz;
  const std::size_t sx = 1, sy = g.nx, sz = g.columns();
  const double* t = s.node_temperature.data();
  const double* kk = s.node_k.data();
  const double k0 = s.k_fixed;
  const auto k_at = [&](std::size_t a) {
    if constexpr (Variable) return kk[a];
    else return k0;
  };
  const std::size_t k_end = s.highest_plane + 1;
  for (std::size_t k = g.k_plate(); k < k_end; ++k) {
    const auto thick = [&](std::size_t column) { return column_thickness(s, column, k); };
    for (std::size_t j = g.first_row(); j + 1 < g.ny; ++j) {
      for (std::size_t i = 1; i + 1 < g.nx; ++i) {
        const std::size_t col = i + g.nx * j, c = col + sz * k;
        const std::size_t before = i + g.nx * g.row_before(j);
        const double th = thick(col);
        if (th == 0) continue;
        const double tc = t[c];
        const auto side = [&](std::size_t nb_col, std::size_t nb, double shape) {
          const double w = std::min(th, thick(nb_col));
          return w > 0 ? conduction_flow(k_at(c), k_at(nb), shape * w, t[nb] - tc) : 0.0;
        };
        double energy = side(col - sx, c - sx, gx) + side(col + sx, c + sx, gx) +
                        side(before, before + sz * k, gy) + side(col + sy, c + sy, gy) +
                        conduction_flow(k_at(c), k_at(c - sz), gz, t[c - sz] - tc);
        if (k < s.top_plane[col]) energy += conduction_flow(k_at(c), k_at(c + sz), gz, t[c + sz] - tc);
        s.e[c] += energy * dt / (g.cell_volume() * th);
      }
    }
  }
}

// Finite-volume update of every free node, then T = T(e) and, if properties vary, K = K(T).
// Across a periodic seam row 0 meets row ny - 2 and row ny - 2 the image of row 0 (row ny - 1),
// refreshed before the update reads it and after it.
template <bool Variable>
void grid_step(Sinter::State& s, double dt) {
  const SubstrateGeometry& g = s.g;
  const double gx = g.dy * g.dz / g.dx, gy = g.dx * g.dz / g.dy, gz = g.dx * g.dy / g.dz;
  const std::size_t sx = 1, sy = g.nx, sz = g.nx * g.ny;
  copy_image_row(s);
  double* e = s.e.data();
  double* t = s.node_temperature.data();
  double* kk = s.node_k.data();
  const double k0 = s.k_fixed;
  // A flat top: every plane up to the plate's here (its top plane owns half cells); a raised
  // top: the planes below the plate's here, from there raised_planes.
  const bool raised = !s.top.empty();
  const std::size_t k_end = raised ? g.k_plate() : g.k_plate() + 1;
#pragma omp parallel for schedule(static) if (g.size() >= kParallelNodes)
  for (std::size_t k = 1; k < k_end; ++k) {
    const bool top = k == g.k_plate();
    const double half = top ? 0.5 : 1.0;
    const double cx = 0.5 * gx * half * dt, cy = 0.5 * gy * half * dt, cz = 0.5 * gz * dt;
    const double inv_volume = 1 / (g.cell_volume() * half);
    for (std::size_t j = g.first_row(); j + 1 < g.ny; ++j) {
      const std::size_t row = g.index(0, j, k), before = g.index(0, g.row_before(j), k);
      for (std::size_t i = 1; i + 1 < g.nx; ++i) {
        const std::size_t c = row + i, b = before + i;
        const double tc = t[c];
        double energy;
        if constexpr (Variable) {
          const double kc = kk[c];
          energy = cx * ((kc + kk[c - sx]) * (t[c - sx] - tc) + (kc + kk[c + sx]) * (t[c + sx] - tc)) +
                   cy * ((kc + kk[b]) * (t[b] - tc) + (kc + kk[c + sy]) * (t[c + sy] - tc)) +
                   cz * (kc + kk[c - sz]) * (t[c - sz] - tc);
          if (!top) energy += cz * (kc + kk[c + sz]) * (t[c + sz] - tc);
        } else {
          energy = 2 * k0 *
                   (cx * (t[c - sx] + t[c + sx] - 2 * tc) + cy * (t[b] + t[c + sy] - 2 * tc) +
                    cz * (t[c - sz] - tc));
          if (!top) energy += 2 * k0 * cz * (t[c + sz] - tc);
        }
        e[c] += energy * inv_volume;
      }
    }
  }
  if (raised) raised_planes<Variable>(s, dt);
  // Energy from the laser and the particles (free nodes only, booked when it was produced).
  for (const auto& [node, energy] : s.sources) e[node] += energy / node_volume(s, node);
  s.sources.clear();
  // The depression: the beam's energy drills from each column's surface down, each node filled
  // to T_d with what conduction and the particles brought it this step counted.
  if (s.scene.has(kDepression)) drill(s);
  // Second pass: the update above read only the old temperatures. The empty nodes over a
  // raised column are skipped (they hold e = 0, T0, until raise_column fills them).
  double hottest = s.node_max;
  double* peak = s.node_peak.data();
  const std::size_t k_top = raised ? s.highest_plane + 1 : k_end, k_plate = g.k_plate();
#pragma omp parallel for schedule(static) reduction(max : hottest) if (g.size() >= kParallelNodes)
  for (std::size_t k = 1; k < k_top; ++k) {
    for (std::size_t j = g.first_row(); j + 1 < g.ny; ++j) {
      const std::size_t row = g.index(0, j, k);
      for (std::size_t i = 1; i + 1 < g.nx; ++i) {
        if (k > k_plate && s.top_plane[i + g.nx * j] < k) continue;
        const std::size_t c = row + i;
        const double tc = s.per_m3.temperature(e[c]);
        t[c] = tc;
        if constexpr (Variable) kk[c] = s.conductivity(tc);
        peak[c] = std::max(peak[c], tc);
        hottest = std::max(hottest, tc);
      }
    }
  }
  s.node_max = hottest;
  copy_image_row(s);
}

}  // namespace

void explicit_step(Sinter::State& s, double dt) {
  const ParticleKernel particles = kParticleKernels[index_of_effects(kParticleEffects, s.scene.effects)];
  if (s.tracer && s.scene.has(kLaser | kLaserSubstrate)) prepare_traces(s, s.time, s.time + dt);
  if (!s.x.empty()) {
    const double dt_p = dt / static_cast<double>(s.substeps);
    const bool evaporation = s.scene.has(kEvaporation);
    for (std::size_t sub = 0; sub < s.substeps; ++sub) {
      particles(s, s.time + dt_p * static_cast<double>(sub), dt_p);
      if (evaporation) evaporate_particles(s, dt_p);
    }
    s.particle_steps += s.substeps;
  }
  if (s.scene.has(kWetting)) {
    spread_molten(s);
    wetted_exchange(s, dt);
  }
  if (s.scene.has(kLaserSubstrate)) s.substrate_laser(s, s.time, dt);
  if (s.scene.has(kEvaporation)) evaporate_surface(s, dt);
  boundary_outflow(s, dt);
  if (s.scene.has(kVariableProperties)) grid_step<true>(s, dt);
  else grid_step<false>(s, dt);
}

}  // namespace powderbed::thermal
