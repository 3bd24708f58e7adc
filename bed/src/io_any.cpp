// Bed I/O chosen by file extension (docs/bed-format.md: any bed feeds any stage).
#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"

namespace powderbed::bed {

Bed read_bed_any(const std::string& path, const Domain* csv_domain) {
  const std::string ext = extension_of(path);
  if (ext == ".h5") return read_bed_h5(path);
  if (ext == ".dump") return read_lammps_dump(path);
  if (ext == ".csv") {
    if (!csv_domain) throw InputError(path + ": CSV carries no domain; one must be given");
    return read_bed_csv(path, *csv_domain);
  }
  if (ext == ".data")
    throw InputError(path + ": LAMMPS .data files are written only (readable: .h5, .csv, .dump)");
  throw InputError(path + ": unknown extension '" + ext +
                   "' (readable: .h5, .csv with a domain, .dump)");
}

void write_bed_any(const Bed& bed, const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext == ".h5") return write_bed_h5(bed, path);
  if (ext == ".csv") return write_bed_csv(bed, path);
  if (ext == ".data") return write_lammps_data(bed, path);
  if (ext == ".dump")
    throw InputError(path + ": LAMMPS .dump files are read only (writable: .h5, .csv, .data)");
  throw InputError(path + ": unknown extension '" + ext + "' (writable: .h5, .csv, .data)");
}

}  // namespace powderbed::bed
