#pragma once
// What a packing's summary says, as JSON fields of the object the writer is in, and the warning
// for a stop rule it did not reach: one writer for packgen's --json and the Python module's
// pack() (json.loads of the same text), so the two cannot drift apart.
#include <cstdint>
#include <string>

#include "powderbed/bed/json.hpp"
#include "powderbed/packgen/pack.hpp"

namespace powderbed::packgen {

// The bed's count, density and contacts (coordination at bed::kReportedTolerances), the run's
// counters, its stop reason, the options that shaped it and the seed.
void write_pack_json(bed::JsonWriter& j, const PackResult& r, const PackOptions& o, std::uint64_t seed);

// Why a count or a target density was not reached (result.target_reached false): the rule that
// stopped the run, its failures and the bed it left ("packgen: warning: " is the caller's).
std::string unreached_warning(const PackResult& r, const PackOptions& o);

}  // namespace powderbed::packgen
