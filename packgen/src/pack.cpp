// The packing run of docs/physics.md §3: sizes from the PSD, one placement algorithm per phase
// (the 0/1/2/3-contact approaches, contact_approaches.hpp, or lowest-site growth,
// lowest_site_growth.hpp) over the shared placement core (placement_core.hpp), the stop rules
// and the progress reports. The run is a template over the collision back-end, dispatched once
// in pack(), so no test in the hot loop goes through a virtual call.
#include <algorithm>
#include <array>
#include <chrono>
#include <utility>

#include "contact_approaches.hpp"
#include "lowest_site_growth.hpp"
#include "placement_core.hpp"
#include "powderbed/packgen/cell_grid.hpp"
#include "powderbed/packgen/kdtree_index.hpp"
#include "powderbed/packgen/pack.hpp"
#include "powderbed/packgen/raster_grid.hpp"
#include "powderbed/packgen/size_sampler.hpp"

namespace powderbed::packgen {

namespace {

using detail::ContactApproaches;
using detail::LowestSiteGrowth;
using detail::PlacementCore;

// The collision back-ends behind one small interface: insert(i), fits(x, y, z, r, after),
// `approximate`. `after`: the exact back-ends test only particles with a larger index (-1: all),
// the raster tests its whole status grid (its answer is not the exact one the skipped particles
// passed). They live in this file's unnamed namespace so that the placement classes
// instantiated over them are local to it: GCC then inlines the helpers called from one place
// (callgrind, 1e4 monodisperse spheres: 9 % more instructions with the back-ends in a header).
struct GridBackend {  // the exact partner grid doubles as the collision grid
  static constexpr bool approximate = false;
  const CellGrid& grid;
  void insert(std::uint32_t) {}
  bool fits(double x, double y, double z, double r, std::int64_t after = -1) const {
    return grid.fits(x, y, z, r, after);
  }
};

struct KdTreeBackend {
  static constexpr bool approximate = false;
  KdTreeIndex index;
  void insert(std::uint32_t i) { index.insert(i); }
  bool fits(double x, double y, double z, double r, std::int64_t after = -1) const {
    return index.fits(x, y, z, r, after);
  }
};

struct RasterBackend {
  static constexpr bool approximate = true;
  RasterGrid raster;
  void insert(std::uint32_t i) { raster.insert(i); }
  bool fits(double x, double y, double z, double r, std::int64_t = -1) const {
    return raster.fits(x, y, z, r);
  }
};

// Lowest-site growth is on when a phase is 3D approach 3 with SiteOrder::lowest; it then finds
// the sites of every particle placed, in earlier phases too.
bool grows_lowest_sites(const bed::Domain& domain, const PackOptions& o) {
  for (const Phase& ph : o.phases) {
    if (domain.dimension == 3 && ph.approach == 3 && o.site_order == SiteOrder::lowest) {
      return true;
    }
  }
  return false;
}

// The last kFailureWindow placements, failed or not (pack.hpp: the failure window); before
// kFailureWindow draws the missing ones count as placed.
class FailureWindow {
 public:
  void add(bool failed) {
    failures_ += std::size_t{failed} - std::size_t{ring_[next_]};
    ring_[next_] = failed;
    next_ = (next_ + 1) % kFailureWindow;
  }
  std::size_t failures() const { return failures_; }

 private:
  std::array<bool, kFailureWindow> ring_{};
  std::size_t next_ = 0, failures_ = 0;
};

template <class Backend>
class Packer {
 public:
  Packer(const bed::Domain& domain, const bed::Psd& psd, const PackOptions& options,
         std::uint64_t seed, Particles& particles, CellGrid& partners, Backend& backend)
      : o_(options),
        core_(domain, psd, options, seed, particles, partners, backend),
        sizes_(psd, options.size_sampling, core_.rng()),
        contacts_(core_),
        growth_(core_),
        lowest_(grows_lowest_sites(domain, options)),
        max_failures_(options.max_failures.value_or(kMaxFailures)),
        window_(!options.max_failures && lowest_) {
    core_.on_placed([this](std::uint32_t i) {
      contacts_.placed(i);
      if (lowest_) growth_.placed(i);
    });
  }

  Packer(const Packer&) = delete;  // the on-placed hook holds `this`
  Packer& operator=(const Packer&) = delete;

  PackResult run();

 private:
  using Clock = std::chrono::steady_clock;

  bool stopped();
  bool place_one(int approach, double r);
  double fraction_done() const;
  void report_progress();
  PackResult finish();

  const PackOptions& o_;
  PlacementCore<Backend> core_;
  SizeSampler sizes_;
  ContactApproaches<Backend> contacts_;
  LowestSiteGrowth<Backend> growth_;
  bool lowest_;
  std::size_t max_failures_;  // --max-failures, else kMaxFailures
  bool window_;               // the failure window is in force (pack.hpp)
  FailureWindow recent_;
  Clock::time_point start_, last_report_;  // of run()
};

// Whether a stop rule holds (docs/physics.md §3): --count, --target-density, or --max-failures
// sizes in a row that found no place, or by default the failure window (pack.hpp); the last two
// mean the target, if any, was missed.
template <class Backend>
bool Packer<Backend>::stopped() {
  PackResult& result = core_.result();
  if (o_.count > 0 && core_.particles().size() >= o_.count) {
    result.stop_reason = "count";
    return true;
  }
  if (o_.target_density > 0 && core_.density() >= o_.target_density) {
    result.stop_reason = "target density";
    return true;
  }
  if (result.failures_in_a_row >= max_failures_) {
    result.stop_reason = "max failures";
  } else if (window_ && recent_.failures() > kFailureWindow / 2) {
    result.stop_reason = "failure window";
  } else {
    return false;
  }
  result.target_reached = o_.count == 0 && o_.target_density == 0;
  return true;
}

// One drawn size: lowest-site growth in its phase, else up to n_T tries of the phase's approach.
template <class Backend>
bool Packer<Backend>::place_one(int approach, double r) {
  if (!core_.size_fits(r)) return false;
  if (approach == 3 && lowest_) return growth_.try_size(r);
  bool placed = false;
  for (int t = 0; t < o_.tries && !placed && !contacts_.exhausted(approach); ++t) {
    placed = contacts_.try_once(approach, r);
  }
  return placed;
}

template <class Backend>
PackResult Packer<Backend>::run() {
  start_ = last_report_ = Clock::now();
  std::size_t phase = 0;
  for (std::size_t loop = 0; !stopped(); ++loop) {
    while (phase + 1 < o_.phases.size() && core_.density() >= o_.phases[phase].until_density) {
      ++phase;
    }
    const double r = sizes_.next(core_.rng());
    PackResult& result = core_.result();
    const int approach = o_.phases[phase].approach;
    const bool placed = place_one(approach, r);
    if (placed) {
      result.failures_in_a_row = 0;
    } else {
      ++result.failed_placements;
      ++result.failures_in_a_row;
    }
    // Only growth's draws: a failure of an earlier phase (n_T random tries) says nothing about
    // the front having met the lid.
    if (approach == 3 && lowest_) recent_.add(!placed);
    if (o_.progress && loop % 256 == 0) report_progress();
  }
  return finish();
}

// Best guess of the fraction done, from the stop rule in force.
template <class Backend>
double Packer<Backend>::fraction_done() const {
  if (o_.count > 0) return double(core_.particles().size()) / double(o_.count);
  if (o_.target_density > 0) return core_.density() / o_.target_density;
  const double in_a_row = double(core_.result().failures_in_a_row) / double(max_failures_);
  if (!window_) return in_a_row;
  return std::max(in_a_row, double(recent_.failures()) / double(kFailureWindow / 2 + 1));
}

// Calls o.progress about every 0.25 s.
template <class Backend>
void Packer<Backend>::report_progress() {
  const auto now = Clock::now();
  if (now - last_report_ <= std::chrono::milliseconds(250)) return;
  last_report_ = now;
  PackProgress pr;
  pr.n = core_.particles().size();
  pr.density = core_.density();
  pr.fraction_done = fraction_done();
  o_.progress(pr);
}

template <class Backend>
PackResult Packer<Backend>::finish() {
  PackResult& result = core_.result();
  result.wall_time = std::chrono::duration<double>(Clock::now() - start_).count();
  const Particles& p = core_.particles();
  bed::Bed& bed = result.bed;
  bed.domain = core_.domain();
  bed.x = p.x;
  bed.y = p.y;
  bed.z = p.z;
  bed.radius = p.r;
  bed.id.resize(p.size());
  for (std::size_t i = 0; i < bed.id.size(); ++i) bed.id[i] = i;
  return std::move(result);
}

}  // namespace

PackResult pack(const bed::Domain& domain, const bed::Psd& psd, const PackOptions& options,
                std::uint64_t seed) {
  validate(domain, psd, options);
  Particles particles;
  CellGrid partners(domain, psd.min_radius(), psd.max_radius(), particles);
  switch (options.collision) {
    case Collision::raster: {
      RasterBackend backend{
          RasterGrid(domain, options.raster_spacing, particles, options.raster_max_bytes)};
      return Packer<RasterBackend>(domain, psd, options, seed, particles, partners, backend).run();
    }
    case Collision::kdtree: {
      KdTreeBackend backend{KdTreeIndex(domain.dimension, psd.max_radius(), particles)};
      return Packer<KdTreeBackend>(domain, psd, options, seed, particles, partners, backend).run();
    }
    case Collision::grid:
      break;
  }
  GridBackend backend{partners};
  return Packer<GridBackend>(domain, psd, options, seed, particles, partners, backend).run();
}

}  // namespace powderbed::packgen
