#pragma once
// sinter's options (the scene, the laser, the scan path, the substrate grid, the effects) and
// the scene they make: one definition for sinter and for build's per-layer scans.
#include <cstddef>
#include <optional>

#include "common/options.hpp"
#include "powderbed/bed/bed.hpp"
#include "powderbed/thermal/scan_path.hpp"
#include "powderbed/thermal/scene.hpp"

namespace powderbed::app {

// Every option of sinter (the common ones, threads, progress, --material among them). The options
// of a plain type are bound to `scene`'s fields (defaults: its values), which parse_options's
// po::notify fills: `scene` outlives the parse.
void add_sinter_options(po::options_description& desc, thermal::SinterScene& scene);

// The scene of the options on `bed` (its x-y extent sizes the substrate) with its scan path:
// `bound` (the scene add_sinter_options bound) with what the options give as words and lists
// (the integrator, the absorption, the grid, the effects); `layer` replaces scan.layer (the
// hatch's rotation step; build: the layer's number). Throws InputError for a bad option, a unit
// slip (unless --trust-units) or a grid beyond memory.
thermal::SinterScene sinter_scene(const po::variables_map& vm, const thermal::SinterScene& bound,
                                  const bed::Bed& bed,
                                  std::optional<std::size_t> layer = std::nullopt);

// The hatch of the options at layer `layer` (none: scan.layer), checked as sinter_scene checks
// it; none when they scan a --scan-path or the single track.
std::optional<thermal::Hatch> scan_hatch(const po::variables_map& vm, const thermal::SinterScene& scene,
                                         const bed::Bed& bed,
                                         std::optional<std::size_t> layer = std::nullopt);

}  // namespace powderbed::app
