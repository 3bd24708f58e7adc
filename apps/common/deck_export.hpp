#pragma once
// LAMMPS / LIGGGHTS deck export for deposit (--export-deck) and bedconv (--deck): a deposit
// scene's laws as bed::DeckLaws, each number with where it came from (docs/decks.md).
#include <string>
#include <vector>

#include "common/options.hpp"
#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/deck.hpp"
#include "powderbed/dem/scene.hpp"

namespace powderbed::app {

// A deposit scene as far as a deck needs it, and where each of its keys was last set.
struct DeckScene {
  dem::Scene scene;
  double young_scale = 1;
  double dt = 0;  // 0: not given (bedconv takes deposit's default step for the bed)
  std::vector<std::pair<std::string, std::string>> origin;  // key -> source
};

// The keys of deposit's scene (its --config INI and a bed's /provenance scene) that a deck
// uses: material.*, wall.*, fluid.viscosity, gravity, contact.law, contact.stiffness,
// young-scale, dt, effects.*. Applies those present in `ini` (key = value lines; [section]
// headers prefix the keys as in --config) over `scene`, noting `source` as their origin; other
// keys are ignored. Throws InputError naming `source` and the key for a value that is not a
// number (or true/false, hertz/linear).
void apply_scene_text(const std::string& ini, const std::string& source, DeckScene& scene);

// The deck's laws for `scene` (the effects that are off become 0 / false), with the origin
// comment lines; `density` per material (type) or one.
bed::DeckLaws deck_laws(const DeckScene& scene, const std::vector<double>& density,
                        const std::string& density_origin, double dt, const std::string& dt_origin);

// deposit --export-deck ENGINE --out DIR/BED.h5: the data file DIR/BED.data and the deck
// DIR/in.BED.<engine> beside it (bed::deck_files), checked before the run as outputs; an
// unknown engine throws InputError naming --export-deck.
std::vector<PathArg> deck_outputs(const std::string& engine, const std::string& bed_path);
// Refuses (InputError) before the run a scene whose laws the engine cannot take (a zeta beyond
// its damping input's range, deck_damping.hpp).
void check_run_deck(const dem::Scene& scene, const std::string& engine);
// The laws of a deposit run (its scene, young-scale and time step), each number's origin
// `made_by`.
bed::DeckLaws run_deck_laws(const dem::Scene& scene, double young_scale, double dt,
                            const std::string& made_by);
// The data file of --export-deck for --out BED_PATH: DIR/BED.data.
std::string deck_data_file(const std::string& bed_path);
// Writes them for the run's bed: the run's scene, young-scale and time step, the scene's one
// density for every material.
void export_run_deck(const bed::Bed& bed, const dem::Scene& scene, double young_scale, double dt,
                     const std::string& engine, const std::string& bed_path);

}  // namespace powderbed::app
