// Where the laser's power goes, for the two absorption models (scene.hpp LaserAbsorption):
// Beer–Lambert on projected areas plus the beam that passes the powder (docs/physics.md §5), or the
// power maps of the ray tracer (ray_traced_laser.hpp) blended between traced beam positions.
// Each model books every joule it deposits in the ledger where it deposits it.
#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"
#include "powderbed/thermal/beer_lambert_laser.hpp"
#include "powderbed/thermal/vapour_depression.hpp"
#include "lit_particles.hpp"
#include "solver_state.hpp"

namespace powderbed::thermal {

namespace {

double beer_lambert_particles(Sinter::State& s, double t, std::vector<double>& q) {
  const ScanSchedule::Beam beam = beam_at(s, t);
  if (!beam.on) return 0;
  double absorbed = 0;
  for_each_lit_particle(s, beam.x, beam.y, peak_intensity(laser_with_power(s, beam.power)),
                        [&](std::size_t i, double f) {
                          q[i] += f;
                          absorbed += f;
                        });
  return absorbed;
}

// Laser power that passes the powder onto the free top nodes (docs/physics.md §5 top-face flux);
// across a periodic seam the beam's rows wrap (row ny - 1 is row 0).
void beer_lambert_substrate(Sinter::State& s, double t, double dt) {
  const SubstrateGeometry& g = s.g;
  const ScanSchedule::Beam beam = beam_at(s, t);
  if (!beam.on) return;
  const LaserParams laser = laser_with_power(s, beam.power);
  const double xl = beam.x, yl = beam.y;
  const double reach = std::sqrt(kBeamCutoff2) * s.laser.spot_radius;
  // The first node index at or past v, held to the free nodes 1 .. count - 2 (and one past them).
  const auto first = [](double lo, double spacing, std::size_t count, double v) {
    const double f = std::ceil((v - lo) / spacing);
    return static_cast<long>(std::clamp(f, 1.0, static_cast<double>(count - 1)));
  };
  const long i0 = first(g.x0, g.dx, g.nx, xl - reach), i1 = first(g.x0, g.dx, g.nx, xl + reach);
  long j0 = first(g.y0, g.dy, g.ny, yl - reach), j1 = first(g.y0, g.dy, g.ny, yl + reach);
  if (g.periodic_y) {
    j0 = static_cast<long>(std::ceil((yl - reach - g.y0) / g.dy));
    j1 = static_cast<long>(std::ceil((yl + reach - g.y0) / g.dy));
  }
  double absorbed = 0;
  for (long j = j0; j < j1; ++j) {
    const double dy = g.y0 + g.dy * static_cast<double>(j) - yl;
    const std::size_t row = g.periodic_y ? g.wrap_row(j) : static_cast<std::size_t>(j);
    for (long i = i0; i < i1; ++i) {
      const double dx = g.x(static_cast<std::size_t>(i)) - xl;
      const std::size_t column = static_cast<std::size_t>(i) + g.nx * row;
      const double energy =
          node_laser_power(laser, dx * dx + dy * dy, s.transmission[column], g.dx, g.dy) * dt;
      add_surface_energy(s, column, energy);
      absorbed += energy;
    }
  }
  s.ledger.laser_substrate += absorbed;
}

// Traced beam position k of segment m: one key, in time order (segment 0's keys are k, so the
// single track draws the random streams it always drew).
constexpr unsigned kSegmentShift = 40;
std::uint64_t trace_key(std::size_t m, std::uint64_t k) {
  return (static_cast<std::uint64_t>(m) << kSegmentShift) | k;
}
std::size_t key_segment(std::uint64_t key) { return static_cast<std::size_t>(key >> kSegmentShift); }

// The traced positions k and k + 1 around the beam at time t, the blend u of k + 1 and the
// segment's power.
struct Blend {
  const AbsorptionMap* a;
  const AbsorptionMap* b;
  double u, power;
};

const AbsorptionMap& traced_map(const Sinter::State& s, std::uint64_t key) {
  for (const auto& t : s.traced)
    if (t.k == key) return t.map;
  throw std::logic_error("ray-traced laser: beam position not traced");  // prepare_traces' job
}

// The traced position below the beam on its segment (k) and how far past it the beam is (u).
std::pair<std::uint64_t, double> trace_position(const Sinter::State& s,
                                                const ScanSchedule::Beam& beam) {
  const double f = std::max(0.0, beam.along / s.trace_spacing);
  const double k = std::floor(f);
  return {static_cast<std::uint64_t>(k), f - k};
}

// nullopt while the laser is off.
std::optional<Blend> blend_at(const Sinter::State& s, double t) {
  const ScanSchedule::Beam beam = beam_at(s, t);
  if (!beam.on) return std::nullopt;
  const auto [k, u] = trace_position(s, beam);
  return Blend{&traced_map(s, trace_key(beam.segment, k)),
               &traced_map(s, trace_key(beam.segment, k + 1)), u, beam.power};
}

double ray_traced_particles(Sinter::State& s, double t, std::vector<double>& q) {
  const auto on = blend_at(s, t);
  if (!on) return 0;
  const Blend& blend = *on;
  double absorbed = 0;
  const auto add = [&](const AbsorptionMap& map, double weight) {
    const double power = blend.power * weight;
    for (const auto& e : map.particles) {
      if (s.gone[e.target]) continue;
      const double f = power * e.fraction;
      q[e.target] += f;
      absorbed += f;
    }
  };
  add(*blend.a, 1 - blend.u);
  add(*blend.b, blend.u);
  return absorbed;
}

void ray_traced_substrate(Sinter::State& s, double t, double dt) {
  const auto on = blend_at(s, t);
  if (!on) return;
  const Blend& blend = *on;
  double absorbed = 0, into_boundary = 0;
  const auto add = [&](const AbsorptionMap& map, double weight) {
    const double energy = blend.power * weight * dt;
    for (const auto& e : map.nodes) {
      const double de = energy * e.fraction;
      absorbed += de;
      if (s.g.fixed_column(e.target)) into_boundary += de;  // a Dirichlet node passes it on
      else add_surface_energy(s, e.target, de);
    }
  };
  add(*blend.a, 1 - blend.u);
  add(*blend.b, blend.u);
  s.ledger.laser_substrate += absorbed;
  s.ledger.boundary += into_boundary;
}

// The surfaces as the next trace sees them: phases (molten: T >= T_m) and, with the depression,
// its depth below the part's top the tracer sees (TraceSurfaces::rise, set once at the start):
// the T_d isotherm is found from each column's top node down, its bottom at z(k) - depth.
void update_surfaces(Sinter::State& s) {
  const double t_m = s.scene.phase_change.melting_point;
  TraceSurfaces& f = s.surfaces;
  for (std::size_t i = 0; i < s.x.size(); ++i) f.particle_phase[i] = s.temperature[i] >= t_m;
  const SubstrateGeometry& g = s.g;
  const std::size_t plane = g.columns();
  for (std::size_t c = 0; c < plane; ++c) f.node_phase[c] = s.node_temperature[top_node(s, c)] >= t_m;
  if (!s.scene.has(kDepression)) return;
  for (std::size_t c = 0; c < plane; ++c) {
    const std::size_t top = top_node(s, c);
    const auto column = [&](std::size_t k) { return s.node_temperature[top - k * plane]; };
    const double from_node = isotherm_depth(column, s.top_plane[c], g.dz, cavity_temperature(s));
    const double seen = g.z_top + (f.rise.empty() ? 0.0 : f.rise[c]);
    f.depression[c] = from_node > 0 ? std::max(0.0, seen - (g.z(s.top_plane[c]) - from_node)) : 0.0;
    s.depression_depth = std::max(s.depression_depth, f.depression[c]);
  }
}

void trace(Sinter::State& s, std::uint64_t key) {
  if (s.gone_traced != s.gone_count) {  // particles have gone (and drops grown) since
    s.tracer->update(s.gone, s.z, s.radius);
    s.gone_traced = s.gone_count;
  }
  update_surfaces(s);
  const std::size_t m = key_segment(key);
  const ScanSegment& seg = s.schedule.segments()[m];
  const auto d = s.schedule.direction(m);
  const double along = static_cast<double>(key - trace_key(m, 0)) * s.trace_spacing;
  AbsorptionMap map = s.tracer->trace(seg.x0 + along * d[0], seg.y0 + along * d[1], key, s.surfaces);
  TraceSummary& sum = s.traces;
  ++sum.traces;
  sum.absorbed += map.absorptance();
  sum.absorbed_particles += map.absorbed_particles;
  sum.escaped += map.escaped;
  sum.outside += map.outside;
  sum.dropped += map.dropped;
  sum.hits += map.hits;
  sum.absorbed_depression += map.absorbed_depression;
  s.traced.push_back({key, std::move(map)});
}

// Particle steps per grid step: the stable bound's, and as many as keep the laser's rise per
// step (P f_i / (m_i c_min) dt_p) below time.max-particle-rise for the traced maps.
void limit_particle_rise(Sinter::State& s) {
  const double c_min = s.per_kg.min_capacity();
  double rate = 0;
  for (const auto& t : s.traced) {
    const double power = s.schedule.segments()[key_segment(t.k)].power;
    for (const auto& e : t.map.particles)
      rate = std::max(rate, power * e.fraction / (s.mass[e.target] * c_min));
  }
  const double needed = std::ceil(s.dt * rate / s.scene.max_particle_rise);
  s.substeps = std::max(s.substeps_stable, static_cast<std::size_t>(needed));
}

}  // namespace

void setup_laser(Sinter::State& s, const bed::Bed& bed) {
  if (s.scene.absorption == LaserAbsorption::beer_lambert) {
    s.particle_laser = beer_lambert_particles;
    s.substrate_laser = beer_lambert_substrate;
    return;
  }
  s.particle_laser = ray_traced_particles;
  s.substrate_laser = ray_traced_substrate;
  s.tracer = std::make_unique<BeamTracer>(bed, s.g, s.scene.spot_radius, s.scene.rays,
                                          surface_optics(s.scene));
  s.trace_spacing = s.scene.retrace_interval * s.scene.spot_radius;
  s.surfaces.particle_phase.assign(s.x.size(), 0);
  s.surfaces.node_phase.assign(s.g.nx * s.g.ny, 0);
  if (s.scene.has(kDepression)) s.surfaces.depression.assign(s.g.nx * s.g.ny, 0.0);
  // The optics see the part the run starts on (a build's earlier layers, levelled as fusion
  // leaves them), not the melt that merges during the run: a merged particle raises its columns
  // by its volume over its footprint at once, a spike whose steep sides would mirror the beam
  // sideways; the melt levels it before it freezes (fusion.hpp), and the next layer sees that.
  if (!s.top.empty()) {
    s.surfaces.rise.resize(s.g.columns());
    for (std::size_t c = 0; c < s.g.columns(); ++c) s.surfaces.rise[c] = s.top[c] - s.g.z_top;
  }
}

SurfaceOptics surface_optics(const SinterScene& scene) {
  SurfaceOptics o;
  o.model = scene.optics;
  const double liquid =
      std::isnan(scene.absorptivity_liquid) ? scene.absorptivity : scene.absorptivity_liquid;
  o.alpha[0] = scene.absorptivity;
  o.alpha[1] = liquid;
  o.index[0] = {scene.index_n_solid, scene.index_k_solid};
  o.index[1] = {scene.index_n_liquid, scene.index_k_liquid};
  return o;
}

void add_surface_energy(Sinter::State& s, std::size_t column, double energy) {
  column = s.g.canonical_column(column);  // a periodic seam's image row is row 0
  if (!s.scene.has(kDepression)) {
    s.sources.push_back({top_node(s, column), energy});
    return;
  }
  if (s.column_energy[column] == 0) s.touched_columns.push_back(static_cast<std::uint32_t>(column));
  s.column_energy[column] += energy;
}

// Each column's energy from its surface down, into the nodes' enthalpies (the grid step's
// conduction and sources are in them already): a node takes what brings it to T_d, the rest
// goes on to the node below (the beam drills through what it displaces).
void drill(Sinter::State& s) {
  const SubstrateGeometry& g = s.g;
  const std::size_t plane = g.columns();
  const double e_d = s.per_m3.enthalpy(s.depression_temperature);
  for (const std::uint32_t c : s.touched_columns) {
    double energy = s.column_energy[c];
    s.column_energy[c] = 0;
    for (std::size_t node = top_node(s, c); energy > 0; node -= plane) {
      const double room = node_volume(s, node) * (e_d - s.e[node]);
      const double take = std::clamp(room, 0.0, energy);
      s.e[node] += take / node_volume(s, node);
      energy -= take;
      if (energy > 0 && node < 2 * plane) {  // the lowest free node is full: nowhere to go
        throw NumericalError(fmt::format(
            "the vapour depression reached the substrate's bottom under column ({}, {}) at step "
            "{} (t = {:g} s): the pool is deeper than the grid (accepted: a deeper "
            "substrate.depth)",
            c % g.nx, c / g.nx, s.step, s.time));
      }
    }
  }
  s.touched_columns.clear();
}

std::size_t surface_node(const Sinter::State& s, std::size_t column) {
  if (!s.scene.has(kDepression)) return top_node(s, column);
  const std::size_t plane = s.g.columns();
  std::size_t node = top_node(s, column);
  while (node >= 2 * plane && s.node_temperature[node] >= cavity_temperature(s)) node -= plane;
  return node;
}

double absorbed_fraction(const Sinter::State& s, double x, double y) {
  if (s.tracer) {
    TraceSurfaces start;  // solid and flat
    start.particle_phase.assign(s.x.size(), 0);
    start.node_phase.assign(s.g.nx * s.g.ny, 0);
    const AbsorptionMap map = s.tracer->trace(x, y, 0, start);
    return map.absorptance() / (1 - map.outside);
  }
  // Beer–Lambert: the particles' share plus the substrate's, summed as the kernels deposit them.
  double absorbed = 0;
  for_each_lit_particle(s, x, y, peak_intensity(s.laser), [&](std::size_t, double f) { absorbed += f; });
  const SubstrateGeometry& g = s.g;
  for (std::size_t j = g.first_row(); j + 1 < g.ny; ++j)
    for (std::size_t i = 1; i + 1 < g.nx; ++i) {
      const double dx = g.x(i) - x, dy = g.y(j) - y;
      absorbed +=
          node_laser_power(s.laser, dx * dx + dy * dy, s.transmission[i + g.nx * j], g.dx, g.dy);
    }
  return absorbed / s.scene.power;
}

// The traced positions the beam needs over [t0, t1], on each segment it runs on then: from the
// one below it at t0 (or the segment's start) to the one past it at t1 (or the segment's end).
void prepare_traces(Sinter::State& s, double t0, double t1) {
  const ScanSchedule& path = s.schedule;
  std::vector<std::uint64_t> needed;
  for (std::size_t m = path.at(t0).segment; m < path.segments().size(); ++m) {
    if (path.start(m) > t1) break;
    if (path.end(m) <= t0) continue;
    const auto k_at = [&](double t) {
      return trace_position(s, path.on_segment(m, std::clamp(t, path.start(m), path.end(m)))).first;
    };
    const std::uint64_t last = k_at(t1) + 1;
    for (std::uint64_t k = k_at(t0); k <= last; ++k) needed.push_back(trace_key(m, k));
  }
  if (needed.empty()) return;
  // A particle that vaporised leaves the beam at once: every map is traced anew without it.
  if (s.gone_count != s.gone_traced) s.traced.clear();
  std::erase_if(s.traced,
                [&](const Sinter::State::TracedBeam& t) { return t.k < needed.front(); });
  bool added = false;
  for (const std::uint64_t key : needed) {
    const bool have = std::any_of(s.traced.begin(), s.traced.end(),
                                  [&](const Sinter::State::TracedBeam& t) { return t.k == key; });
    if (have) continue;
    trace(s, key);
    added = true;
  }
  if (added) limit_particle_rise(s);
}

}  // namespace powderbed::thermal
