// Melt pool statistics per scan segment (solver.hpp TrackStats). The window of segment m runs
// from its start to the start of segment m + 1, so the pool a track leaves behind as the laser
// jumps is its own, and the peaks of later tracks never enter it. A node or particle counts in
// a window only if it got hotter during it: a particle still molten from the track before (a
// lone particle on the powder cools slowly) but cooling is not the new track's melt. Peaks are kept only where they
// are measured: the nodes of the columns on the cross-section through the segment's midpoint,
// and the particles; the centre line is read each step for the pool's length.
#include <algorithm>
#include <cmath>
#include <limits>

#include "powderbed/bed/height_map.hpp"
#include "powderbed/thermal/melt_pool.hpp"
#include "solver_state.hpp"

namespace powderbed::thermal {

namespace {

// The column nearest (x, y), or nothing outside the grid.
bool nearest_column(const SubstrateGeometry& g, double x, double y, std::size_t& column) {
  const double fi = std::round((x - g.x0) / g.dx), fj = std::round((y - g.y0) / g.dy);
  if (fi < 0 || fj < 0 || fi > static_cast<double>(g.nx - 1) || fj > static_cast<double>(g.ny - 1))
    return false;
  column = static_cast<std::size_t>(fi) + g.nx * static_cast<std::size_t>(fj);
  return true;
}

// How far from a track its cross-section may reach on a plate periodic across y (infinite on a
// bounded one): not past the seam onto itself (|a d_x| under half the period) and, where the
// segment is long enough to reach across the seam (its half-length plus two spot radii of pool
// beyond L |d_y|), not to its own image, which lies L |d_x| along the normal: else the pool's
// part across the seam would count as the section's other end.
double section_reach(const SubstrateGeometry& g, const ScanSegment& seg, std::array<double, 2> d,
                     double spot_radius) {
  if (!g.periodic_y) return std::numeric_limits<double>::infinity();
  const double period = g.period_y();
  double reach = std::abs(d[0]) > 0 ? 0.5 * period / std::abs(d[0]) : std::numeric_limits<double>::infinity();
  if (period * std::abs(d[1]) <= 0.5 * seg.length() + 2 * spot_radius)
    reach = std::min(reach, 0.5 * period * std::abs(d[0]));
  return reach;
}

Sinter::State::TrackProbe make_probe(const Sinter::State& s, std::size_t m) {
  const SubstrateGeometry& g = s.g;
  const ScanSegment& seg = s.schedule.segments()[m];
  const auto d = s.schedule.direction(m);
  const double cx = 0.5 * (seg.x0 + seg.x1), cy = 0.5 * (seg.y0 + seg.y1);
  Sinter::State::TrackProbe p;
  // Across: the columns nearest points along the normal (-dy, dx) at half the finer spacing,
  // over the whole grid, each once, placed where its node projects onto the plane. On a plate
  // periodic across y, within section_reach, the points past the seam wrapped into the period
  // and their nodes placed where they lie seen from the track.
  const double step = 0.5 * std::min(g.dx, g.dy);
  const double span = std::hypot(g.dx * static_cast<double>(g.nx - 1), g.dy * static_cast<double>(g.ny - 1));
  const double period = g.period_y();
  const double reach = section_reach(g, seg, d, s.scene.spot_radius);
  const auto count = static_cast<long>(std::ceil(span / step));
  for (long q = -count; q <= count; ++q) {
    const double a = static_cast<double>(q) * step;
    if (std::abs(a) >= reach) continue;
    double py = cy + a * d[0], shift = 0;
    if (g.periodic_y) {
      const double wrapped = bed::wrap_into(py, g.y0, period);
      shift = py - wrapped;
      py = wrapped;
    }
    std::size_t column;
    if (!nearest_column(g, cx - a * d[1], py, column)) continue;
    const double x = g.x(column % g.nx), y = g.y(column / g.nx) + shift;
    column = g.canonical_column(column);
    if (std::find(p.columns.begin(), p.columns.end(), column) != p.columns.end()) continue;
    const double along = -(x - cx) * d[1] + (y - cy) * d[0];
    if (!p.across.empty() && along <= p.across.back()) continue;  // keep them in order
    p.columns.push_back(column);
    p.across.push_back(along);
  }
  // Along: the centre line at half the finer grid spacing.
  p.line_step = 0.5 * std::min(g.dx, g.dy);
  const double length = seg.length();
  const auto samples = static_cast<std::size_t>(std::floor(length / p.line_step)) + 1;
  for (std::size_t q = 0; q < samples; ++q) {
    const double a = static_cast<double>(q) * p.line_step;
    p.line.push_back({seg.x0 + a * d[0], seg.y0 + a * d[1]});
  }
  return p;
}

double top_temperature(const Sinter::State& s, double x, double y) {
  const TopStencil st = top_stencil(s.g, x, y);
  double t = 0;
  for (int w = 0; w < 4; ++w) t += st.weight[w] * s.node_temperature[top_node(s, st.column[w])];
  return t;
}

// Mean temperature of the columns' top nodes within one spot radius of (x, y) (the nearest node when none is).
double mean_top_temperature(const Sinter::State& s, double x, double y) {
  const SubstrateGeometry& g = s.g;
  const double w = s.scene.spot_radius;
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t j = 0; j < g.ny; ++j) {
    const double dy = g.y(j) - y;
    if (std::abs(dy) > w) continue;
    for (std::size_t i = 0; i < g.nx; ++i) {
      const double dx = g.x(i) - x;
      if (dx * dx + dy * dy > w * w) continue;
      sum += s.node_temperature[top_node(s, i + g.nx * j)];
      ++n;
    }
  }
  return n > 0 ? sum / static_cast<double>(n) : top_temperature(s, x, y);
}

void open_window(Sinter::State& s, std::size_t m) {
  const ScanSegment& seg = s.schedule.segments()[m];
  s.track = m;
  s.current = TrackStats{};
  s.current.t_start = s.time;
  s.current.start_temperature = mean_top_temperature(s, seg.x0, seg.y0);
  const auto& p = s.probes[m];
  const SubstrateGeometry& g = s.g;
  s.section_start.resize(p.columns.size() * g.nz);
  for (std::size_t q = 0; q < p.columns.size(); ++q)
    for (std::size_t k = 0; k < g.nz; ++k)
      s.section_start[q * g.nz + k] = s.node_temperature[p.columns[q] + g.nx * g.ny * k];
  s.section_peak = s.section_start;
  s.track_particle_start = s.temperature;
  s.track_particle_peak = s.temperature;
  s.line_molten.assign(s.probes[m].line.size(), 0);
}

void close_window(Sinter::State& s) {
  const std::size_t m = s.track;
  const auto& p = s.probes[m];
  const ScanSegment& seg = s.schedule.segments()[m];
  const auto d = s.schedule.direction(m);
  // What did not get hotter in the window takes no part in it.
  const auto risen = [](std::vector<double> peak, const std::vector<double>& start) {
    for (std::size_t i = 0; i < peak.size(); ++i)
      if (!(peak[i] > start[i])) peak[i] = 0;
    return peak;
  };
  const auto section = risen(s.section_peak, s.section_start);
  const auto particles_risen = risen(s.track_particle_peak, s.track_particle_start);
  SectionInput in{&s.g, &p.columns, &p.across, &section, &s.top_plane,
                  &s.x, &s.y, &s.z, &s.radius, &particles_risen,
                  s.scene.phase_change.melting_point,
                  0.5 * (seg.x0 + seg.x1), 0.5 * (seg.y0 + seg.y1), d[0], d[1], &s.top};
  s.current.pool = measure_section(in);
  const double t_m = s.scene.phase_change.melting_point;
  for (std::size_t i = 0; i < s.x.size(); ++i)
    if (particles_risen[i] >= t_m) ++s.current.particles_molten;
  const auto [particles, substrate] = internal_energy(s);
  s.current.stored_energy = particles + substrate;
  s.current.t_end = s.time;
  s.tracks.push_back(s.current);
}

// The longest run of centre-line samples molten now, m.
double molten_length(Sinter::State& s) {
  const auto& p = s.probes[s.track];
  const ScanSegment& seg = s.schedule.segments()[s.track];
  const auto d = s.schedule.direction(s.track);
  const double t_m = s.scene.phase_change.melting_point;
  auto& molten = s.line_molten;
  for (std::size_t q = 0; q < p.line.size(); ++q)
    molten[q] = top_temperature(s, p.line[q][0], p.line[q][1]) >= t_m;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (s.temperature[i] < t_m || s.gone[i]) continue;
    const double ox = s.x[i] - seg.x0, oy = s.y[i] - seg.y0, r = s.radius[i];
    const double along = ox * d[0] + oy * d[1], off = -ox * d[1] + oy * d[0];
    if (std::abs(off) >= r) continue;
    const double half = std::sqrt(r * r - off * off);
    const double q0 = std::ceil((along - half) / p.line_step), q1 = std::floor((along + half) / p.line_step);
    for (double q = std::max(q0, 0.0); q <= q1 && q < static_cast<double>(molten.size()); ++q)
      molten[static_cast<std::size_t>(q)] = 1;
  }
  std::size_t best = 0, run = 0;
  for (const auto v : molten) {
    run = v ? run + 1 : 0;
    best = std::max(best, run);
  }
  return static_cast<double>(best) * p.line_step;
}

void update_window(Sinter::State& s) {
  const SubstrateGeometry& g = s.g;
  const auto& p = s.probes[s.track];
  const std::size_t plane = g.nx * g.ny;
  for (std::size_t q = 0; q < p.columns.size(); ++q)
    for (std::size_t k = 0; k < g.nz; ++k) {
      double& peak = s.section_peak[q * g.nz + k];
      peak = std::max(peak, s.node_temperature[p.columns[q] + plane * k]);
    }
  double hottest = s.current.peak_temperature;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    s.track_particle_peak[i] = std::max(s.track_particle_peak[i], s.temperature[i]);
    hottest = std::max(hottest, s.temperature[i]);
  }
  for (std::size_t c = 0; c < plane; ++c) hottest = std::max(hottest, s.node_temperature[top_node(s, c)]);
  s.current.peak_temperature = hottest;
  s.current.length = std::max(s.current.length, molten_length(s));
}

}  // namespace

void setup_tracks(Sinter::State& s) {
  s.probes.clear();
  for (std::size_t m = 0; m < s.schedule.segments().size(); ++m) s.probes.push_back(make_probe(s, m));
  s.tracks.clear();
  open_window(s, 0);
}

void watch_tracks(Sinter::State& s) {
  const std::size_t n = s.schedule.segments().size();
  while (s.track + 1 < n && s.time >= s.schedule.start(s.track + 1)) {
    update_window(s);  // the state at the boundary ends this window and starts the next
    close_window(s);
    open_window(s, s.track + 1);
  }
  update_window(s);
}

void close_tracks(Sinter::State& s) {
  if (s.tracks.size() == s.track + 1) return;  // closed already (run called twice)
  close_window(s);
}

}  // namespace powderbed::thermal
