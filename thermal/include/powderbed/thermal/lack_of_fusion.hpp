#pragma once
// Lack of fusion after a scan (docs/build.md "Lack of fusion"): where the melt of this layer did
// not reach the solid below it (the plate on the first layer, the fused top of the layers
// before on the next ones), so that powder, or nothing, is left between them. Judged per
// column of the substrate grid, whose top node is the solid's top there (less than one dz thick,
// substrate.hpp): the column is bonded when that node's peak temperature over the scan reached
// the fusion threshold (T_m at the default melt fraction 1/2, the isotherm the melt pool is
// measured on), and it lacks fusion when it did not. How far the melt went into the solid is
// the remelt depth: from the solid's top at the scan's start down to where the column's peak
// crosses the threshold under its molten top (linear between nodes, as the melt pool's depth;
// 0 where the column lacks fusion). Only the scanned area counts:
// the columns within `half_width` of a segment of the path (perpendicular to it, between its
// ends): half the hatch spacing for a hatch, each track answering for its own strip of the
// layer; the beam radius for a path without a spacing (a CSV path, one track).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "powderbed/thermal/scan_path.hpp"
#include "powderbed/thermal/solver.hpp"

namespace powderbed::thermal {

enum LackOfFusionCell : std::uint8_t { kNotScanned = 0, kBonded = 1, kUnbonded = 2 };

struct LackOfFusion {
  std::vector<std::uint8_t> map;  // per column i + nx j: a LackOfFusionCell
  std::vector<double> remelt;     // per scanned column, in map order: remelt depth, m
  std::size_t scanned = 0, unbonded = 0;
  double threshold = 0;           // K
  double half_width = 0;          // m
  // Area fraction of the scanned columns that lack fusion (0 when nothing was scanned).
  double fraction() const {
    return scanned > 0 ? static_cast<double>(unbonded) / static_cast<double>(scanned) : 0.0;
  }
  // Mean and smallest remelt depth over the scanned columns, m (0 when nothing was scanned).
  double mean_remelt() const;
  double min_remelt() const;
};

// From the peak temperatures of the run `sinter` has made along its path (Sinter::scan_path: a
// single track too, resolved as the run ran it); `start`: the solid's top the run started from
// (the top it was given; empty: the flat plate).
LackOfFusion lack_of_fusion(const Sinter& sinter, double half_width, double threshold,
                            const TopHeight& start = {});

// The bottom of the melt under column `column`'s top node (plane `top_plane`), from the peak
// temperatures of the substrate's nodes: down from the top node while the peak stays at or above
// the threshold, the last step interpolated to the crossing (linear between nodes, as the melt
// pool's depth); +infinity when the top node's peak stayed below it (nothing melted there).
double molten_bottom(const SubstrateGeometry& g, const std::vector<double>& peak,
                     std::size_t column, std::size_t top_plane, double threshold);

// The width of the bonded stripe across x = x_plane (the top-face column row nearest to it): the
// bonded columns' count times dy: what a single track fuses of the solid under it.
double bonded_width(const LackOfFusion& lof, const SubstrateGeometry& g, double x_plane);

}  // namespace powderbed::thermal
