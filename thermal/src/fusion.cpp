#include "powderbed/thermal/fusion.hpp"

#include <algorithm>
#include <cmath>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/surface_contacts.hpp"
#include "powderbed/thermal/bonding.hpp"

namespace powderbed::thermal {

namespace {

// The bed with only the particles `keep` marks (optional arrays follow when present).
bed::Bed keep_particles(const bed::Bed& bed, const std::vector<std::uint8_t>& keep) {
  bed::Bed out;
  out.domain = bed.domain;
  out.provenance = bed.provenance;
  const auto copy = [&](const auto& from, auto& to) {
    if (from.empty()) return;
    for (std::size_t i = 0; i < keep.size(); ++i)
      if (keep[i]) to.push_back(from[i]);
  };
  copy(bed.x, out.x);
  copy(bed.y, out.y);
  copy(bed.z, out.z);
  copy(bed.radius, out.radius);
  copy(bed.id, out.id);
  copy(bed.vx, out.vx);
  copy(bed.vy, out.vy);
  copy(bed.vz, out.vz);
  copy(bed.material, out.material);
  copy(bed.temperature, out.temperature);
  copy(bed.phase, out.phase);
  return out;
}

// The bed as the scan left it: a drop that coalesced its molten neighbours has grown (its
// height and radius are the sinter's; x and y, and the rest, are the bed's).
bed::Bed as_scanned(const bed::Bed& bed, const Sinter& sinter) {
  bed::Bed now = bed;
  now.z = sinter.particle_z();
  now.radius = sinter.particle_radius();
  return now;
}

// A particle that coalesced into a drop ends as that drop does (fused, a ball or vapour) and is
// counted so; its mass is the drop's.
void follow_drops(const std::vector<std::uint32_t>& into, Fusion& f) {
  for (std::size_t i = 0; i < into.size(); ++i) {
    if (into[i] == i) continue;
    std::size_t root = into[i];
    while (into[root] != root) root = into[root];
    f.state[i] = f.state[root];
    f.fused += f.state[i] == kFused ? 1 : 0;
    f.balled += f.state[i] == kBalled ? 1 : 0;
    f.vaporised += f.state[i] == kVapour ? 1 : 0;
  }
}

}  // namespace

double Fusion::mass_error() const {
  const double before = powder_mass_before + solid_mass_before;
  const double after = powder_mass_after + solid_mass_after + vaporised_mass;
  return before > 0 ? std::abs(after - before) / before : 0.0;
}

double Fusion::fused_fraction() const {
  const double met = powder_mass_before + merged_mass;
  return met > 0 ? (met - powder_mass_after - vaporised_mass) / met : 0.0;
}

double solid_mass(const SubstrateGeometry& g, const TopHeight& top, double density) {
  double volume = 0;
  for (std::size_t c = 0; c < top.size(); ++c)
    if (!g.image_column(c)) volume += g.dx * g.dy * (top[c] - g.z_top);
  return density * volume;
}

// The solid's top as the surface powder touches: on a bed periodic along x or y whose grid
// spans that period, periodic there, its two edge rows one line (bed::HeightMap::
// join_periodic_edges: their mean, the volume kept). On a grid that is not periodic a track
// crossing the seam raises one edge and not the other; left so, powder resting at the low edge
// finds itself inside the step the moment the edges are joined. A periodic grid's image row is
// row 0 (deposits go to row 0), so it takes row 0's heights first and the mean changes nothing.
bed::HeightMap seamed_surface(const bed::Bed& bed, const SubstrateGeometry& g, const TopHeight& top) {
  bed::HeightMap m = top_surface(g, top);
  if (g.periodic_y && !m.empty())
    std::copy_n(m.z.begin(), g.nx, m.z.begin() + static_cast<std::ptrdiff_t>(g.nx * (g.ny - 1)));
  const auto periodic = [&](int axis) {
    return bed.domain.periodic[axis] && m.spans(axis, bed.domain.lower[axis], bed.domain.length(axis));
  };
  m.periodic_x = periodic(0);
  m.periodic_y = periodic(1);
  m.join_periodic_edges();
  return m;
}

void join_seams(const bed::Bed& bed, const SubstrateGeometry& g, TopHeight& top) {
  top = seamed_surface(bed, g, top).z;
}

// The rise of `top` over `before` spread by a Gaussian of standard deviation `length`: each
// column's rise scattered to the columns within 3 length, by weights normalised over those that
// exist (so the volume is kept to round-off at the plate's edges too) and, given `pool`, that it
// marks; a rise with no such column within reach stays where it is. Across a periodic seam the
// columns wrap (the image row takes row 0's heights when the seam is joined).
void level_deposit(const SubstrateGeometry& g, const TopHeight& before, double length, TopHeight& top,
                   const std::vector<std::uint8_t>* pool = nullptr) {
  const auto reach = [&](double d) { return static_cast<long>(std::ceil(3 * length / d)); };
  const long rx = reach(g.dx), ry = reach(g.dy);
  const auto nx = static_cast<long>(g.nx), ny = static_cast<long>(g.ny);
  const auto column = [&](long a, long b) {
    return static_cast<std::size_t>(a) + g.nx * (g.periodic_y ? g.wrap_row(b) : static_cast<std::size_t>(b));
  };
  // The rows b within reach of row j: on the grid, or counted on past a periodic seam.
  const auto rows = [&](long j) {
    return g.periodic_y ? std::pair{j - ry, j + ry} : std::pair{std::max(0L, j - ry), std::min(ny - 1, j + ry)};
  };
  TopHeight levelled = before;
  std::vector<double> w;
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i) {
      if (g.periodic_y && j == ny - 1) continue;  // the image row: row 0's rise is levelled
      const double rise = top[column(i, j)] - before[column(i, j)];
      if (rise == 0) continue;
      double sum = 0;
      w.clear();
      const auto [b0, b1] = rows(j);
      for (long b = b0; b <= b1; ++b)
        for (long a = std::max(0L, i - rx); a <= std::min(nx - 1, i + rx); ++a) {
          const double ex = static_cast<double>(a - i) * g.dx, ey = static_cast<double>(b - j) * g.dy;
          const bool open = !pool || (*pool)[column(a, b)];
          w.push_back(open ? std::exp(-(ex * ex + ey * ey) / (2 * length * length)) : 0.0);
          sum += w.back();
        }
      if (sum == 0) {
        levelled[column(i, j)] += rise;
        continue;
      }
      std::size_t k = 0;
      for (long b = b0; b <= b1; ++b)
        for (long a = std::max(0L, i - rx); a <= std::min(nx - 1, i + rx); ++a)
          levelled[column(a, b)] += rise * w[k++] / sum;
    }
  top = std::move(levelled);
}

// The powder (state 0) the solid's top overlaps by more than capture x r joins it, pass after
// pass until a pass captures none (each raises the top, which may reach further particles). Each
// pass's deposit is levelled over `level` like the scan's, within the columns the scan's deposit
// reached (the pool): a captured particle melts into the pool as a fused one does. Left over its
// footprint its volume would stand ~1.3 r high on a cell or two, a spike the floor contact's
// samples can miss until one strikes it; levelled beyond the pool, its thin tail would reach the
// next resting particle, and capture would run through the whole bed (seen: powder 0.6 mm from
// the nearest track taken).
void capture_buried(const bed::Bed& bed, const SubstrateGeometry& g, const std::vector<double>& mass,
                    double rho0, double capture, double level, const TopHeight& unscanned,
                    Fusion& f, std::vector<std::uint8_t>& keep) {
  std::vector<std::uint8_t> pool(f.top.size());
  for (std::size_t c = 0; c < pool.size(); ++c) pool[c] = f.top[c] > unscanned[c] ? 1 : 0;
  for (std::size_t pass = 0; pass < 100; ++pass) {
    const bed::HeightMap top = seamed_surface(bed, g, f.top);
    f.top = top.z;
    std::vector<std::size_t> taken;
    for (std::size_t i = 0; i < bed.n(); ++i)
      if (stays_in_bed(f.state[i]) && bed::surface_overlap(top, bed.x[i], bed.y[i], bed.z[i], bed.radius[i]) > capture * bed.radius[i])
        taken.push_back(i);
    if (taken.empty()) return;
    const TopHeight before = f.top;
    for (const std::size_t i : taken) {
      f.balled -= f.state[i] == kBalled ? 1 : 0;
      f.state[i] = kFused;
      keep[i] = 0;
      ++f.fused;
      ++f.captured;
      f.powder_mass_after -= mass[i];
      for (const auto& [column, weight] : top_footprint(g, bed.x[i], bed.y[i], bed.radius[i]))
        f.top[column] += mass[i] / rho0 * weight / (g.dx * g.dy);
    }
    if (level > 0) level_deposit(g, before, level, f.top, &pool);
  }
}

Fusion fuse(const bed::Bed& start, const Sinter& sinter, double melt_fraction, double capture,
            double level) {
  require_in_range(melt_fraction > 0 && melt_fraction <= 1, "fuse.melt-fraction", melt_fraction,
                   "0 < f <= 1");
  const SubstrateGeometry& g = sinter.grid();
  const PhaseChange& phase = sinter.material().phase_change();
  const double rho0 = sinter.material().density(sinter.scene().initial_temperature);
  const auto& peak = sinter.particle_max_temperature();
  const auto& mass = sinter.particle_mass();
  const auto& merged = sinter.particle_merged();
  const auto now = sinter.particle_phase();
  const auto& into = sinter.particle_coalesced_into();
  const bed::Bed bed = as_scanned(start, sinter);
  Fusion f;
  f.threshold = phase.melting_point + (melt_fraction - 0.5) * phase.window;
  const std::vector<std::uint8_t> bonded = bonded_melt(bed, sinter, f.threshold);
  f.top = sinter.top_height();
  if (f.top.empty()) f.top.assign(g.nx * g.ny, g.z_top);
  f.solid_mass_before = solid_mass(g, f.top, rho0);
  f.state.assign(bed.n(), 0);
  std::vector<std::uint8_t> keep(bed.n(), 1);
  for (std::size_t i = 0; i < bed.n(); ++i) {
    if (!into.empty() && into[i] != i) {  // in the drop it coalesced into (counted below)
      keep[i] = 0;
      continue;
    }
    if (!merged.empty() && merged[i]) {  // in the pool during the scan: in the top already
      f.state[i] = kFused;
      keep[i] = 0;
      ++f.fused;
      f.merged_mass += mass[i];
      continue;
    }
    f.powder_mass_before += mass[i];
    if (now[i] == 2) {  // vaporised: left the bed
      f.state[i] = kVapour;
      keep[i] = 0;
      ++f.vaporised;
      f.vaporised_mass += mass[i];
      continue;
    }
    if (peak[i] < f.threshold || !bonded[i]) {  // powder, or a ball that met no molten solid
      f.state[i] = peak[i] < f.threshold ? kPowder : kBalled;
      f.balled += f.state[i] == kBalled ? 1 : 0;
      f.powder_mass_after += mass[i];
      continue;
    }
    f.state[i] = kFused;
    keep[i] = 0;
    ++f.fused;
    const double volume = mass[i] / rho0;
    for (const auto& [column, weight] : top_footprint(g, bed.x[i], bed.y[i], bed.radius[i]))
      f.top[column] += volume * weight / (g.dx * g.dy);
  }
  if (!into.empty()) follow_drops(into, f);
  require_in_range(level >= 0 && std::isfinite(level), "fuse.level", level, "a length >= 0 m");
  TopHeight before = sinter.top_height();
  if (before.empty()) before.assign(g.nx * g.ny, g.z_top);
  if (level > 0) level_deposit(g, before, level, f.top);
  join_seams(bed, g, f.top);
  f.melt_top = f.top;
  if (capture > 0) capture_buried(bed, g, mass, rho0, capture, level, before, f, keep);
  f.solid_mass_after = solid_mass(g, f.top, rho0);
  f.powder = keep_particles(bed, keep);
  f.bead = measure_bead(g, f.top);
  return f;
}

}  // namespace powderbed::thermal
