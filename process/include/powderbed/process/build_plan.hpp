#pragma once
// A build's plan (docs/build.md): everything a layer needs that stays from one layer to the
// next, as plain values. The build program fills it from its scene files; nothing here parses.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/thermal/material.hpp"
#include "powderbed/thermal/scan_path.hpp"
#include "powderbed/thermal/scene.hpp"

namespace powderbed::process {

// How a scanned layer joins the solid (thermal::fuse's arguments). A build's policy differs from
// fuse's defaults (those of sinter --fuse, one layer on a bare plate) in two places, both because
// the next layer is spread on what stays: powder the grown solid overlaps is captured, and the
// deposit is levelled as the melt levels before it freezes (docs/build.md).
struct FusionPolicy {
  double melt_fraction = 0.5;  // of a particle's enthalpy of melting: 0.5 fuses what reached T_m
  // Capture: powder overlapped by more than this share of its radius joins the solid. 0.05: the
  // Hertz overlap of a resting particle under the scenes' softening is ~2 % of r.
  double capture = 0.05;
  double level = -1;  // the levelling length L, m (< 0: half the beam radius: a pool spans ~2 w)
};

// A spread of one layer by some engine (deposit's DEM or LIGGGHTS): dem::run_spread's contract,
// with the layer's number and the build's folder (where an engine may keep its own files).
using SpreadEngine = std::function<dem::SpreadSummary(
    bed::Bed& bed, const dem::Scene& scene, const dem::SpreadSettings& settings,
    const std::optional<dem::SpreadState>& state, std::uint64_t layer, const std::string& out)>;

struct BuildPlan {
  dem::Scene scene;             // the powder (deposit's scene)
  dem::SpreadSettings spread;   // the recoater and supply; one layer a call (layers = 1)
  double finest_diameter = 0;   // of the supply's size distribution, m (no layer thinner)
  thermal::SinterScene scan;    // the scan of the build's first layer
  // The hatch, turned by its rotation each layer; none: every layer scans scan.scan_path.
  std::optional<thermal::Hatch> hatch;
  thermal::MaterialTable table;  // scan.material_table, read once
  FusionPolicy fusion;
  std::string out;               // the folder the layers' files go to
  std::size_t snapshots = 10;    // scan snapshots a layer (0: none)
  SpreadEngine engine;           // empty: dem::run_spread
  // The provenance of the spread beds (deposit's labels) and the scan's resolved scene (INI
  // text), for the files.
  bed::Provenance spread_provenance;
  std::string scan_scene_text;
  // Where a layer's warnings go (one line each, without the "build: warning: " the program
  // prints before them): empty, to stderr as the program prints them; the Python module turns
  // them into Python warnings.
  std::function<void(const std::string&)> warning;
};

// The scan scene of layer k: the plan's, with the hatch turned by (k - 1) rotation steps
// past the first layer's.
thermal::SinterScene scan_for_layer(const BuildPlan& plan, std::uint64_t layer);

// The tool's lowest point at layer k (the plate has gone down k - 1 layers), on `bed`'s box.
double tool_bottom(const BuildPlan& plan, const bed::Domain& box, std::uint64_t layer);

// Every layer from `first` on for `layers` layers checked before layer `first` is spread (the
// spread checks each layer's tool only when it gets there): the last layer's tool under the
// box's top, and no layer thinner than the finest particle. Throws InputError naming --layers
// or recoater.layer-thickness.
void check_layers(const BuildPlan& plan, const bed::Domain& box, std::uint64_t first,
                  std::uint64_t layers);

// The half width of the strip a scan melts around each track: half the hatch, or the beam radius
// of a single track (lack_of_fusion.hpp).
double scanned_half_width(const BuildPlan& plan);

}  // namespace powderbed::process
