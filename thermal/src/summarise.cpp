// What a run made (Sinter::run's result): the energy balance checked, the peaks, the melt pool
// on x = Lx/2 and along the track, the wetting counts.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/moments.hpp"
#include "powderbed/thermal/melt_pool.hpp"
#include "solver_state.hpp"

namespace powderbed::thermal {

namespace {

// The sections of the steady part of a single track on the grid line j = ny/2 (MeltPoolAlong).
MeltPoolAlong measure_along(const Sinter::State& s, MeltPoolInput in) {
  MeltPoolAlong a;
  const SubstrateGeometry& g = s.g;
  const auto& segments = s.schedule.segments();
  if (!s.scene.scan_path.empty() || segments.size() != 1 ||
      std::abs(segments.front().y0 - g.y(g.ny / 2)) > 0.5 * g.dy)
    return a;
  bed::Moments width, depth;
  const auto [first, last] = steady_columns(g);
  for (std::size_t i = first; i <= last; ++i) {
    in.x_plane = g.x(i);
    const MeltPool p = measure_melt_pool(in);
    width.add(p.width);
    depth.add(p.depth);
  }
  a.sections = width.n;
  a.width_mean = width.mean();
  a.width_sd = width.sd();
  a.depth_mean = depth.mean();
  a.depth_sd = depth.sd();
  return a;
}

}  // namespace

PeakTemperatures peak_temperatures(const Sinter::State& s) {
  PeakTemperatures p;
  for (const double t : s.peak) p.particles = std::max(p.particles, t);
  p.substrate = s.node_max;
  return p;
}

SinterResult summarise(Sinter::State& s, double particles_start, double substrate_start) {
  const double t_end = s.t_end;
  SinterResult r;
  r.steps = s.step;
  r.particle_steps = s.particle_steps;
  r.dt_grid = s.dt;
  r.dt_particle = s.dt / static_cast<double>(s.substeps);
  r.t_end = t_end;
  r.implicit_iterations = s.implicit_iterations;
  // Internal energy change from the state; the booked fluxes were summed separately as they
  // were produced, so the balance checks the bookkeeping.
  const auto [particles_end, substrate_end] = internal_energy(s);
  s.ledger.internal_particles = particles_end - particles_start;
  s.ledger.internal_substrate = substrate_end - substrate_start;
  r.energy = s.ledger;
  // Every joule is booked where it is produced, so the balance closes to round-off (~1e-14);
  // anything near 1e-6 means the run went wrong (a step beyond the stable bound that stayed
  // finite): its numbers are not a result.
  // (A run with no laser has no scale to measure the balance against.)
  if (const double error = r.energy.relative_error(); s.ledger.absorbed() > 0 && !(error <= 1e-6)) {
    throw NumericalError(fmt::format(
        "energy balance broken at the end of the run (step {}): absorbed + surface gains - "
        "internal change - boundary outflow = {:g} of the energy absorbed (accepted: below "
        "1e-6); the time step is beyond the stable bound (--unsafe-dt?)",
        s.step, error));
  }
  const double t_m = s.scene.phase_change.melting_point;
  const bool evaporation = s.scene.has(kEvaporation);
  r.peaks = peak_temperatures(s);
  r.max_temperature = r.peaks.highest();
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (s.peak[i] >= t_m) ++r.particles_molten;
    // Without evaporation a particle that reached T_v counts ([GZ]'s reading); with it, one
    // whose mass evaporated.
    if (evaporation ? s.gone[i] && !merged_away(s, i)
                    : s.peak[i] >= s.scene.phase_change.boiling_point)
      ++r.particles_vaporised;
  }
  r.evaporated_mass_particles = s.evaporated_particles;
  r.evaporated_mass = s.evaporated_particles + s.evaporated_substrate;
  r.peak_recoil_pressure = s.peak_recoil;
  if (s.scene.has(kDepression)) {
    r.depression_temperature = s.depression_temperature;
    r.depression_depth = s.depression_depth;
  }
  const SubstrateGeometry& g = s.g;
  MeltPoolInput in{&g, &s.node_peak, &s.top_plane, &s.x, &s.y, &s.z, &s.radius, &s.peak, t_m,
                   g.x0 + 0.5 * static_cast<double>(g.nx - 1) * g.dx};
  r.melt_pool = measure_melt_pool(in);
  r.along = measure_along(s, in);
  const double beam = s.schedule.beam_energy(t_end);
  r.absorptance = beam > 0 ? s.ledger.absorbed() / beam : 0.0;
  r.traces = s.traces;
  close_tracks(s);
  r.tracks = s.tracks;
  r.substrate_wetted = static_cast<std::size_t>(std::count_if(
      s.wetted.begin(), s.wetted.end(), [](const auto& w) { return !w.through_pool; }));
  r.substrate_arrested = static_cast<std::size_t>(
      std::count_if(s.wetted.begin(), s.wetted.end(),
                    [&](const auto& w) { return !w.through_pool && w.interface > 0 && !s.gone[w.particle]; }));
  r.particles_merged = s.merged_count;
  r.particles_coalesced = s.coalesced_count;
  r.bridges = s.bridges;
  return r;
}

}  // namespace powderbed::thermal
