#pragma once
// Input decks for LAMMPS and LIGGGHTS (docs/decks.md): a bed's LAMMPS data file plus an in.*
// script with the laws of the scene that made it (or would move it), so a study can go to a
// cluster. The deck runs in its own folder: `lmp -in in.bed.lammps`, `liggghts -in
// in.bed.liggghts`, either under mpirun.
#include <cstdint>
#include <string>
#include <vector>

#include "powderbed/bed/bed.hpp"

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

}  // namespace powderbed::bed
