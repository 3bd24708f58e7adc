#pragma once
// What a drop's or a spread's summary says, as JSON fields of the object the writer is in (SI
// units): one writer for deposit's --json and the Python module's dicts (json.loads of the
// same text), so the two cannot drift apart. The bed's own count and what the caller removed
// after the run ("n", "lost") are the caller's, as are its settings and statistics.
#include "powderbed/bed/json.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"

namespace powderbed::dem {

// A drop: its steps and times, the step's choice and what limited it, the energies and
// overlaps at the end, the list's rebuilds, and the "insertion" and "lid" objects when it had
// them.
void write_run_json(bed::JsonWriter& j, const RunSummary& r);
// A spread: its steps and times as write_run_json's, the overlap and rebuilds, the layers done
// and the "layers" array (write_layer_json each).
void write_spread_json(bed::JsonWriter& j, const SpreadSummary& s);
// One layer of a spread (a spread's and a build layer's).
void write_layer_json(bed::JsonWriter& j, const LayerSummary& l);

}  // namespace powderbed::dem
