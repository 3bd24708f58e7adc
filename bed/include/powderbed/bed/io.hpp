#pragma once
// Bed files: the HDF5 format of docs/bed-format.md (with an XDMF sidecar), CSV x,y,z,r, LAMMPS
// data files, LAMMPS/LIGGGHTS dumps, YADE text and GenGeo .geo (docs/decks.md). Every writer is atomic (temporary file + rename);
// every reader validates and throws InputError naming the file, dataset/line and what is wrong.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "powderbed/bed/bed.hpp"

namespace powderbed::bed {

constexpr int kBedFormatVersion = 1;
// Default particle density of LAMMPS exports, kg/m^3 (316L stainless steel), used when neither
// the bed's scene nor the command line gives one.
constexpr double kDefaultLammpsDensity = 7952.0;

// HDF5 bed (format version 1) plus `<path without .h5>.xmf` for ParaView. `extra`, when given,
// adds to the bed's HDF5 file before it is renamed into place (it gets the temporary's path), so
// that what it adds (a spread's /restart) appears together with the bed or not at all.
void write_bed_h5(const Bed& bed, const std::string& path,
                  const std::function<void(const std::string& temp_path)>& extra = {});
Bed read_bed_h5(const std::string& path);

// CSV with header "x,y,z,r" (SI units). The file carries no domain, so the reader needs one.
void write_bed_csv(const Bed& bed, const std::string& path);
Bed read_bed_csv(const std::string& path, const Domain& domain);

// What a LAMMPS data file holds beyond the bed (docs/decks.md).
struct LammpsDataOptions {
  // Density of each atom type (type = material index + 1), kg/m^3: one value for every type,
  // or one per type. atom_style sphere needs a density per atom.
  std::vector<double> type_density{kDefaultLammpsDensity};
  // Atom types after the materials' that hold no atoms (a deck's wall material: LIGGGHTS's
  // wall/gran takes the wall's properties from an atom type).
  int extra_types = 0;
  // Comment lines (without '#') written under the title: where the numbers come from.
  std::vector<std::string> comments;
};

// LAMMPS data file, atom_style sphere (id type diameter density x y z), atom id = bed id + 1,
// one atom type per material (type = material index + 1), a Velocities section when the bed
// has velocities, and a "# boundary p p f" comment that read_lammps_data takes the periodic
// axes from (a data file has no other place for them). Also LIGGGHTS's atom_style granular.
void write_lammps_data(const Bed& bed, const std::string& path,
                       const LammpsDataOptions& options = {});
// The same with one density for every atom type, kg/m^3.
void write_lammps_data(const Bed& bed, const std::string& path, double density);
// A LAMMPS data file with an "Atoms # sphere" section (ours, and what LAMMPS's write_data
// writes for atom_style sphere; image flags are ignored: write_data's positions are wrapped):
// ids - 1 become the bed's ids, types - 1 its material indices (kept when there is more than
// one type), the Velocities section its velocities. The box is the domain; the axes named p in
// a "# boundary" comment are periodic, the others not.
Bed read_lammps_data(const std::string& path);

// One snapshot of a LAMMPS/LIGGGHTS text dump.
struct DumpSnapshot {
  std::uint64_t step = 0;
  double time = -1;  // s, from an ITEM: TIME section; -1 when the dump has none
  Bed bed;
};
// LAMMPS/LIGGGHTS text dump (`.dump`, `.lammpstrj`, either gzipped): ITEM: ATOMS with id, x y z
// (or xs/xu) and radius or diameter columns; vx vy vz become velocities and a type column the
// material index (type - 1) when there is more than one type. read_lammps_dump reads the last
// snapshot; read_lammps_dump_all every snapshot, each validated, in file order. The box bounds
// become the domain (pp -> periodic).
Bed read_lammps_dump(const std::string& path);
std::vector<DumpSnapshot> read_lammps_dump_all(const std::string& path);

// YADE's text export (yade.export.text: a "#format x_y_z_r" header, then "x y z r" per sphere;
// lines starting with '#' are comments; also ymport.text's input). Ids are the line order from
// 0. The file carries no domain: `domain` when given, else the spheres' bounding box (centre
// +- radius), not periodic.
Bed read_yade_text(const std::string& path, const Domain* domain = nullptr);
// GenGeo's LSMGeometry file (.geo, version 1.2: BoundingBox, PeriodicBoundaries, Dimension,
// BeginParticles Simple with "x y z r id tag" lines; bonds after EndParticles are ignored), in
// the file's length unit read as metres. The bounding box is the domain; ids are GenGeo's.
Bed read_gengeo(const std::string& path);

// A warning (one line) when rounding to that many digits may move a gap across the contact
// criterion d <= (r_i + r_j)(1 + tolerance) of contact_stats, else "": the printed centres and
// radii are off by up to half a unit in their last digit, the gap by up to 2 sqrt(3) times
// that of the centres plus twice that of the radii, against tolerance (r_i + r_j) for the
// smallest pair.
std::string printed_precision_warning(const Bed& bed, double tolerance);

// By extension: .h5 (HDF5), .csv (needs domain), .dump and .lammpstrj (the last snapshot),
// .data (LAMMPS data), .txt (YADE text; `csv_domain` when given), .geo (GenGeo); a .gz after
// .dump, .lammpstrj, .data, .txt or .csv is read through gunzip. Writable: .h5, .csv, .data.
Bed read_bed_any(const std::string& path, const Domain* csv_domain = nullptr);
void write_bed_any(const Bed& bed, const std::string& path);
// Lower-case extension with the dot (".h5"), or "" when there is none: what read_bed_any and
// write_bed_any dispatch on. For "x.dump.gz" it is ".gz"; readable_extension_of gives ".dump".
std::string extension_of(const std::string& path);
std::string readable_extension_of(const std::string& path);

}  // namespace powderbed::bed
