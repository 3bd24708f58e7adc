#pragma once
// Input decks for LAMMPS and LIGGGHTS (docs/decks.md): a bed's LAMMPS data file plus an in.*
// script with the laws of the scene that made it (or would move it), so a study can go to a
// cluster. The deck runs in its own folder: `lmp -in in.bed.lammps`, `liggghts -in
// in.bed.liggghts`, either under mpirun.
#include <cstdint>
#include <string>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/height_map.hpp"

namespace powderbed::bed {

enum class DeckEngine { lammps, liggghts };
// "lammps" | "liggghts"; throws InputError naming `option` otherwise.
DeckEngine parse_deck_engine(const std::string& text, const std::string& option);
const char* deck_engine_name(DeckEngine engine);

// The laws a deck writes, in SI units, as deposit's scene states them (dem/scene.hpp); an
// effect that is off is 0 (friction, damping, gravity, drag) or false (contact, walls).
struct DeckLaws {
  std::string law = "hertz";  // normal law of pairs and walls: "hertz" | "linear"
  double young = 0, poisson = 0;            // particles' E (Pa), nu
  double wall_young = 0, wall_poisson = 0;  // walls' E (Pa), nu
  double young_scale = 1;   // hertz: the run uses E / young_scale (particles and walls)
  double stiffness = 0;     // linear: k_n, N/m
  double damping_ratio = 0; // zeta, pairs and walls
  double friction = 0;      // mu_d, pairs and walls
  double gravity = 0;       // m/s^2, along -z
  double viscosity = 0;     // Stokes drag -6 pi mu_f r v, Pa s
  bool contact = true;      // particle-particle contact
  bool walls = true;        // contact with the domain's non-periodic faces
  double dt = 0;            // s
  std::vector<double> density;  // kg/m^3 per atom type (type = material index + 1), or one
  std::uint64_t steps = 1000;   // the deck's default run length (variable NSTEPS)
  // Spreading decks (deposit's spread loop, docs/deposit-spread.md): particle rotation (fix
  // nve/sphere), static friction (friction.model = history: LIGGGHTS `tangential history`) and
  // EPSD rolling resistance mu_r (`rolling_friction epsd`, viscous part zeta). A drop has none.
  bool rotation = false;
  bool tangential_history = false;
  double rolling = 0;
  // Header comment lines: where each number came from (scene file, bed, option, default).
  std::vector<std::string> origin;
};

// The deck's files for a data file path "dir/bed.data": the input "dir/in.bed.<engine>" and
// the dump it writes, "bed.<engine>.lammpstrj", and the data file it writes at the end,
// "bed.<engine>.final.data" (both in dir, named relative to it).
struct DeckFiles {
  std::string input;
  std::string dump;
  std::string final_data;
};
DeckFiles deck_files(const std::string& data_path, DeckEngine engine);

// Writes the data file (one atom type per material plus one for the walls, each type's density,
// velocities, periodic axes) and the input deck beside it. Throws InputError for a 2D bed, a
// dt <= 0, a law or zeta the engine cannot take (deck_damping.hpp), a missing density.
void write_deck(const Bed& bed, const DeckLaws& laws, DeckEngine engine,
                const std::string& data_path);

// A spreading deck (docs/decks.md "Spreading decks"): the recoater of deposit's scene
// (dem/recoater.hpp's rounded box, as plain numbers: bed/ does not depend on dem/), the supply and
// the layer loop. LIGGGHTS: the tool an STL beside the deck moved by fix move/mesh, the solid
// under the powder a second STL. LAMMPS: the tool a region (block or cylinder along y) moved by
// its move/rotate keywords under fix wall/gran/region; no raised floor, no rounded blade edges.
struct DeckTool {
  bool roller = false;
  // The cross-section in the x-z plane: the points within `rounding` of the rectangle
  // |x - x_c| <= half_width, bottom + rounding <= z <= bottom + rounding + height (roller:
  // half_width = height = 0, rounding = R; blade: the box's height above its edges).
  double half_width = 0, rounding = 0;
  double gap = 0;                // the lowest point above the plate in layer 1, m
  double start = 0, end = 0;     // x of the centre, m
  double speed = 0;              // m/s along +x
  double omega = 0;              // roller spin about +y, rad/s
  double delay = 0, settle = 0;  // s
};
struct SpreadDeck {
  DeckEngine engine = DeckEngine::liggghts;
  DeckTool tool;
  std::uint64_t layers = 1;
  double layer_thickness = 0;  // m: the tool rises this much each layer (the plate's descent)
  bool remove_overflow = true; // delete what lies past the tool's front where it stopped
  // Layers 2.. take their supply from LIGGGHTS's insert/pack (LAMMPS: create_atoms random) in x0..x1 across the box, from the
  // tool's bottom of the layer before, `height` tall: `count` particles or `volume` m^3 of the
  // PSD's `bins` (radius, number fraction). Layer 1's supply is in the bed (deposit placed it).
  double supply_x0 = 0, supply_x1 = 0, supply_height = 0;
  std::size_t supply_count = 0;
  double supply_volume = 0;
  std::vector<std::pair<double, double>> psd_bins;
  std::uint64_t seed = 1;
  HeightMap floor;  // the solid under the powder (empty: the plate)
};
// The files a spreading deck for "dir/bed.data" writes besides deck_files(): the tool's and the
// floor's STL (LIGGGHTS), and the bed after layer k ("bed.<engine>.layer-K.lammpstrj"); full paths.
std::string spread_tool_stl(const std::string& data_path);
std::string spread_floor_stl(const std::string& data_path);
std::string spread_layer_dump(const std::string& data_path, std::uint64_t layer, DeckEngine engine);
// Writes the data file, the deck and (LIGGGHTS) the STL files. Throws InputError as write_deck
// does, for a tool that leaves the box in x (LIGGGHTS) or rises above its top, a supply region
// out of the box, and for LAMMPS a raised floor or a blade with rounded edges.
void write_spread_deck(const Bed& bed, const DeckLaws& laws, const SpreadDeck& spread,
                       const std::string& data_path);

}  // namespace powderbed::bed
