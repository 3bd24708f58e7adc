#pragma once
// build's pictures of each layer and of a map (docs/build.md "Pictures", "Process maps"):
// scripts/plot_build_layer.py and plot_build_map.py draw them with matplotlib, run through the wrapper the build system writes beside the programs
// (python/CMakeLists.txt), which pins the interpreter the build found. A picture is never worth
// a failed build: when the plotter is missing or fails, one warning line says why and the build
// goes on without pictures.
#include <cstdint>
#include <string>

#include "powderbed/process/build_report.hpp"

namespace powderbed::app {

// The picture files of a layer as build.json lists them: kind top, fusion, height, section.
using LayerPictureFiles = process::LayerPictureFiles;

class LayerPictures {
 public:
  // `on`: --pictures; the plotter is looked for beside this program (find_plotter).
  explicit LayerPictures(bool on);
  // Draws layer `layer`'s pictures from its scan file into `out` as layer-NNN-KIND.png; returns
  // the files written, none when pictures are off or could not be drawn (then, the first time,
  // one warning line on stderr, and no later layer tries again).
  LayerPictureFiles draw(const std::string& scan_file, const std::string& out, std::uint64_t layer);

 private:
  void give_up(std::uint64_t layer, const std::string& why);
  bool on_;
  std::string plotter_;
  std::string missing_;  // why there is no plotter (empty when there is one)
};

// The plotter `name` beside the running program: ../scripts/NAME in a build tree
// (build/apps/build), ../libexec/powderbed/NAME where cmake --install put it. Empty when neither
// is there; `looked` gets the paths tried.
std::string find_plotter(const char* name, std::string& looked);

// Draws a map's picture `png` from its `json` (build --map); empty when drawn, else why not.
std::string draw_map(const std::string& json, const std::string& png);

}  // namespace powderbed::app
