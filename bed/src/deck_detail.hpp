#pragma once
// The pieces of an input deck that the drop deck (deck.cpp) and the spreading deck
// (deck_spread.cpp) share: one mapping of the laws for both (docs/decks.md).
#include <sstream>
#include <string>

#include "powderbed/bed/deck.hpp"

namespace powderbed::bed::deck_detail {

std::string folder_of(const std::string& path);
std::string name_of(const std::string& path);
std::string stem_of(const std::string& path);  // the file's name without its extension
std::string num(double v);                     // %.17g: reads back as the same double
std::size_t type_count(const Bed& bed);        // particle atom types (materials)
// The bed and the laws checked (InputError naming what is wrong).
void check(const Bed& bed, const DeckLaws& laws, const std::string& data_path);
// The comment header (where every number came from, the damping mapping). A DeckFiles with no
// dump (a spreading deck's) leaves out the drop deck's run variables and dump.
void header(std::ostringstream& out, const Bed& bed, const DeckLaws& laws, DeckEngine engine,
            const std::string& data_name, const DeckFiles& files);
// Variables, units, atom style, boundary, read_data, neighbour list.
void setup(std::ostringstream& out, const Bed& bed, const DeckLaws& laws, DeckEngine engine,
           const std::string& data_name, const DeckFiles& files);
// The mean mass and radius of the bed's particles (the one dashpot LIGGGHTS's linear law takes;
// LAMMPS's rolling spring).
struct MeanParticle {
  double mass = 0, radius = 0;
};
MeanParticle mean_particle(const Bed& bed, const DeckLaws& laws);
// LAMMPS's pair style and the box's walls (fix wall/gran granular per fixed axis); returns the
// walls' contact arguments (after `granular`), which a region wall takes too.
std::string lammps_laws(std::ostringstream& out, const Bed& bed, const DeckLaws& laws);
// LIGGGHTS's per-type properties, pair style and the box's primitive walls; the model and its
// settings, which a mesh wall takes too.
struct LiggghtsContact {
  std::string model, settings;
};
LiggghtsContact liggghts_laws(std::ostringstream& out, const Bed& bed, const DeckLaws& laws);
// Gravity, Stokes drag, the integrator (nve, or nve/sphere with rotation) and the time step.
void body_forces(std::ostringstream& out, const DeckLaws& laws);
// The data file (one atom type per material plus the walls') and the deck text, the deck
// committed only once both are written.
void write_deck_files(const Bed& bed, const DeckLaws& laws, const std::string& data_path,
                      const std::string& input_path, const std::string& text);

}  // namespace powderbed::bed::deck_detail
