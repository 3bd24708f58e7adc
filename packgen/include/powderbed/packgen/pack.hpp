#pragma once
// Geometric packing of docs/physics.md §3 ([LP], extended to 3D): particles placed one at a time by
// 0/1/2/3-contact rules, checked by one of three collision back-ends.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
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

// K's defaults (--directions), by dimension. 2D: [LP] try "a set of directions" around the
// partner without giving K; 10 evenly spaced angles give the paper's 1-contact density of
// 0.62-0.64 on its square (docs/results/packgen-2d-study.md: K = 10 packs 0.637, K = 16 0.647).
// 3D: random directions on the sphere (and 16 circle angles for 2-contact), a different rule,
// keeps the library's first value, 16.
constexpr int kDirections2D = 10;
constexpr int kDirections3D = 16;

// The default stop rule (docs/physics.md §3 "Stop rules"), used when max_failures is unset:
// kMaxFailures consecutive failed sizes ([LP]'s saturation test, the rule of the contact
// approaches), and for lowest-site growth also the failure window: more than half of the last
// kFailureWindow drawn sizes found no place. A size fails in lowest-site growth only when no
// known site and no floor spot takes it, i.e. the front has met the lid for that size; each
// size placed after that is one that fitted where larger ones did not, so running on to 100
// failures in a row packs the last layers with the small tail of the PSD (GenGeo scene of
// docs/results/packgen-speed.md, seeds 1-10: KS 0.08-0.17 against 0.02-0.05 at the first
// failure). The window stops once most draws fail: that keeps most of the top layer the front
// was filling (median phi 0.519 against 0.498 at the first failure and 0.536 at 100 in a row)
// at KS 0.03-0.08 and 188 attempts per sphere (174 and 235), and, unlike a cap on the total failures or on the density gained per attempt,
// it does not stop a mixture whose large sizes fail all along the growth (a 1:10 bimodal mix
// fails 9 % of its draws from the start, far from half).
constexpr std::size_t kMaxFailures = 100;
constexpr std::size_t kFailureWindow = 20;

struct PackOptions {
  std::vector<Phase> phases{Phase{}};
  Collision collision = Collision::grid;
  double raster_spacing = 0;          // m, raster only
  int tries = 1000;                   // n_T: positions per size before a new size is drawn
  // K: directions (1-contact) / circle angles (2-contact 3D); unset: kDirections2D or
  // kDirections3D by the domain's dimension (directions_for).
  std::optional<int> directions;
  std::size_t count = 0;              // stop at this many particles (0: off)
  double target_density = 0;          // stop at this density (0: off)
  // Stop after this many consecutive failed placements; unset: the default rule (kMaxFailures,
  // and the failure window in lowest-site growth).
  std::optional<std::size_t> max_failures;
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
  // "count", "target density", "max failures", "failure window"
  std::string stop_reason;
};

// K for a run in `dimension` (2 or 3): options.directions, else that dimension's default.
int directions_for(const PackOptions& options, int dimension);

// Throws InputError (one line naming the option) for options that cannot work with this
// domain and PSD: approach outside 0..3 or 3 in 2D, tries/directions < 1, target density
// outside (0, 1), both a count and a target density, a domain smaller than the smallest
// particle or holding more than max_particles (a unit slip), a count above 2^20 that cannot fit
// (check_count_fits), raster spacing <= 0 or too fine.
void validate(const bed::Domain& domain, const bed::Psd& psd, const PackOptions& options);

// Throws InputError when `count` particles cannot fit in the domain even at density 1 (its
// measure over the PSD's smallest particle's). validate() applies it only to counts whose
// reservation matters (above 2^20): below that the packing finds out and its caller says how
// many were placed (deposit's insertion); packgen applies it to any --count.
void check_count_fits(const bed::Domain& domain, const bed::Psd& psd, std::size_t count);

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
