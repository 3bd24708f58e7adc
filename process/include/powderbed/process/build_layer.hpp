#pragma once
// One layer of a build (docs/build.md): the recoater spreads powder on the solid of the layers
// before, the laser scans it, what melted fuses into the solid's top, and the layer's files are
// written in the plan's folder (layer-NNN-spread.h5, layer-NNN-scan.h5, layer-NNN.h5).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/process/build_plan.hpp"
#include "powderbed/thermal/part_porosity.hpp"
#include "powderbed/thermal/solver.hpp"

namespace powderbed::process {

// What a layer did, for the report (build.json's layer objects).
struct LayerReport {
  std::uint64_t layer = 0;
  dem::LayerSummary spread;
  std::uint64_t rebuilds = 0;              // the spread's neighbour-list builds
  std::size_t ejected = 0;                 // in flight above the tool's bottom at the end, removed
  std::size_t behind = 0;                  // behind the tool's start at the end, removed
  double tool_bottom = 0, clearance = 0;  // m: the tool's bottom above the plate, and above the solid
  double density = 0;                      // scanned_layer_density
  thermal::SinterResult scan;
  double scan_wall = 0;
  std::size_t scanned_particles = 0, fused = 0, vaporised = 0, powder_left = 0;
  double fused_fraction = 0;               // of the powder's mass the scan met
  double mass_error = 0, lack_of_fusion = 0, top_min = 0, top_max = 0;  // top: above the plate
  double scanned_area = 0;                 // m^2: the columns the lack-of-fusion map judged
  double remelt_mean = 0, remelt_min = 0;  // m: remelt depth into the solid below (lack_of_fusion.hpp)
  double solid_mass = 0;                   // kg above the plate after the layer
  thermal::PartPorosity part;              // the part so far (part_porosity.hpp)
  thermal::PartPorosity interior;          // of it, below the top the layer before left
  double part_column_area = 0;             // m^2: dx dy of the part's columns
  std::size_t captured = 0;                // of the fused: powder the grown solid swallowed
  std::size_t balled = 0;                  // melted on solid that did not melt: balls left in the bed
};

// Progress through one stage of a layer (its spread or its scan): the fraction done, 0 to 1, and
// what is running ("layer 3 spread"). May be empty (no progress).
using Progress = std::function<void(double fraction, const std::string& what)>;

// A layer's file in `out`: layer-NNN<suffix>.h5.
std::string layer_file(const std::string& out, std::uint64_t layer, const char* suffix);

// A layer spread on the solid (the state's floor): the bed the scan meets (with the spread's
// provenance; written as layer-NNN-spread.h5), the spread's state after it and the report's
// spread part. `bed` becomes that bed.
struct SpreadLayer {
  bed::Bed spread;
  dem::SpreadState next;
  LayerReport rep;
};
SpreadLayer spread_layer(const BuildPlan& plan, bed::Bed& bed,
                         const std::optional<dem::SpreadState>& state, std::uint64_t layer,
                         const Progress& progress);

// The scan of a spread layer, its fusion and what stays: the fused solid becomes the floor of
// the next layer's spread, the rest stays powder (`bed`, the spread bed); writes the layer's scan
// file and its layer file (with the part's record); the state becomes the next layer's.
LayerReport scan_layer(const BuildPlan& plan, bed::Bed& bed, SpreadLayer spread,
                       std::optional<dem::SpreadState>& state, thermal::PartRecord& part,
                       std::uint64_t layer, const Progress& progress);

// One layer: spread, then scan and fuse.
LayerReport build_layer(const BuildPlan& plan, bed::Bed& bed, std::optional<dem::SpreadState>& state,
                        thermal::PartRecord& part, std::uint64_t layer,
                        const Progress& spread_progress, const Progress& scan_progress);

}  // namespace powderbed::process
