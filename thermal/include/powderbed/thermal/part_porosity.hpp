#pragma once
// The porosity of a part built layer by layer (docs/build.md "Porosity of the part"): which of
// the solid above the plate never melted. The solid is a height field per column of the
// substrate grid (its top: fusion.hpp), so a pore is not a void in it but solid that never was
// molten: the powder the grown solid captured (fuse's capture) and no later scan remelted. Each
// column keeps the height intervals of such solid; a layer's scan removes what its melt reached
// (from the column's molten top down to where the peak temperature crosses the threshold, as the
// remelt depth of lack_of_fusion.hpp), and its fusion adds the powder it captured.
//
// What it stands for: a lack-of-fusion pore is a region of unmelted powder between tracks or
// layers. The height field keeps that powder's solid volume, packed, so the never-molten volume
// here is the pore's powder; the pore itself is larger by 1 / φ of the powder it holds (about
// 2 for spread powder). A column that lacks fusion under a deposit its molten neighbours bonded
// holds an unbonded interface of no volume: the layer's lack_of_fusion counts it, this does not.
// Keyhole pores (the depression collapsing) are not modelled.
//
// The part's porosity is taken over its core: the columns every layer's scan covered, to the
// part's final top and over its interior (below the top the layer before the last left). The
// interior is what a later layer's scan has been over, as all but the top of a built part is: a
// measured density (Archimedes, or a polished section away from the top) is the interior's,
// while the final top carries the powder the last scan captured, a film no later scan remelts.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "powderbed/thermal/fusion.hpp"
#include "powderbed/thermal/lack_of_fusion.hpp"
#include "powderbed/thermal/substrate.hpp"

namespace powderbed::bed {
class H5Output;
}

namespace powderbed::thermal {

struct HeightInterval {
  double lo = 0, hi = 0;  // m, absolute z
};

struct PartRecord {
  // The columns' grid: the substrate grid's nx × ny nodes (x fastest), its plane spacing and
  // the plate's top face.
  std::size_t nx = 0, ny = 0;
  double x0 = 0, y0 = 0, dx = 0, dy = 0, dz = 0, z_top = 0;
  std::uint64_t layers = 0;                            // layers recorded
  TopHeight top;                                       // per column: the part's top, m
  TopHeight below_last;                                // per column: its top before the last layer, m
  std::vector<std::uint64_t> scanned;                  // per column: layers whose scan covered it
  std::vector<std::vector<HeightInterval>> never_molten;  // per column, in order of height

  bool empty() const { return top.empty(); }
  std::size_t columns() const { return nx * ny; }
};

// An empty record on the grid `g` (a flat plate, no layer yet).
PartRecord part_record(const SubstrateGeometry& g);

// InputError when the record's columns are not those of the grid `g` (a continued build whose
// scan grid changed).
void check_part_grid(const PartRecord& r, const SubstrateGeometry& g);

// Records a layer: what its scan (`sinter`, on the part the record holds) melted, the powder its
// fusion `f` captured, its scanned columns (`lof`'s map) and the part's new top (check_part_grid
// first).
void record_layer(PartRecord& r, const Sinter& sinter, const Fusion& f, const LackOfFusion& lof);

struct PartPorosity {
  std::size_t core_columns = 0;   // scanned by every layer
  double volume = 0;              // m^3: the solid above the plate over the core
  double never_molten = 0;        // m^3: of it, never molten
  // never_molten / volume (0 when the core holds no solid).
  double fraction() const { return volume > 0 ? never_molten / volume : 0.0; }
};
// To the part's final top.
PartPorosity part_porosity(const PartRecord& r);
// Of its interior: below the top the layer before the last left (no volume after one layer).
PartPorosity interior_porosity(const PartRecord& r);

// The record as cells for pictures and ParaView: nk planes of dz from the plate's top up to the
// highest column's top, nk × ny × nx (x fastest), each cell the fraction of its volume that is
// solid, and that is never-molten solid.
struct PartField {
  std::size_t nk = 0;
  std::vector<double> solid, never_molten;
};
PartField part_field(const PartRecord& r);

// The record as the group /part of an HDF5 file (attributes for the grid, datasets top,
// scanned and never_molten rows of (column, lo, hi)), so a continued build reads back every bit;
// and the cells of part_field as /part/solid_fraction and /part/never_molten_fraction.
void write_part_record(bed::H5Output& out, const PartRecord& r);
// Reads /part of `path`; an empty record when the file has none (a spread's layer, no build's).
PartRecord read_part_record(const std::string& path);

}  // namespace powderbed::thermal
