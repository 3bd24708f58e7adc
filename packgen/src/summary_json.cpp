// summary_json.hpp: packgen's --json fields and its warning, and the Python module's.
#include "powderbed/packgen/summary_json.hpp"

#include <fmt/format.h>

#include <iterator>
#include <vector>

#include "powderbed/bed/contact_report.hpp"
#include "powderbed/bed/stats.hpp"

namespace powderbed::packgen {

void write_pack_json(bed::JsonWriter& j, const PackResult& r, const PackOptions& o, std::uint64_t seed) {
  const bed::Bed& b = r.bed;
  const std::vector<bed::ContactStats> by_tol = bed::contact_stats(
      b, std::vector<double>(std::begin(bed::kReportedTolerances), std::end(bed::kReportedTolerances)));
  j.value("n", std::uint64_t{b.n()});
  j.value("density", bed::packing_density(b));
  j.value("coordination", by_tol[0].coordination);
  j.begin_object("coordination_by_tol");
  for (std::size_t t = 0; t < by_tol.size(); ++t)
    j.value(bed::tolerance_key(bed::kReportedTolerances[t]), by_tol[t].coordination);
  j.end_object();
  j.value("rattlers", std::uint64_t{by_tol[0].rattlers});
  j.value("wall_contacts", std::uint64_t{by_tol[0].wall_contacts});
  j.value("max_relative_overlap", bed::max_relative_overlap(b));
  j.value("wall_time", r.wall_time);
  j.value("attempts", std::uint64_t{r.attempts});
  j.value("tries", std::uint64_t{r.tries});
  j.value("failed_placements", std::uint64_t{r.failed_placements});
  j.value("retired", std::uint64_t{r.retired});
  j.value("refused_valid", std::uint64_t{r.refused_valid});
  j.value("accepted_overlapping", std::uint64_t{r.accepted_overlapping});
  j.value("target_reached", r.target_reached);
  j.value("stop_reason", r.stop_reason);
  j.value("collision", collision_name(o.collision));
  j.value("approach", o.phases.back().approach);
  j.value("site_order", site_order_name(o.site_order));
  j.value("size_sampling", size_sampling_name(o.size_sampling));
  j.value("sites", std::uint64_t{r.sites});
  j.value("seed", seed);
}

std::string unreached_warning(const PackResult& r, const PackOptions& o) {
  const std::string target =
      o.count > 0 ? fmt::format("--count {}", o.count)
                  : fmt::format("--target-density {}", bed::tolerance_key(o.target_density));
  return fmt::format("{} not reached: stopped by the {} rule after {} failed placements, {} in a "
                     "row, with {} particles at density {:g}; the bed was written",
                     target, r.stop_reason, r.failed_placements, r.failures_in_a_row, r.bed.n(),
                     bed::packing_density(r.bed));
}

}  // namespace powderbed::packgen
