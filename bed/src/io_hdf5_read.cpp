// Reader of the HDF5 bed file, format version 1 (docs/bed-format.md): checks everything and
// refuses a bad file with one line "<file>: <dataset>: <what is wrong>".
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cstring>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <type_traits>
#include <sstream>
#include <utility>
#include <vector>

#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_handle.hpp"
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

// A file mapped read-only for the checks made before libhdf5 opens it; bytes is null when it
// cannot be mapped or is under 16 bytes (H5Fopen then reports what is wrong).
struct MappedFile {
  const unsigned char* bytes = nullptr;
  std::size_t size = 0;
  explicit MappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0) return;
    struct stat st {};
    if (::fstat(fd, &st) == 0 && st.st_size >= 16) {
      void* map = ::mmap(nullptr, static_cast<std::size_t>(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
      if (map != MAP_FAILED) {
        bytes = static_cast<const unsigned char*>(map);
        size = static_cast<std::size_t>(st.st_size);
      }
    }
    ::close(fd);
  }
  ~MappedFile() {
    if (bytes) ::munmap(const_cast<unsigned char*>(bytes), size);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
};

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
          std::ostringstream msg;
          msg << "z of particle " << i << " is " << bed.z[i] << " in a 2D bed (accepted: 0)";
          fail("/particles/position", msg.str());
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
    if (!std::ifstream(path_)) throw InputError(path_ + ": cannot open (missing or unreadable)");
    if (H5Fis_hdf5(path_.c_str()) <= 0)
      throw InputError(path_ + ": not an HDF5 file (accepted: a powderbed bed, format version 1)");
    check_global_heaps();
    file_ = H5File(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
    if (!file_.valid()) throw InputError(path_ + ": cannot open as HDF5 (damaged file?)");
    check_attribute_messages();
  }

  // libhdf5 1.10 decodes an attribute message (while looking an attribute up by name) without
  // checking that its name is terminated or that its parts fit the message (found by
  // tests/fuzz: a read past the header in H5MM_strdup). The attribute messages of the groups
  // whose attributes are read ("/", /domain, /provenance; version 1 object headers, as
  // libhdf5 1.10 writes them, and their continuation blocks) are checked first.
  void check_attribute_messages() const {
    const MappedFile file(path_);
    if (!file.bytes) return;  // H5Fopen reports it
    const unsigned char* bytes = file.bytes;
    const std::size_t size = file.size;
    auto u16 = [&](std::size_t k) { return std::size_t{bytes[k]} | (std::size_t{bytes[k + 1]} << 8); };
    auto u64 = [&](std::size_t k) {
      std::uint64_t v = 0;
      for (int b = 7; b >= 0; --b) v = (v << 8) | bytes[k + static_cast<std::size_t>(b)];
      return v;
    };
    auto align8 = [](std::size_t n) { return (n + 7) / 8 * 8; };
    std::string problem;
    // The messages of one block [begin, end): type u16, size u16, flags, 3 reserved, data.
    auto check_block = [&](const std::string& object, std::size_t begin, std::size_t end,
                           std::vector<std::pair<std::size_t, std::size_t>>& more) {
      for (std::size_t m = begin; problem.empty() && m + 8 <= end;) {
        const std::size_t type = u16(m), length = u16(m + 2);
        const std::size_t data = m + 8;
        if (data + length > end) {
          problem = object + ": a header message runs past its block";
          break;
        }
        if (type == 0x10 && length >= 16) {  // continuation: offset, length
          const std::uint64_t at = u64(data), n = u64(data + 8);
          if (at >= size || n > size - at) {
            problem = object + ": a header continuation points past the end of the file";
            break;
          }
          more.emplace_back(static_cast<std::size_t>(at), static_cast<std::size_t>(at + n));
        }
        if (type == 0x0C && length >= 8) {  // attribute
          const unsigned version = bytes[data];
          const std::size_t name = u16(data + 2), dt = u16(data + 4), ds = u16(data + 6);
          const std::size_t head = version == 3 ? 9 : 8;
          const std::size_t need = version == 1 ? head + align8(name) + align8(dt) + align8(ds)
                                                : head + name + dt + ds;
          if (version < 1 || version > 3 || name == 0 || need > length ||
              bytes[data + head + name - 1] != 0) {
            problem = object + ": a damaged attribute message (name or parts do not fit)";
            break;
          }
          // Its value: dataspace points x datatype size must fit the message too.
          const std::size_t dt_at = data + head + (version == 1 ? align8(name) : name);
          const std::size_t ds_at = dt_at + (version == 1 ? align8(dt) : dt);
          // Only the classes a bed's attributes have: integer 0, float 1, string 3, variable-
          // length 9 over integer characters (libhdf5 decodes compound and enum member names
          // unchecked).
          const unsigned cls = bytes[dt_at] & 0x0f;
          if (dt < 8 || (cls != 0 && cls != 1 && cls != 3 && cls != 9) ||
              (cls == 9 && (dt < 16 || (bytes[dt_at + 8] & 0x0f) != 0))) {
            problem = object + ": an attribute of a datatype a bed does not use (class " +
                      std::to_string(cls) + ")";
            break;
          }
          if (dt >= 8 && ds >= 4) {
            const std::uint64_t type_size = u64(dt_at + 4) & 0xffffffffu;
            const unsigned ds_version = bytes[ds_at], rank = bytes[ds_at + 1];
            const std::size_t dims_at = ds_at + (ds_version == 1 ? 8 : 4);
            double points = (ds_version == 2 && bytes[ds_at + 3] == 2) ? 0.0 : 1.0;  // null space
            if (dims_at + 8 * std::size_t{rank} > ds_at + ds) {
              problem = object + ": a damaged attribute dataspace";
              break;
            }
            for (unsigned r = 0; r < rank; ++r) points *= static_cast<double>(u64(dims_at + 8 * r));
            if (static_cast<double>(need) + points * static_cast<double>(type_size) >
                static_cast<double>(length)) {
              problem = object + ": an attribute value larger than its message";
              break;
            }
          }
        }
        m = data + length;
      }
    };
    for (const char* name : {".", "domain", "provenance"}) {
      if (!problem.empty()) break;
      if (std::string(name) != "." && H5Lexists(file_, name, H5P_DEFAULT) <= 0) continue;
      H5O_info_t info{};
      if (H5Oget_info_by_name2(file_, name, &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0) continue;
      const std::string object = std::string("/") + (std::string(name) == "." ? "" : name);
      const auto addr = static_cast<std::size_t>(info.addr);
      if (addr + 16 > size || bytes[addr] != 1) continue;  // version 2 headers: not checked
      const std::size_t header = static_cast<std::size_t>(u64(addr + 8) & 0xffffffffu);
      std::vector<std::pair<std::size_t, std::size_t>> blocks{{addr + 16, addr + 16 + header}};
      if (blocks[0].second > size) {
        problem = object + ": its header runs past the end of the file";
        break;
      }
      for (std::size_t b = 0; problem.empty() && b < blocks.size() && b < 64; ++b) {
        const auto [begin, end] = blocks[b];
        check_block(object, begin, end, blocks);
      }
    }
    if (!problem.empty()) throw InputError(path_ + ": " + problem + " (damaged file?)");
  }

  // libhdf5 1.10 trusts the sizes in a global heap collection (where variable-length strings
  // such as /format live): a damaged collection size makes it allocate gigabytes, a damaged
  // object size makes it read past the collection (found by tests/fuzz). So each collection
  // ("GCOL", version 1) is checked first: inside the file, and every object inside it.
  void check_global_heaps() const {
    const MappedFile file(path_);
    if (!file.bytes) return;  // H5Fopen reports it
    const unsigned char* bytes = file.bytes;
    const std::size_t size = file.size;
    auto u64 = [&](std::size_t at) {
      std::uint64_t v = 0;
      for (int k = 7; k >= 0; --k) v = (v << 8) | bytes[at + static_cast<std::size_t>(k)];
      return v;
    };
    std::string problem;
    std::size_t previous_end = 0;
    std::vector<std::size_t> collections;
    std::map<std::pair<std::size_t, unsigned>, std::uint64_t> objects;  // (heap, index) -> size
    const unsigned char* at = bytes;
    const unsigned char* end = bytes + size;
    while (problem.empty() && (at = static_cast<const unsigned char*>(
                                   std::memchr(at, 'G', static_cast<std::size_t>(end - at))))) {
      const std::size_t o = static_cast<std::size_t>(at - bytes);
      ++at;
      if (o + 16 > size || std::memcmp(bytes + o, "GCOL", 4) != 0 || bytes[o + 4] != 1 ||
          bytes[o + 5] != 0 || bytes[o + 6] != 0 || bytes[o + 7] != 0)
        continue;
      const std::uint64_t length = u64(o + 8);
      if (o < previous_end) {  // libhdf5's cache loops forever on overlapping collections
        problem = "global heap at byte " + std::to_string(o) + " overlaps the one before it";
        break;
      }
      if (length < 16 || length > size - o) {
        problem = "global heap at byte " + std::to_string(o) + " declares " +
                  std::to_string(length) + " bytes, past the end of the file";
        break;
      }
      std::size_t p = o + 16;
      const std::size_t stop = o + static_cast<std::size_t>(length);
      previous_end = stop;
      while (p + 16 <= stop) {
        const unsigned index = bytes[p] | (unsigned{bytes[p + 1]} << 8);
        const std::uint64_t object = u64(p + 8);
        if (index == 0) {  // free space, its size counting its header: 0 loops libhdf5 forever
          if (object < 16 || object > stop - p) {
            problem = "global heap free space at byte " + std::to_string(p) + " declares " +
                      std::to_string(object) + " bytes (damaged)";
            break;
          }
          p += static_cast<std::size_t>(object);
          continue;
        }
        if (object > stop - p - 16) {
          problem = "global heap object " + std::to_string(index) + " at byte " +
                    std::to_string(p) + " declares " + std::to_string(object) +
                    " bytes, past its collection";
          break;
        }
        objects[{o, index}] = object;
        p += 16 + static_cast<std::size_t>((object + 7) / 8 * 8);
      }
      collections.push_back(o);
    }
    // The references of the string attributes this reader reads: libhdf5 copies `length`
    // bytes of object `index` of the collection at `address` without checking any of the
    // three. Each attribute message (versions 1 to 3) holding one of these names is found by
    // its name and its reference checked against the collections above.
    static const char* const names[] = {"format", "length_unit", "created_by", "command_line",
                                        "stage", "scene", "contact_law"};
    auto u16 = [&](std::size_t k) { return unsigned{bytes[k]} | (unsigned{bytes[k + 1]} << 8); };
    auto u32 = [&](std::size_t k) {
      return std::uint32_t{bytes[k]} | (std::uint32_t{bytes[k + 1]} << 8) |
             (std::uint32_t{bytes[k + 2]} << 16) | (std::uint32_t{bytes[k + 3]} << 24);
    };
    auto align8 = [](std::size_t n) { return (n + 7) / 8 * 8; };
    for (const char* name : names) {
      if (!problem.empty()) break;
      const std::size_t len = std::strlen(name) + 1;  // with its terminating null
      for (std::size_t from = 8; problem.empty() && from + len <= size;) {
        const auto* hit = static_cast<const unsigned char*>(
            ::memmem(bytes + from, size - from, name, len));
        if (!hit) break;
        const std::size_t pos = static_cast<std::size_t>(hit - bytes);
        from = pos + 1;
        // Message header before the name: v1 [1, 0, name, dt, ds] (8 bytes, fields padded to
        // 8); v2 [2, flags, name, dt, ds] (8 bytes); v3 the same plus a charset byte (9).
        std::size_t head = 0;
        int version = 0;
        if (pos >= 9 && bytes[pos - 9] == 3 && u16(pos - 7) == len) {
          head = pos - 9;
          version = 3;
        } else if (pos >= 8 && (bytes[pos - 8] == 1 || bytes[pos - 8] == 2) && u16(pos - 6) == len) {
          head = pos - 8;
          version = bytes[pos - 8];
        } else {
          continue;
        }
        const std::size_t dt = u16(head + 4), ds = u16(head + 6);
        const bool pad = version == 1;
        const std::size_t type_at = pos + (pad ? align8(len) : len);
        const std::size_t data_at = type_at + (pad ? align8(dt) : dt) + (pad ? align8(ds) : ds);
        // A variable-length string type: class 9 (low nibble of the first byte), type 1 string.
        if (dt < 8 || type_at + 8 > size || (bytes[type_at] & 0x0f) != 9 ||
            (bytes[type_at + 1] & 0x0f) != 1 || data_at + 16 > size)
          continue;
        // Its characters: a 1-byte base type (libhdf5 allocates length x base size before
        // reading: a damaged base size of 13 369 345 asked for 3.2 GB).
        if (dt >= 20 && u32(type_at + 12) != 1) {
          problem = std::string("attribute ") + name + " has a damaged string type (characters of " +
                    std::to_string(u32(type_at + 12)) + " bytes)";
          break;
        }
        const std::uint32_t length = u32(data_at);
        const std::uint64_t address = u64(data_at + 4);
        const std::uint32_t index = u32(data_at + 12);
        if (length == 0 && address == 0) continue;  // an empty string stores no heap object
        const auto it = objects.find({static_cast<std::size_t>(address), index});
        if (it == objects.end() || length > it->second) {
          problem = std::string("attribute ") + name + " refers to " + std::to_string(length) +
                    " bytes of object " + std::to_string(index) + " of a global heap at byte " +
                    std::to_string(address) + " that does not hold them";
        }
      }
    }
    if (!problem.empty())
      throw InputError(path_ + ": " + problem + " (damaged file; accepted: a powderbed bed)");
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
      fail(object, what + " declares " + std::to_string(size) +
                       " characters (accepted: 1 to " + std::to_string(kMaxStringAttr) + ")");
    }
    if (stored < size) {
      fail(object, what + " declares " + std::to_string(size) + " characters but stores " +
                       std::to_string(stored) + " bytes (damaged file?)");
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
      fail(object, std::string("attribute ") + name + " has " + std::to_string(got) +
                       " values (accepted: " + std::to_string(count) + ")");
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
      fail("/", "format version " + std::to_string(version) +
                    " is newer than this reader (accepted: " + std::to_string(kBedFormatVersion) +
                    "; update powderbed)");
    }
    if (version < 1) {
      fail("/", "format version " + std::to_string(version) +
                    " (accepted: " + std::to_string(kBedFormatVersion) + ")");
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
          fail("/domain", std::string("periodic[") + std::to_string(a) + "] is " +
                              std::to_string(periodic[a]) + " (accepted: 0 or 1)");
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
      std::ostringstream msg;
      msg << "wrong shape (rank " << rank;
      if (rank == 2) msg << ", " << dims[0] << " x " << dims[1];
      msg << "; accepted: " << (cols == 0 ? "N" : "N x 3") << ")";
      fail(object, msg.str());
    }
    check_extent(set, type, object, dims[0], cols == 0 ? 1 : cols, sizeof(T));
    if (rows < 0) {
      rows = static_cast<hssize_t>(dims[0]);
    } else if (dims[0] != static_cast<hsize_t>(rows)) {
      fail(object, "has " + std::to_string(dims[0]) + " rows but /particles/position has " +
                       std::to_string(rows) + " (accepted: one per particle)");
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
  }

  // The extent a dataset declares, checked against what the file stores and what this machine
  // holds BEFORE anything is allocated (a damaged or hostile 18 KB file can declare 2e9 rows):
  // an unfiltered dataset must store every byte it declares; a compressed one cannot be more
  // than kMaxCompression times its stored size (deflate's limit is about 1032); and the rows
  // must fit in memory.
  void check_extent(hid_t set, hid_t type, const std::string& object, hsize_t rows, hsize_t cols,
                    std::size_t mem_size) const {
    constexpr double kMaxCompression = 2048;
    const std::size_t file_size = H5Tget_size(type);
    if (file_size == 0 || file_size > 16) {
      fail(object, "has " + std::to_string(file_size) +
                       "-byte numbers (damaged file?; accepted: 1 to 16 bytes)");
    }
    const double values = static_cast<double>(rows) * static_cast<double>(cols);
    if (values == 0) return;
    const double declared = values * static_cast<double>(file_size);
    const double stored = static_cast<double>(H5Dget_storage_size(set));
    H5Handle<H5Pclose> plist(H5Dget_create_plist(set));
    const int filters = plist.valid() ? H5Pget_nfilters(plist) : 0;
    const double holds = filters > 0 ? stored * kMaxCompression : stored;
    if (declared > holds) {
      std::ostringstream msg;
      msg << "declares " << rows << " rows (" << declared << " bytes) but the file stores "
          << stored << " bytes" << (filters > 0 ? " compressed" : "")
          << " (damaged or truncated file?; accepted: a dataset that holds its rows)";
      fail(object, msg.str());
    }
    const double need = values * static_cast<double>(mem_size);
    const double memory = detail::physical_memory_bytes();
    if (memory > 0 && need > 0.5 * memory) {
      std::ostringstream msg;
      msg << "has " << rows << " rows, needing " << need / 1e9 << " GB (accepted: up to half "
          << "of this machine's " << memory / 1e9 << " GB)";
      fail(object, msg.str());
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
