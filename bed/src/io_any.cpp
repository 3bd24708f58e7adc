// Bed I/O chosen by file extension (docs/bed-format.md: any bed feeds any stage).
#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"

namespace powderbed::bed {

namespace {
constexpr const char* kReadable =
    ".h5, .csv with a domain, .dump, .lammpstrj, .data, .txt (YADE), .geo (GenGeo); "
    ".gz of the text ones";
}  // namespace

Bed read_bed_any(const std::string& path, const Domain* csv_domain) {
  const std::string ext = readable_extension_of(path);
  const bool gz = extension_of(path) == ".gz";
  if (ext == ".h5" && !gz) return read_bed_h5(path);
  if (ext == ".dump" || ext == ".lammpstrj") return read_lammps_dump(path);
  if (ext == ".data") return read_lammps_data(path);
  if (ext == ".txt") return read_yade_text(path, csv_domain);
  if (ext == ".geo") return read_gengeo(path);
  if (ext == ".csv") {
    if (!csv_domain) throw InputError(path + ": CSV carries no domain; one must be given");
    return read_bed_csv(path, *csv_domain);
  }
  throw InputError(path + ": unknown extension '" + extension_of(path) + "' (readable: " +
                   kReadable + ")");
}

void write_bed_any(const Bed& bed, const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext == ".h5") return write_bed_h5(bed, path);
  if (ext == ".csv") return write_bed_csv(bed, path);
  if (ext == ".data") return write_lammps_data(bed, path);
  throw InputError(path + ": '" + ext + "' is not writable (writable: .h5, .csv, .data)");
}

}  // namespace powderbed::bed
