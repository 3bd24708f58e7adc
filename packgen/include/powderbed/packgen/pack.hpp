#pragma once
// Geometric packing of docs/physics.md §3 ([LP], extended to 3D): particles placed one at a time by
// 0/1/2/3-contact rules, checked by one of three collision back-ends.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/domain.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/packgen/size_sampler.hpp"

namespace powderbed::packgen {

enum class Collision { raster, grid, kdtree };

// Which 3-contact site a 3D approach-3 try takes (docs/physics.md §3 3-contact): `random` picks a random
// particle and two random partners near it ([LP]-style tries); `lowest` fills the lowest free
// site of all (site_heap.hpp: Bennett / Visscher–Bolsterli growth on the floor), O(N) and denser.
enum class SiteOrder { random, lowest };

// One phase of a run: `approach` (0..3 contacts) until the density reaches `until_density`
// (the last phase runs until the stop rule; its until_density is ignored).
struct Phase {
  int approach = 1;
  double until_density = 1.0;
};

struct PackProgress {
  std::size_t n = 0;
  double density = 0;
  double fraction_done = 0;  // 0..1, best guess from the stop rule in force
};

struct PackOptions {
  std::vector<Phase> phases{Phase{}};
  Collision collision = Collision::grid;
  double raster_spacing = 0;          // m, raster only
  int tries = 1000;                   // n_T: positions per size before a new size is drawn
  int directions = 16;                // K: directions (1-contact) / circle angles (2-contact 3D)
  std::size_t count = 0;              // stop at this many particles (0: off)
  double target_density = 0;          // stop at this density (0: off)
  std::size_t max_failures = 100;     // stop after this many consecutive failed placements
  // Front advancing (O(N)): a particle is dropped from the partner list after this many
  // consecutive failed tries around it (0: never, every placed particle stays a partner).
  int retire_after = 32;
  double edge_fraction = 0;           // fraction of 0-contact tries in the band along walls
  SiteOrder site_order = SiteOrder::lowest;  // 3D approach 3 only
  SizeSampling size_sampling = SizeSampling::iid;  // size_sampler.hpp
  // Lowest-site growth: fraction of the floor area first covered by particles dropped at
  // random onto the floor (0: growth starts as soon as the first sites exist).
  double floor_seed = 0;
  std::size_t raster_max_bytes = std::size_t{2} << 30;
  // Unit-slip guard (docs/hardening.md): a domain that would hold more than this many particles
  // of the PSD's mean size is refused as a likely metres-for-micrometres slip unless
  // allow_huge (packgen --allow-huge) says the size is meant.
  double max_particles = 1e9;
  bool allow_huge = false;
  // Called about every 0.25 s when set (the app shows progress with an ETA).
  std::function<void(const PackProgress&)> progress;
};

struct PackResult {
  bed::Bed bed;
  std::size_t attempts = 0;            // candidate positions tested for collision
  std::size_t tries = 0;               // tries (one partner choice or one 0-contact position)
  std::size_t failed_placements = 0;   // sizes given up after n_T tries
  std::size_t failures_in_a_row = 0;   // at the end of the run
  std::size_t retired = 0;             // particles dropped from the partner list
  std::size_t sites = 0;               // lowest-site growth: free sites found
  // Raster only (checked against the exact grid): positions the raster refused that were
  // valid, and positions it accepted that overlap.
  std::size_t refused_valid = 0;
  std::size_t accepted_overlapping = 0;
  double wall_time = 0;                // s
  bool target_reached = true;          // false when --count / --target-density was not reached
  std::string stop_reason;             // "count", "target density", "max failures"
};

// Throws InputError (one line naming the option) for options that cannot work with this
// domain and PSD: approach outside 0..3 or 3 in 2D, tries/directions < 1, target density
// outside (0, 1), a domain smaller than the smallest particle, raster spacing <= 0 or too fine.
void validate(const bed::Domain& domain, const bed::Psd& psd, const PackOptions& options);

// "0:0.3,1" -> phases (approach[:until_density], densities increasing in (0, 1)).
std::vector<Phase> parse_phases(const std::string& text, const std::string& option = "--phases");
Collision parse_collision(const std::string& text, const std::string& option = "--collision");
const char* collision_name(Collision c);
SiteOrder parse_site_order(const std::string& text, const std::string& option = "--site-order");
const char* site_order_name(SiteOrder s);

// Packs the domain (docs/physics.md §3); same inputs and seed give the same bed bit for bit, and the
// exact back-ends (grid, kdtree) give the same bed as each other.
PackResult pack(const bed::Domain& domain, const bed::Psd& psd, const PackOptions& options,
                std::uint64_t seed);

}  // namespace powderbed::packgen
