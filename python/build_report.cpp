#include "build_report.hpp"

#include <pybind11/stl.h>

#include "dem_summaries.hpp"
#include "sinter_summary.hpp"

namespace py = pybind11;

namespace powderbed::python {

py::dict layer_report_dict(const process::LayerReport& l) {
  py::dict d;
  d["layer"] = l.layer;
  d["particles_spread"] = l.scanned_particles;
  d["tool_bottom"] = l.tool_bottom;
  d["recoater_clearance"] = l.clearance;
  d["layer_density"] = l.density;
  d["neighbour_rebuilds"] = l.rebuilds;
  d["ejected"] = l.ejected;
  d["behind_start"] = l.behind;
  d["scan_wall_time"] = l.scan_wall;
  d["fused"] = l.fused;
  d["vaporised"] = l.vaporised;
  d["powder_left"] = l.powder_left;
  d["captured"] = l.captured;
  d["balled"] = l.balled;
  d["fused_fraction"] = l.fused_fraction;
  d["lack_of_fusion"] = l.lack_of_fusion;
  d["remelt_depth_mean"] = l.remelt_mean;
  d["remelt_depth_min"] = l.remelt_min;
  d["scanned_area"] = l.scanned_area;
  d["mass_error"] = l.mass_error;
  d["solid_top_min"] = l.top_min;
  d["solid_top_max"] = l.top_max;
  d["solid_mass"] = l.solid_mass;
  d["part_porosity"] = l.part.fraction();
  d["part_core_area"] = static_cast<double>(l.part.core_columns) * l.part_column_area;
  // The stages' own summaries, as spread and sinter return them.
  d["spread"] = layer_summary_dict(l.spread);
  d["scan"] = sinter_result_dict(l.scan);
  return d;
}

}  // namespace powderbed::python
