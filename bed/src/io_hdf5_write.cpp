// Writer of the HDF5 bed file, format version 1 (docs/bed-format.md), plus its XDMF sidecar.
#include <array>
#include <utility>
#include <vector>

#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_handle.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/xdmf.hpp"

namespace powderbed::bed {

namespace {

class H5Writer {
 public:
  explicit H5Writer(std::string path) : path_(std::move(path)) {}

  // A failed write (a full disk, EIO): the system's reason, read before any other HDF5 call.
  [[noreturn]] void fail(const std::string& object, const std::string& what) const {
    throw InputError(path_ + ": " + object + ": " + what + ": " + hdf5_failure_reason());
  }

  // Variable-length UTF-8 string attribute (h5py reads it as str, not bytes).
  void string_attr(hid_t loc, const std::string& object, const char* name,
                   const std::string& value) const {
    H5Type type(H5Tcopy(H5T_C_S1));
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    H5Space space(H5Screate(H5S_SCALAR));
    H5Attr attr(H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT));
    const char* text = value.c_str();
    if (!attr.valid() || H5Awrite(attr, type, &text) < 0 || !attr.close())
      fail(object, std::string("cannot write attribute ") + name);
  }

  // Numeric attribute of `count` values (count 1 -> scalar dataspace).
  void numeric_attr(hid_t loc, const std::string& object, const char* name, hid_t file_type,
                    hid_t mem_type, const void* data, hsize_t count) const {
    H5Space space(count == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr));
    H5Attr attr(H5Acreate2(loc, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT));
    if (!attr.valid() || H5Awrite(attr, mem_type, data) < 0 || !attr.close())
      fail(object, std::string("cannot write attribute ") + name);
  }

  // Contiguous dataset of `rows` x `cols` (cols 0 -> one-dimensional), written in one call,
  // with its SI unit as the attribute `units` ("1": a number without unit).
  void dataset(hid_t group, const std::string& object, const char* name, hid_t file_type,
               hid_t mem_type, const void* data, hsize_t rows, hsize_t cols,
               const char* units) const {
    const hsize_t dims[2] = {rows, cols};
    H5Space space(H5Screate_simple(cols == 0 ? 1 : 2, dims, nullptr));
    H5Dataset set(H5Dcreate2(group, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT,
                             H5P_DEFAULT));
    if (!set.valid()) fail(object, "cannot create dataset");
    if (rows > 0 && H5Dwrite(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
      fail(object, "cannot write dataset");
    string_attr(set, object, "units", units);
    // A small dataset waits in HDF5's sieve buffer until closed; a failed flush there loses it
    // and a later file close still succeeds, so the close is checked too.
    if (!set.close()) fail(object, "cannot write dataset");
  }

  void write(const Bed& bed, const std::string& file_name) const {
    H5File file(H5Fcreate(file_name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
    if (!file.valid()) fail("/", "cannot create HDF5 file '" + file_name + "'");
    write_root(file, bed);
    write_domain(file, bed.domain);
    write_particles(file, bed);
    write_polyvertex(file, bed.n());
    write_provenance(file, bed.provenance);
    if (!file.close()) fail("/", "cannot finish HDF5 file '" + file_name + "'");
  }

 private:
  void write_root(hid_t file, const Bed& bed) const {
    const int version = kBedFormatVersion;
    const int dimension = bed.domain.dimension;
    const std::uint64_t seed = bed.provenance.rng_seed;
    string_attr(file, "/", "format", "powderbed.bed");
    numeric_attr(file, "/", "version", H5T_STD_I32LE, H5T_NATIVE_INT, &version, 1);
    numeric_attr(file, "/", "dimension", H5T_STD_I32LE, H5T_NATIVE_INT, &dimension, 1);
    string_attr(file, "/", "length_unit", "m");
    string_attr(file, "/", "created_by", bed.provenance.created_by);
    string_attr(file, "/", "command_line", bed.provenance.command_line);
    numeric_attr(file, "/", "rng_seed", H5T_STD_U64LE, H5T_NATIVE_UINT64, &seed, 1);
  }

  void write_domain(hid_t file, const Domain& d) const {
    H5Group group(H5Gcreate2(file, "domain", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    if (!group.valid()) fail("/domain", "cannot create group");
    const std::array<std::uint8_t, 3> periodic = {d.periodic[0], d.periodic[1], d.periodic[2]};
    numeric_attr(group, "/domain", "lower", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, d.lower.data(), 3);
    numeric_attr(group, "/domain", "upper", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, d.upper.data(), 3);
    numeric_attr(group, "/domain", "periodic", H5T_STD_U8LE, H5T_NATIVE_UINT8, periodic.data(),
                 3);
  }

  void write_particles(hid_t file, const Bed& bed) const {
    H5Group group(H5Gcreate2(file, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    if (!group.valid()) fail("/particles", "cannot create group");
    const hsize_t n = bed.n();
    const auto set = [&](const char* name, hid_t file_type, hid_t mem_type, const void* data,
                         hsize_t cols, const char* units) {
      dataset(group, std::string("/particles/") + name, name, file_type, mem_type, data, n, cols,
              units);
    };
    std::vector<double> rows = interleave(bed.x, bed.y, bed.z);
    set("position", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, rows.data(), 3, "m");
    set("radius", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, bed.radius.data(), 0, "m");
    set("id", H5T_STD_U64LE, H5T_NATIVE_UINT64, bed.id.data(), 0, "1");
    if (!bed.material.empty())
      set("material", H5T_STD_U16LE, H5T_NATIVE_UINT16, bed.material.data(), 0, "1");
    if (bed.has_velocity()) {
      rows = interleave(bed.vx, bed.vy, bed.vz);
      set("velocity", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, rows.data(), 3, "m/s");
    }
    if (!bed.temperature.empty())
      set("temperature", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, bed.temperature.data(), 0, "K");
    if (!bed.phase.empty()) set("phase", H5T_STD_U8LE, H5T_NATIVE_UINT8, bed.phase.data(), 0, "1");
  }

  // The Polyvertex connectivity the XDMF sidecar reads (powderbed/bed/xdmf.hpp).
  void write_polyvertex(hid_t file, std::size_t n) const {
    H5Group group(H5Gcreate2(file, "xdmf", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    if (!group.valid()) fail("/xdmf", "cannot create group");
    const std::vector<std::uint64_t> c = polyvertex_connectivity(n);
    dataset(group, kPolyvertexDataset, "polyvertex", H5T_STD_U64LE, H5T_NATIVE_UINT64, c.data(), n,
            0, "1");
  }

  void write_provenance(hid_t file, const Provenance& p) const {
    H5Group group(H5Gcreate2(file, "provenance", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    if (!group.valid()) fail("/provenance", "cannot create group");
    string_attr(group, "/provenance", "stage", p.stage);
    string_attr(group, "/provenance", "scene", p.scene);
    const ContactProvenance& c = p.contact;
    if (c.law.empty()) return;
    string_attr(group, "/provenance", "contact_law", c.law);
    const std::pair<const char*, double> values[] = {
        {"contact_young", c.young},           {"contact_poisson", c.poisson},
        {"contact_wall_young", c.wall_young}, {"contact_wall_poisson", c.wall_poisson},
        {"contact_young_scale", c.young_scale}, {"contact_stiffness", c.stiffness},
        {"contact_fines_stiffness_radius", c.fines_stiffness_radius}};
    for (const auto& [name, value] : values)
      numeric_attr(group, "/provenance", name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, 1);
  }

  // Structure of arrays -> N x 3 rows.
  static std::vector<double> interleave(const std::vector<double>& a, const std::vector<double>& b,
                                        const std::vector<double>& c) {
    std::vector<double> rows(3 * a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      rows[3 * i] = a[i];
      rows[3 * i + 1] = b[i];
      rows[3 * i + 2] = c[i];
    }
    return rows;
  }

  std::string path_;
};

std::string file_name_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

void write_bed_h5(const Bed& bed, const std::string& path,
                  const std::function<void(const std::string& temp_path)>& extra) {
  bed.validate(path);
  silence_hdf5_errors();
  detail::AtomicFile h5(path);
  detail::AtomicFile xmf(detail::xdmf_path(path));
  H5Writer(path).write(bed, h5.temp_path());
  if (extra) extra(h5.temp_path());
  detail::write_text(xmf.temp_path(), xmf.path(), detail::xdmf_text(bed, file_name_of(path)));
  h5.commit();
  xmf.commit();
}

}  // namespace powderbed::bed
