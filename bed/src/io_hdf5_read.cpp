// Reader of the HDF5 bed file, format version 1 (docs/bed-format.md): checks everything and
// refuses a bad file with one line "<file>: <dataset>: <what is wrong>".
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "io_detail.hpp"
#include "io_hdf5_checks.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_handle.hpp"
#include "powderbed/bed/input_file.hpp"
#include "powderbed/bed/io.hpp"

namespace powderbed::bed {

namespace {

// Conversion exception handler: a value out of the memory type's range (or a float -> integer
// truncation) aborts the read instead of being clamped.
H5T_conv_ret_t abort_on_range(H5T_conv_except_t kind, hid_t, hid_t, void*, void*, void* flag) {
  if (kind == H5T_CONV_EXCEPT_RANGE_HI || kind == H5T_CONV_EXCEPT_RANGE_LOW ||
      kind == H5T_CONV_EXCEPT_TRUNCATE) {
    *static_cast<bool*>(flag) = true;
    return H5T_CONV_ABORT;
  }
  return H5T_CONV_UNHANDLED;
}

template <class T>
const char* type_name() {
  if constexpr (std::is_same_v<T, std::uint16_t>) return "uint16";
  else if constexpr (std::is_same_v<T, std::uint8_t>) return "uint8";
  else if constexpr (std::is_same_v<T, std::uint64_t>) return "uint64";
  else return "float64";
}

template <class T>
std::string accepted_range() {
  if constexpr (std::is_integral_v<T>)
    return "0 to " + std::to_string(std::numeric_limits<T>::max());
  else
    return "float64 numbers";
}

class H5Reader {
 public:
  explicit H5Reader(std::string path) : path_(std::move(path)) {}

  Bed read() {
    open();
    Bed bed;
    read_root(bed);
    read_domain(bed.domain);
    read_particles(bed);
    read_provenance(bed.provenance);
    bed.validate(path_);  // NaN/Inf, radius <= 0, phase range, repeated ids
    if (bed.domain.dimension == 2) {
      for (std::size_t i = 0; i < bed.n(); ++i) {
        if (bed.z[i] != 0.0) {
          fail("/particles/position",
               fmt::format("z of particle {} is {:g} in a 2D bed (accepted: 0)", i, bed.z[i]));
        }
      }
    }
    bed.validate_geometry(path_);  // inside the domain, radii plausible for it
    return bed;
  }

 private:
  [[noreturn]] void fail(const std::string& object, const std::string& what) const {
    throw InputError(path_ + ": " + object + ": " + what);
  }

  void open() {
    require_regular_file(path_, "bed file");  // a FIFO would block the open below
    if (!std::ifstream(path_)) throw InputError(path_ + ": cannot open (missing or unreadable)");
    if (H5Fis_hdf5(path_.c_str()) <= 0)
      throw InputError(path_ + ": not an HDF5 file (accepted: a powderbed bed, format version 1)");
    // What libhdf5 1.10 would decode unchecked (io_hdf5_checks.hpp): the global heaps before
    // it opens the file, the attribute messages before any attribute is looked up.
    const std::string heaps = detail::damaged_global_heaps(path_);
    if (!heaps.empty())
      throw InputError(path_ + ": " + heaps + " (damaged file; accepted: a powderbed bed)");
    file_ = H5File(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
    if (!file_.valid()) throw InputError(path_ + ": cannot open as HDF5 (damaged file?)");
    const std::string messages = detail::damaged_attribute_messages(path_, file_);
    if (!messages.empty()) throw InputError(path_ + ": " + messages + " (damaged file?)");
  }

  H5Group group(const char* name) const {
    const std::string object = std::string("/") + name;
    if (H5Lexists(file_, name, H5P_DEFAULT) <= 0) fail(object, "missing (required group)");
    H5Group g(H5Gopen2(file_, name, H5P_DEFAULT));
    if (!g.valid()) fail(object, "is not a group");
    return g;
  }

  bool has_attr(hid_t loc, const char* name) const { return H5Aexists(loc, name) > 0; }

  H5Attr attr(hid_t loc, const std::string& object, const char* name) const {
    if (!has_attr(loc, name)) fail(object, std::string("attribute ") + name + " is missing");
    H5Attr a(H5Aopen(loc, name, H5P_DEFAULT));
    if (!a.valid()) fail(object, std::string("attribute ") + name + " cannot be opened (damaged file?)");
    return a;
  }

  // The number of values of attribute `a`, checked before anything is read: a scalar or a
  // simple dataspace (a damaged file can declare any extent; nothing is allocated from it).
  hssize_t attr_points(hid_t a, const std::string& object, const char* name) const {
    H5Space space(H5Aget_space(a));
    if (!space.valid()) fail(object, std::string("attribute ") + name + " has no dataspace (damaged file?)");
    const H5S_class_t kind = H5Sget_simple_extent_type(space);
    if (kind == H5S_SCALAR) return 1;
    if (kind != H5S_SIMPLE)
      fail(object, std::string("attribute ") + name + " is empty (accepted: a value)");
    return H5Sget_simple_extent_npoints(space);
  }

  // Longest string attribute read (the scene text of /provenance is a few KB).
  static constexpr std::size_t kMaxStringAttr = std::size_t{16} << 20;

  std::string string_attr(hid_t loc, const std::string& object, const char* name) const {
    H5Attr a = attr(loc, object, name);
    const std::string what = std::string("attribute ") + name;
    H5Type type(H5Aget_type(a));
    if (!type.valid() || H5Tget_class(type) != H5T_STRING) fail(object, what + " is not a string");
    const hssize_t points = attr_points(a, object, name);
    if (points != 1) {
      fail(object, what + " has " + std::to_string(points) +
                       " values (accepted: one string)");
    }
    const hsize_t stored = H5Aget_storage_size(a);
    const htri_t variable = H5Tis_variable_str(type);
    if (variable < 0) fail(object, what + " has a damaged string type");
    if (variable > 0) {  // as h5py writes them
      // One heap reference (16 bytes in HDF5 1.10) is what a variable-length string stores.
      if (stored == 0 || stored > 64) fail(object, what + " has a damaged string reference");
      H5Type mem(H5Tcopy(H5T_C_S1));
      H5Tset_size(mem, H5T_VARIABLE);
      H5Tset_cset(mem, H5Tget_cset(type));  // HDF5 does not convert ASCII <-> UTF-8
      char* text = nullptr;
      if (H5Aread(a, mem, &text) < 0) fail(object, what + " cannot be read");
      std::string value = text ? text : "";
      H5free_memory(text);
      if (value.size() > kMaxStringAttr) fail(object, what + " is too long");
      return value;
    }
    const std::size_t size = H5Tget_size(type);
    if (size == 0 || size > kMaxStringAttr) {
      fail(object, fmt::format("{} declares {} characters (accepted: 1 to {})", what, size,
                               kMaxStringAttr));
    }
    if (stored < size) {
      fail(object, fmt::format("{} declares {} characters but stores {} bytes (damaged file?)",
                               what, size, stored));
    }
    // Read through a memory type of our own (C string of the file's size and character set),
    // never through the file's type.
    H5Type mem(H5Tcopy(H5T_C_S1));
    H5Tset_size(mem, size);
    H5Tset_cset(mem, H5Tget_cset(type));
    H5Tset_strpad(mem, H5T_STR_NULLPAD);
    std::string value(size, '\0');
    if (H5Aread(a, mem, value.data()) < 0) fail(object, what + " cannot be read");
    value.resize(value.find('\0') == std::string::npos ? value.size() : value.find('\0'));
    return value;
  }

  // `count` numbers of attribute `name`, converted by HDF5 to `mem_type`.
  template <class T>
  void numeric_attr(hid_t loc, const std::string& object, const char* name, hid_t mem_type,
                    T* out, hssize_t count) const {
    H5Attr a = attr(loc, object, name);
    H5Type type(H5Aget_type(a));
    const H5T_class_t cls = type.valid() ? H5Tget_class(type) : H5T_NO_CLASS;
    if (cls != H5T_INTEGER && cls != H5T_FLOAT)
      fail(object, std::string("attribute ") + name + " is not numeric");
    const std::size_t size = H5Tget_size(type);
    if (size == 0 || size > 16) {
      fail(object, std::string("attribute ") + name + " has a " + std::to_string(size) +
                       "-byte number (accepted: 1 to 16 bytes)");
    }
    const hssize_t got = attr_points(a, object, name);
    if (got != count) {
      fail(object, fmt::format("attribute {} has {} values (accepted: {})", name, got, count));
    }
    if (H5Aget_storage_size(a) < static_cast<hsize_t>(count) * size)
      fail(object, std::string("attribute ") + name + " is truncated (damaged file?)");
    if (H5Aread(a, mem_type, out) < 0)
      fail(object, std::string("attribute ") + name + " cannot be read");
  }

  void read_root(Bed& bed) const {
    const std::string format = string_attr(file_, "/", "format");
    if (format != "powderbed.bed")
      fail("/", "format is '" + format + "' (accepted: powderbed.bed)");
    int version = 0;
    numeric_attr(file_, "/", "version", H5T_NATIVE_INT, &version, 1);
    if (version > kBedFormatVersion) {
      fail("/", fmt::format("format version {} is newer than this reader (accepted: {}; update "
                            "powderbed)",
                            version, kBedFormatVersion));
    }
    if (version < 1) {
      fail("/", fmt::format("format version {} (accepted: {})", version, kBedFormatVersion));
    }
    numeric_attr(file_, "/", "dimension", H5T_NATIVE_INT, &bed.domain.dimension, 1);
    if (has_attr(file_, "length_unit")) {
      const std::string unit = string_attr(file_, "/", "length_unit");
      if (unit != "m") fail("/", "length_unit is '" + unit + "' (accepted: m)");
    }
    Provenance& p = bed.provenance;
    if (has_attr(file_, "created_by")) p.created_by = string_attr(file_, "/", "created_by");
    if (has_attr(file_, "command_line")) p.command_line = string_attr(file_, "/", "command_line");
    if (has_attr(file_, "rng_seed"))
      numeric_attr(file_, "/", "rng_seed", H5T_NATIVE_UINT64, &p.rng_seed, 1);
  }

  void read_domain(Domain& d) const {
    H5Group g = group("domain");
    numeric_attr(g, "/domain", "lower", H5T_NATIVE_DOUBLE, d.lower.data(), 3);
    numeric_attr(g, "/domain", "upper", H5T_NATIVE_DOUBLE, d.upper.data(), 3);
    if (has_attr(g, "periodic")) {
      std::array<std::uint8_t, 3> periodic{};
      numeric_attr(g, "/domain", "periodic", H5T_NATIVE_UINT8, periodic.data(), 3);
      for (int a = 0; a < 3; ++a) {
        if (periodic[a] > 1) {
          fail("/domain", fmt::format("periodic[{}] is {} (accepted: 0 or 1)", a,
                                      int{periodic[a]}));
        }
        d.periodic[a] = periodic[a] == 1;
      }
    }
    d.validate((path_ + ": /domain").c_str());
  }

  // Dataset /particles/<name> of `rows` x `cols` (cols 0: one-dimensional; rows < 0: any, taken
  // from the file) read in one H5Dread, converted to `mem_type`. Returns false when `optional`
  // and absent.
  template <class T>
  bool dataset(hid_t particles, const char* name, H5T_class_t cls, hid_t mem_type, bool optional,
               hssize_t& rows, hsize_t cols, std::vector<T>& out) const {
    const std::string object = std::string("/particles/") + name;
    if (H5Lexists(particles, name, H5P_DEFAULT) <= 0) {
      if (optional) return false;
      fail(object, "missing (required dataset)");
    }
    H5Dataset set(H5Dopen2(particles, name, H5P_DEFAULT));
    if (!set.valid()) fail(object, "is not a dataset");
    H5Type type(H5Dget_type(set));
    if (!type.valid() || H5Tget_class(type) != cls)
      fail(object, cls == H5T_FLOAT ? "is not floating point" : "is not integer");
    H5Space space(H5Dget_space(set));
    const int rank = H5Sget_simple_extent_ndims(space);
    hsize_t dims[2] = {0, 0};
    if (rank == 1 || rank == 2) H5Sget_simple_extent_dims(space, dims, nullptr);
    const int want_rank = cols == 0 ? 1 : 2;
    if (rank != want_rank || (rank == 2 && dims[1] != cols)) {
      const std::string shape = rank == 2 ? fmt::format(", {} x {}", dims[0], dims[1]) : "";
      fail(object, fmt::format("wrong shape (rank {}{}; accepted: {})", rank, shape,
                               cols == 0 ? "N" : "N x 3"));
    }
    if (const std::string why = detail::oversized_dataset(set, type, dims[0], cols == 0 ? 1 : cols, sizeof(T));
        !why.empty())
      fail(object, why);
    if (rows < 0) {
      rows = static_cast<hssize_t>(dims[0]);
    } else if (dims[0] != static_cast<hsize_t>(rows)) {
      fail(object, fmt::format("has {} rows but /particles/position has {} (accepted: one per "
                               "particle)",
                               dims[0], rows));
    }
    out.resize(dims[0] * (cols == 0 ? 1 : cols));
    // HDF5 clamps a value that its memory type cannot hold (a material index 70000 or -1 read
    // as uint16 becomes 65535 or 0) unless told to abort: a clamped value is refused instead.
    H5Handle<H5Pclose> xfer(H5Pcreate(H5P_DATASET_XFER));
    bool out_of_range = false;
    H5Pset_type_conv_cb(xfer, abort_on_range, &out_of_range);
    if (!out.empty() && H5Dread(set, mem_type, H5S_ALL, H5S_ALL, xfer, out.data()) < 0) {
      if (out_of_range) {
        fail(object, std::string("holds values outside the range of ") + type_name<T>() +
                         " (accepted: " + accepted_range<T>() + ")");
      }
      fail(object, "cannot be read (damaged file?)");
    }
    return true;
  }

  void read_particles(Bed& bed) const {
    H5Group g = group("particles");
    hssize_t n = -1;
    std::vector<double> rows;
    dataset(g, "position", H5T_FLOAT, H5T_NATIVE_DOUBLE, false, n, 3, rows);
    split(rows, bed.x, bed.y, bed.z);
    dataset(g, "radius", H5T_FLOAT, H5T_NATIVE_DOUBLE, false, n, 0, bed.radius);
    dataset(g, "id", H5T_INTEGER, H5T_NATIVE_UINT64, false, n, 0, bed.id);
    dataset(g, "material", H5T_INTEGER, H5T_NATIVE_UINT16, true, n, 0, bed.material);
    if (dataset(g, "velocity", H5T_FLOAT, H5T_NATIVE_DOUBLE, true, n, 3, rows))
      split(rows, bed.vx, bed.vy, bed.vz);
    dataset(g, "temperature", H5T_FLOAT, H5T_NATIVE_DOUBLE, true, n, 0, bed.temperature);
    dataset(g, "phase", H5T_INTEGER, H5T_NATIVE_UINT8, true, n, 0, bed.phase);
  }

  void read_provenance(Provenance& p) const {
    if (H5Lexists(file_, "provenance", H5P_DEFAULT) <= 0) return;  // optional group
    H5Group g = group("provenance");
    if (has_attr(g, "stage")) p.stage = string_attr(g, "/provenance", "stage");
    if (has_attr(g, "scene")) p.scene = string_attr(g, "/provenance", "scene");
    if (!has_attr(g, "contact_law")) return;  // not recorded (ContactProvenance)
    ContactProvenance& c = p.contact;
    c.law = string_attr(g, "/provenance", "contact_law");
    if (c.law != "hertz" && c.law != "linear")
      fail("/provenance", "contact_law is '" + c.law + "' (accepted: hertz, linear)");
    const std::pair<const char*, double*> values[] = {
        {"contact_young", &c.young},           {"contact_poisson", &c.poisson},
        {"contact_wall_young", &c.wall_young}, {"contact_wall_poisson", &c.wall_poisson},
        {"contact_young_scale", &c.young_scale}, {"contact_stiffness", &c.stiffness}};
    for (const auto& [name, value] : values) {
      numeric_attr(g, "/provenance", name, H5T_NATIVE_DOUBLE, value, 1);
      if (!std::isfinite(*value))
        fail("/provenance", std::string(name) + " is not finite (accepted: a finite number)");
    }
    // Optional: beds written before fines scaling existed have none.
    if (has_attr(g, "contact_fines_stiffness_radius")) {
      numeric_attr(g, "/provenance", "contact_fines_stiffness_radius", H5T_NATIVE_DOUBLE,
                   &c.fines_stiffness_radius, 1);
      if (!(c.fines_stiffness_radius >= 0) || !std::isfinite(c.fines_stiffness_radius))
        fail("/provenance", "contact_fines_stiffness_radius is not a finite radius >= 0 "
                            "(accepted: 0 for none, or R_ref in m)");
    }
  }

  // N x 3 rows -> structure of arrays.
  static void split(const std::vector<double>& rows, std::vector<double>& a,
                    std::vector<double>& b, std::vector<double>& c) {
    const std::size_t n = rows.size() / 3;
    a.resize(n);
    b.resize(n);
    c.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      a[i] = rows[3 * i];
      b[i] = rows[3 * i + 1];
      c[i] = rows[3 * i + 2];
    }
  }

  std::string path_;
  H5File file_;
};

}  // namespace

Bed read_bed_h5(const std::string& path) {
  silence_hdf5_errors();
  return H5Reader(path).read();
}

}  // namespace powderbed::bed
