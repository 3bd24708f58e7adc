#pragma once
// A build's report as JSON (build.json, `build --json`), written once here so that the program's
// file and the Python module's dicts (json.loads of this text) cannot drift apart.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "powderbed/bed/json.hpp"
#include "powderbed/process/build_layer.hpp"

namespace powderbed::process {

// The picture files drawn from a layer's files: (kind, file name in the build's folder); none
// when no pictures were drawn (the program's --pictures false, the Python module).
using LayerPictureFiles = std::vector<std::pair<std::string, std::string>>;

// A layer's report and the pictures drawn from its files.
struct ReportedLayer {
  LayerReport report;
  LayerPictureFiles pictures;
};

// A layer's object in build.json's "layers" (one object, written into `j`).
void write_layer_json(bed::JsonWriter& j, const LayerReport& l, const LayerPictureFiles& pictures);

// What build.json says of the whole run besides its layers.
struct BuildTotals {
  std::uint64_t layers_done = 0;  // the spread's state after the last layer (--in's included)
  std::uint64_t first_layer = 1;
  std::size_t particles = 0;      // the powder left after the last layer
  double wall_time = 0;           // s
  std::string out;                // the build's folder
};

// build.json's text (one line, no newline): the totals, the layers and the units of its numbers.
std::string build_report_json(const std::vector<ReportedLayer>& layers, const BuildTotals& totals);

// build.json in totals.out, written through a temporary file and a rename; returns its text.
std::string write_build_report(const std::vector<ReportedLayer>& layers, const BuildTotals& totals);

}  // namespace powderbed::process
