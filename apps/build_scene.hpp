#pragma once
// build's scene (docs/build.md): the program's option table and what its options make, the
// plan of process::build_layer, the powder to start from and the part's record, checked before
// anything is written. One reading for the program build and the Python module's build_scene,
// so that a scene file means the same in both.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "common/options.hpp"
#include "deposit_options.hpp"
#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/process/build_plan.hpp"
#include "powderbed/thermal/part_porosity.hpp"
#include "powderbed/thermal/scene.hpp"

namespace powderbed::app {

// build's usage line and its options (the common ones, threads, progress, the spread engine's).
extern const char* const kBuildUsage;
void add_build_options(po::options_description& desc);

// The build's plan and the stage options it was made from: the map's points parse the scan
// stage again with their power, speed and hatch.
struct Build {
  process::BuildPlan plan;
  po::variables_map dvm, svm;
  DepositOptions spread_options;          // what the spread stage's options of a plain type filled
  thermal::SinterScene scan_options;      // ... and the scan stage's (sinter_scene starts there)
  std::string sinter_scene, sinter_args;  // the scan stage's scene and --sinter-args
};

// The build's own options, the stage scenes parsed by their programs' options into the plan, the
// checks made before anything is written; `argc`, `argv`: the command line the spread beds
// record. Makes the thread team of --threads OpenMP's default.
Build read_build(const po::variables_map& vm, int argc, char** argv);

// The powder and the spread's state to continue from (--in), or an empty box.
bed::Bed build_input(const po::variables_map& vm, const Build& b,
                     std::optional<dem::SpreadState>& state);

// The scan stage parsed and checked on the bed's plate before any layer is spread: its options,
// its path on the plate and its grid under the solid (a bed without particles: the scene and the
// grid alone); `more`: a map point's power, speed and hatch. Returns the part's record to go on
// from: `record` (from --in) checked against that grid, or a new one on it when `record` is
// empty.
thermal::PartRecord check_scan(Build& b, const bed::Bed& bed,
                               const std::optional<dem::SpreadState>& state,
                               thermal::PartRecord record, const std::string& more = "");

// A build of layers ready to run: the plan, the powder, the spread's state and the part's record
// to start from (--in's, or an empty box), and the layers to build, all checked.
struct BuildStart {
  Build b;
  bed::Bed bed;
  std::optional<dem::SpreadState> state;
  thermal::PartRecord part;
  std::uint64_t first = 1, layers = 1;  // the first layer's number and how many
};
BuildStart start_build(const po::variables_map& vm, Build b);

// Makes the --out folder (false: it was there); one line naming it when the file system refuses.
bool make_out(const std::string& out);

// Removes --out again when the build fails before it wrote anything there (it made the folder).
struct OutFolderGuard {
  std::string path;
  bool made = false;
  OutFolderGuard(std::string folder, bool made_it) : path(std::move(folder)), made(made_it) {}
  OutFolderGuard(const OutFolderGuard&) = delete;
  OutFolderGuard& operator=(const OutFolderGuard&) = delete;
  ~OutFolderGuard();
};

}  // namespace powderbed::app
