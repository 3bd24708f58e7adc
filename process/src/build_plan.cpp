#include "powderbed/process/build_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "powderbed/bed/errors.hpp"

namespace powderbed::process {

thermal::SinterScene scan_for_layer(const BuildPlan& plan, std::uint64_t layer) {
  thermal::SinterScene scene = plan.scan;
  if (plan.hatch) {
    thermal::Hatch h = *plan.hatch;
    h.layer += static_cast<std::size_t>(layer - 1);
    scene.scan_path = thermal::hatch_segments(h);
  }
  return scene;
}

double tool_bottom(const BuildPlan& plan, const bed::Domain& box, std::uint64_t layer) {
  return box.lower[2] + plan.spread.tool.gap +
         static_cast<double>(layer - 1) * plan.spread.layer_thickness;
}

void check_layers(const BuildPlan& plan, const bed::Domain& box, std::uint64_t first,
                  std::uint64_t layers) {
  const double top = box.upper[2];
  const std::uint64_t last = first + layers - 1;
  // A layer (past the first, whose gap is the tool's) thinner than the finest particle the
  // supply holds: the plate would go down by less than any particle it is to take.
  if (last > 1 && plan.spread.layer_thickness < plan.finest_diameter) {
    throw InputError(fmt::format(
        "recoater.layer-thickness: {:g} m, thinner than the finest particle of the spread scene's "
        "psd ({:g} m across) (accepted: a layer at least as thick as the finest particle)",
        plan.spread.layer_thickness, plan.finest_diameter));
  }
  if (last >= first && tool_bottom(plan, box, last) < top) return;
  // The last layer that fits (0: not even the first), by the spread's own test; the estimate
  // from the box's height may be one off in floating point. Layers that do not raise the tool
  // all fit or none does.
  const double t = plan.spread.layer_thickness;
  const double room = t > 0 ? (top - box.lower[2] - plan.spread.tool.gap) / t : 0.0;
  auto fit = static_cast<std::uint64_t>(std::clamp(std::ceil(room), 0.0, 1e15));
  if (fit > 0 && !(tool_bottom(plan, box, fit) < top)) --fit;
  if (t > 0 && tool_bottom(plan, box, fit + 1) < top) ++fit;
  throw InputError(fmt::format("--layers: {} from layer {}: the tool rises above the box's top "
                               "after layer {} (accepted: a taller box or at most {} layers)",
                               layers, first, fit, fit >= first ? fit - first + 1 : 0));
}

double scanned_half_width(const BuildPlan& plan) {
  return plan.hatch ? 0.5 * plan.hatch->spacing : plan.scan.spot_radius;
}

}  // namespace powderbed::process
