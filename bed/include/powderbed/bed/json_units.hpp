#pragma once
// The "units" object of every program's --json summary (README "The programs"): each numeric
// key the summary holds with its SI unit ("m", "K", "W/(m K)", "s", "kg", "J", ...; "1": a count,
// a fraction or a ratio). Keys are named as they appear in the summary, without their parent
// objects: a key has the same unit wherever it appears. Each program has one table of its own
// (UnitEntry rows); tests/apps/test_json_units.cpp checks that every number of each summary
// has its unit.
#include <span>

#include "powderbed/bed/json.hpp"

namespace powderbed::bed {

struct UnitEntry {
  const char* key;
  const char* unit;
};

// Writes "units": {key: unit} for every numeric key `json` has written so far
// (JsonWriter::numeric_keys) that `table` names, in the order they were written; call it last,
// inside the summary's top-level object.
void write_units(bed::JsonWriter& json, std::span<const UnitEntry> table);

}  // namespace powderbed::bed
