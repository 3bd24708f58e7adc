#pragma once
// Spreading a powder layer with a recoater, layer after layer (docs/deposit-spread.md): the
// granular loop with particle rotation, static (history) or sliding friction, rolling
// resistance, the plate (the box's floor), the box's top and the side faces that are not
// periodic, and the moving tool of recoater.hpp. A run of its own beside run_deposition: its
// contact is composed of sub-models chosen once per run (dem/src/contact_model.hpp), and it
// sums every particle's forces in one fixed order on any number of threads, so that a run is
// reproducible bit for bit and a continued run equals the uninterrupted one.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/height_map.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/recoater.hpp"
#include "powderbed/dem/rest_criteria.hpp"
#include "powderbed/dem/scene.hpp"

namespace powderbed::bed {
class H5Output;
}

namespace powderbed::dem {

// The powder supply of a layer: the app fills `region` (a box in front of the tool, on the
// plate or on the powder already there) with new particles without overlap and returns them
// (ids are renumbered after the bed's). Throws InputError when they do not fit.
using SupplyMaker = std::function<bed::Bed(const bed::Domain& region, std::uint64_t layer)>;

struct ToolForceSample {
  std::uint64_t layer = 0;
  double time = 0;    // s
  double x = 0;       // tool position, m
  double force[3] = {0, 0, 0};  // force of the tool on the powder, N
};

// Everything a layer's end leaves for the next (the bed file's /restart group): with the bed's
// positions and velocities this is the whole state, so a run continued from it equals the
// uninterrupted one bit for bit.
// Values of SpreadState::wall_history per particle (above).
inline constexpr std::size_t kWallHistoryValues = 7 * 6 + 4 * 7;

struct SpreadState {
  std::uint64_t layers_done = 0;
  std::uint64_t step = 0;         // steps since the first layer began
  double dt = 0;                  // s, kept so a continued run uses the same step
  double time = 0;                // simulated s (step * dt)
  double tool_x = 0;              // where the tool stopped, m
  double plate_offset = 0;        // how far the plate has gone down, m (layers_done - 1) * layer
  std::vector<double> wx, wy, wz; // angular velocity per particle, rad/s
  // Contacts with history, by particle id: ids (i < j in index order), F_s and M_r, 3 each.
  std::vector<std::uint64_t> pair_ids;   // 2 per contact
  std::vector<double> pair_history;      // 6 per contact
  // Wall contacts per particle, kWallHistoryValues values: the plate, tool, x low, x high, y low,
  // y high and top, 6 values each; then the floor's contacts, 4 x (the facet touched + 1, 6).
  std::vector<double> wall_history;
  // The solid the powder rests on (SpreadSettings::floor; empty: the flat plate). A continued
  // run spreads on it when its settings give none.
  bed::HeightMap floor;
};

struct LayerSummary {
  std::uint64_t layer = 0;
  std::size_t n = 0;              // particles after the layer
  std::size_t supplied = 0;       // particles the layer's supply added
  std::uint64_t steps = 0;
  double sim_time = 0;            // s, at the layer's end
  double wall_time = 0;           // s
  double tool_bottom = 0;         // z of the tool's lowest point above the original plate, m
  double max_tool_force = 0;      // N, largest |F| of the tool on the powder
  double mean_tool_force_x = 0;   // N, mean x force while the tool moved
  double kinetic_energy = 0;      // J, at the end
  double max_speed = 0;           // m/s, at the end
  // Solid fraction of the particles whose centres lie under the tool's lowest point, between
  // the supply's back (or the dosing platform's edge past it) and the tool's end (by centres,
  // the quick look; bedstat measures layers).
  double density_under_gap = 0;
  std::size_t lost = 0;           // centres below the plate or outside non-periodic faces
  std::size_t overflow = 0;       // removed past the tool's end (SpreadSettings::remove_overflow)
  // Removed at the layer's start where the dosing platform rose into them
  // (SpreadSettings::platform_edge): powder that had rolled back onto it below the new top.
  std::size_t under_platform = 0;
  std::size_t frozen = 0;         // particles frozen through the layer (SpreadSettings::freeze_depth)
  // Steps x frozen particles the tool overlapped (it passes through them without a force): 0
  // when what froze lay out of the tool's reach, as it must (docs/deposit-spread.md "Many layers").
  std::uint64_t frozen_tool_contacts = 0;
  // SpreadSettings::sleep: the particles asleep, averaged over the layer's steps, and how many
  // times particles fell asleep or woke (each time the bed is reordered and the list rebuilt).
  double asleep = 0;
  std::uint64_t sleep_changes = 0;
  // SpreadSettings::until_rest: how long the layer settled after the tool stopped (the tool's
  // settle and what it took on to rest), and whether it came to rest within the cap.
  double settle_time = 0;  // s
  bool at_rest = false;
};

// Powder at rest sleeps (docs/deposit-spread.md "Sleeping powder"; dem/src/sleep.hpp): a
// particle that has moved slower than `speed` (its centre, and its surface about the centre)
// for `steps` steps in a row, wholly under the tool's lowest point, and touches only particles
// that have too (or sleep), stops being integrated; its contacts with other sleepers are no
// longer computed (their forces cannot change while neither moves). It wakes, with the
// sleepers it touches, when an awake particle touching it moves faster than `wake_speed`.
struct SleepSettings {
  bool on = false;
  double speed = 1e-4;         // m/s
  double wake_speed = 1e-3;    // m/s
  std::uint64_t steps = 1000;  // in a row at rest
};

struct SpreadSettings {
  Recoater tool;
  bool with_tool = true;          // false: a granular run of t_end without tool or supply
  // false: the particles do not turn, and friction slides at their centres' relative velocity,
  // as in the drop solver's model ([GZ]); then friction.model = history and rolling are refused.
  bool rotation = true;
  // Supply region along x (its y extent is the box's, its z starts on the plate or on the
  // powder there and is `supply_height` tall); the maker fills it. No maker: no supply (the
  // bed holds the powder).
  double supply_x0 = 0, supply_x1 = 0, supply_height = 0;
  SupplyMaker supply;
  // The dosing platform's edge along x (docs/deposit-spread.md "The dosing platform"): the
  // floor at x <= edge stands at the tool's bottom, each layer, the fixed table a machine doses
  // on beside its build chamber, so the supply lies on it and not on the earlier layers'
  // powder. Particles it rises into at a layer's start are removed (LayerSummary::under_platform).
  // The part's floor in the state (SpreadState::floor) stays the solid's. Unset: no platform, the
  // supply falls on the plate or the powder there. supply_x1 <= edge < tool.end.
  std::optional<double> platform_edge;
  std::uint64_t layers = 1;       // layers to spread in this run
  // After each layer, remove the powder the tool pushed past its end (centres in front of its
  // front face where it stopped): the machine's overflow slot, so that the excess does not pile
  // up over many layers. false keeps every particle.
  bool remove_overflow = true;
  // With remove_overflow: remove only the powder past the tool's end above the tool's bottom,
  // the edge of a machine's build chamber, and keep what lies under it, so that the bed reaches
  // the box's far wall as a machine's bed stands against its chamber's wall. false: everything
  // past the end goes, and the bed ends in a free face there (docs/results/spread-layers.md).
  bool chamber = false;
  double layer_thickness = 0;     // m, how far the plate goes down between layers
  // > 0: at each layer's start, the particles whose centres lie more than this (m) below the
  // tool's bottom are frozen for the rest of the run: they keep their places with no velocity,
  // the moving particles touch them as fixed spheres, and they are not integrated, nor are
  // their contacts among themselves computed (LIGGGHTS's `fix freeze` with the frozen group's
  // own pairs excluded from the neighbour list). Powder that deep lies still under a passing
  // blade, and without freezing every earlier layer is integrated every step, so N layers cost
  // ~N^2 (docs/deposit-spread.md "Many layers"). 0: off, every particle moves.
  double freeze_depth = 0;
  SleepSettings sleep;
  // After the tool's settle, each layer settles on until the powder behind the tool rests: its
  // fastest particle (centres short of the tool's back) slower than rest.max_speed for
  // rest.window, checked about ten times a window; rest_cap s of settling at most. A laser
  // scans a bed at rest (machines recoat seconds before they scan); a fixed settle of a few
  // milliseconds leaves the last powder the blade let fall still in the air
  // (docs/deposit-spread.md "Settling to rest").
  bool until_rest = false;
  RestCriteria rest;
  double rest_cap = 0.1;  // s
  // The solid the powder is spread on (the fused top of earlier layers, build): a wall of
  // triangles on the nodes (HeightMap::surface), touched at each local minimum of the distance
  // (bed/surface_contacts.hpp), each contact with its own history; empty: the flat plate
  // at the box's floor (or the restart's floor, when it has one). Heights at or above the box's
  // floor.
  bed::HeightMap floor;
  double young_scale = 1;
  double dt = 0;                  // s; 0: 0.2 x the Rayleigh step (time_step.hpp)
  bool unsafe_dt = false;
  // OpenMP threads of the particle and pair loops; 0: OpenMP's default. The bed is the same bit
  // for bit for any count (each particle's forces are summed in one fixed order). Beds with
  // fewer particles than parallel_min_particles at a layer's start run on one thread: a fork
  // and barrier cost microseconds, and a step makes several (RunSettings's threshold).
  int threads = 0;
  std::size_t parallel_min_particles = 4096;
  double skin = 0;                // m; 0: 0.5 x the largest radius (less on a narrow periodic axis)
  double t_end = 0;               // without tool: simulated time, s
  // Gravity tilted by this angle about +y (rad): g = g (sin a, 0, -cos a), a plate inclined
  // by a (tests of friction on a slope).
  double gravity_tilt = 0;
  // Every step when set, with the whole step's velocities; true stops the run. The velocities
  // are then brought to each whole step (the second half kick is not merged with the next
  // step's first), so a watched run's last bits differ from an unwatched one's.
  std::function<bool(std::uint64_t step, double time, const bed::Bed& bed,
                     const std::vector<double>& wy)>
      observer;
  // Every frame_every steps (and, without a tool, at the run's first step) when set: the bed with the
  // whole step's velocities, in a copy, so that the run's bits are the same with or without it
  // (unlike the observer's); true stops the run. What a drop's rest test and trajectory read.
  std::function<bool(std::uint64_t step, double time, const bed::Bed& bed)> frame;
  std::uint64_t frame_every = 0;
  std::uint64_t tool_force_every = 0;  // steps between samples (0: none)
  std::function<void(const ToolForceSample&)> tool_force;
  // After each layer, with the bed and the state a restart needs.
  std::function<void(const LayerSummary&, const bed::Bed&, const SpreadState&)> layer_done;
  // Every progress_every steps: the fraction of the layer (or of t_end) done and the kinetic
  // energy (J). With until_rest a layer is its pass and rest_cap of settling at most, so the
  // fraction never goes back; a layer that rests before the cap ends short of 1.
  std::function<void(double fraction, double kinetic_energy)> progress;
  std::uint64_t progress_every = 2000;
  // The thermo table (diagnostics.hpp ThermoRow, with the layer and the tool's x), when set: a
  // row every thermo_every steps of the run (0: thermo_interval of this run's steps, layers x a
  // layer's) and at each layer's end. It reads the state only (the kinetic energy at the last
  // whole step, as progress's), so the run's bits are the same with or without it.
  ThermoFn thermo;
  std::uint64_t thermo_every = 0;
};

struct SpreadSummary {
  std::vector<LayerSummary> layers;
  std::uint64_t steps = 0;
  double sim_time = 0, dt = 0, dt_stable = 0, wall_time = 0;
  const char* dt_limited_by = "none";  // TimeStepBound::limited_by of dt_stable
  double dt_limiting_radius = 0;       // m, TimeStepBound::limiting_radius
  double particle_steps_per_s = 0;
  double max_overlap = 0;         // largest overlap / smaller radius at the end (pairs)
  std::uint64_t neighbour_rebuilds = 0;
  SpreadState state;              // at the end (what the last bed's /restart holds)
};

// Spreads settings.layers layers on `bed` (in place; it may start empty), continuing from
// `restart` when given (the state a bed's /restart group holds). Throws InputError for a bad
// tool (gap <= 0, start >= end, speed <= 0, a blade thinner than twice its edge radius), a tool
// that starts inside the powder, a supply region that overlaps the tool or leaves the box,
// and NumericalError when the state goes
// non-finite.
SpreadSummary run_spread(bed::Bed& bed, const Scene& scene, const SpreadSettings& settings,
                         const SpreadState* restart = nullptr);

// Appends layer `layer`'s supply to `bed` as run_spread does at the layer's start: the region
// supply_x0..supply_x1 across the box, on the plate, the floor's highest point or the powder
// already under it, supply_height tall, filled by settings.supply (ids after the bed's, at rest);
// returns how many came (0 without a maker). What an engine other than run_spread needs to
// start a layer with deposit's supply (deck export, build --spread-engine). Throws InputError for
// a region in front of no tool or out of the box.
std::size_t add_layer_supply(bed::Bed& bed, const SpreadSettings& settings,
                             const bed::HeightMap& floor, std::uint64_t layer);
// Removes the particles whose `keep` is 0 from the bed and from the state a restart needs (their
// rotation, wall history and every contact they had), keeping the others' order; returns how
// many went. What the overflow slot takes, and what fusion turns into solid (build).
std::size_t remove_particles(bed::Bed& bed, SpreadState& state, const std::vector<char>& keep);

// A spread's bed file: the bed and its /restart group written to one temporary and renamed into
// place once, so a kill or a full disk leaves the old file or the whole new one, never a bed
// without its state. Read back with read_spread_state (InputError naming the file when the
// group is missing or inconsistent with the bed). `more` adds a caller's groups to the same
// file before it is renamed (build: the part's record).
void write_spread_bed(const std::string& h5_path, const bed::Bed& bed, const SpreadState& state,
                      const std::function<void(bed::H5Output&)>& more = {});
bool has_spread_state(const std::string& h5_path);
SpreadState read_spread_state(const std::string& h5_path, const bed::Bed& bed);

}  // namespace powderbed::dem
