#pragma once
// What a laser run's result says, as JSON fields of the object the writer is in (SI units), in
// two blocks: the melt pool (its size and sections, the peak temperatures, evaporation, the
// depression), then the run (particles molten, the energy balance, absorptance, the tracks, the
// ray trace's split of the beam, wetting, the energy ledger, the steps). One writer for every
// summary of a run: sinter's --json (which puts the bed's and the program's fields between and
// after them) and the Python module's dict (json.loads of both).
#include "powderbed/bed/json.hpp"
#include "powderbed/thermal/solver.hpp"

namespace powderbed::thermal {

void write_melt_pool_json(bed::JsonWriter& j, const SinterResult& r);
void write_run_json(bed::JsonWriter& j, const SinterResult& r);

}  // namespace powderbed::thermal
