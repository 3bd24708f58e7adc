#pragma once
// Bed files: the HDF5 format of docs/bed-format.md (with an XDMF sidecar), CSV x,y,z,r, LAMMPS data
// export and LAMMPS/LIGGGHTS dump import. Every writer is atomic (temporary file + rename);
// every reader validates and throws InputError naming the file, dataset/line and what is wrong.
#include <string>

#include "powderbed/bed/bed.hpp"

namespace powderbed::bed {

constexpr int kBedFormatVersion = 1;
// Default particle density of LAMMPS exports, kg/m^3 (316L stainless steel).
constexpr double kDefaultLammpsDensity = 7952.0;

// HDF5 bed (format version 1) plus `<path without .h5>.xmf` for ParaView.
void write_bed_h5(const Bed& bed, const std::string& path);
Bed read_bed_h5(const std::string& path);

// CSV with header "x,y,z,r" (SI units). The file carries no domain, so the reader needs one.
void write_bed_csv(const Bed& bed, const std::string& path);
Bed read_bed_csv(const std::string& path, const Domain& domain);

// LAMMPS data file, atom_style sphere (id type diameter density x y z), one atom type.
// `density` (kg/m^3) is written per atom since atom_style sphere needs it.
void write_lammps_data(const Bed& bed, const std::string& path,
                       double density = kDefaultLammpsDensity);
// LAMMPS/LIGGGHTS text dump (ITEM: ATOMS with id, x y z and radius or diameter columns); the
// last snapshot is read, the box bounds become the domain.
Bed read_lammps_dump(const std::string& path);

// By extension: .h5 (HDF5), .csv (needs domain), .dump (read), .data (write).
Bed read_bed_any(const std::string& path, const Domain* csv_domain = nullptr);
void write_bed_any(const Bed& bed, const std::string& path);
// Lower-case extension with the dot (".h5"), or "" when there is none: what read_bed_any and
// write_bed_any dispatch on.
std::string extension_of(const std::string& path);

}  // namespace powderbed::bed
