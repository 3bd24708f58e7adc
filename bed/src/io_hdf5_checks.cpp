// Raw-byte checks of an HDF5 bed file (io_hdf5_checks.hpp). Offsets and layouts: the HDF5 file
// format specification, version 3.0 (global heap collections "GCOL" §III.E, version 1 object
// headers §IV.A.1.a, the attribute message 0x000C §IV.A.2.m, the continuation message 0x0010
// §IV.A.2.q); every field is little-endian.
#include "io_hdf5_checks.hpp"

#include <fmt/format.h>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <utility>
#include <vector>

#include "io_detail.hpp"
#include "powderbed/bed/h5_handle.hpp"

namespace powderbed::bed::detail {

namespace {

// A file mapped read-only; bytes is null when it cannot be mapped or is under 16 bytes
// (H5Fopen then reports what is wrong).
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

  // Little-endian fields at byte k.
  std::size_t u16(std::size_t k) const {
    return std::size_t{bytes[k]} | (std::size_t{bytes[k + 1]} << 8);
  }
  std::uint32_t u32(std::size_t k) const {
    return std::uint32_t{bytes[k]} | (std::uint32_t{bytes[k + 1]} << 8) |
           (std::uint32_t{bytes[k + 2]} << 16) | (std::uint32_t{bytes[k + 3]} << 24);
  }
  std::uint64_t u64(std::size_t k) const {
    std::uint64_t v = 0;
    for (int b = 7; b >= 0; --b) v = (v << 8) | bytes[k + static_cast<std::size_t>(b)];
    return v;
  }
};

std::size_t align8(std::size_t n) { return (n + 7) / 8 * 8; }

// The objects of every global heap collection: (collection address, index) -> size.
using HeapObjects = std::map<std::pair<std::size_t, unsigned>, std::uint64_t>;

// The objects of the collection at byte o, ending at `stop`: free space (index 0) must count
// its own header (a size of 0 loops libhdf5 forever), and no object may run past the end.
std::string check_heap_objects(const MappedFile& f, std::size_t o, std::size_t stop,
                               HeapObjects& objects) {
  std::size_t p = o + 16;
  while (p + 16 <= stop) {
    const unsigned index = static_cast<unsigned>(f.u16(p));
    const std::uint64_t object = f.u64(p + 8);
    if (index == 0) {
      if (object < 16 || object > stop - p) {
        return "global heap free space at byte " + std::to_string(p) + " declares " +
               std::to_string(object) + " bytes (damaged)";
      }
      p += static_cast<std::size_t>(object);
      continue;
    }
    if (object > stop - p - 16) {
      return "global heap object " + std::to_string(index) + " at byte " + std::to_string(p) +
             " declares " + std::to_string(object) + " bytes, past its collection";
    }
    objects[{o, index}] = object;
    p += 16 + static_cast<std::size_t>((object + 7) / 8 * 8);
  }
  return "";
}

// Every collection ("GCOL", version 1) in the file: inside it, after the one before (libhdf5's
// cache loops forever on overlapping collections), and its objects.
std::string check_heap_collections(const MappedFile& f, HeapObjects& objects) {
  std::size_t previous_end = 0;
  const unsigned char* at = f.bytes;
  const unsigned char* end = f.bytes + f.size;
  while ((at = static_cast<const unsigned char*>(
              std::memchr(at, 'G', static_cast<std::size_t>(end - at))))) {
    const std::size_t o = static_cast<std::size_t>(at - f.bytes);
    ++at;
    if (o + 16 > f.size || std::memcmp(f.bytes + o, "GCOL", 4) != 0 || f.bytes[o + 4] != 1 ||
        f.bytes[o + 5] != 0 || f.bytes[o + 6] != 0 || f.bytes[o + 7] != 0)
      continue;
    const std::uint64_t length = f.u64(o + 8);
    if (o < previous_end) {
      return "global heap at byte " + std::to_string(o) + " overlaps the one before it";
    }
    if (length < 16 || length > f.size - o) {
      return "global heap at byte " + std::to_string(o) + " declares " + std::to_string(length) +
             " bytes, past the end of the file";
    }
    previous_end = o + static_cast<std::size_t>(length);
    const std::string problem = check_heap_objects(f, o, previous_end, objects);
    if (!problem.empty()) return problem;
  }
  return "";
}

// The attribute `name` (len: with its terminating null) found at byte pos, if pos is the name
// of an attribute message holding a variable-length string: its characters are one byte (libhdf5
// allocates length x base size before reading: a damaged base size of 13 369 345 asked for
// 3.2 GB) and its heap reference names an object that holds `length` bytes.
std::string check_string_reference(const MappedFile& f, const char* name, std::size_t len,
                                   std::size_t pos, const HeapObjects& objects) {
  // Message header before the name: v1 [1, 0, name, dt, ds] (8 bytes, fields padded to 8);
  // v2 [2, flags, name, dt, ds] (8 bytes); v3 the same plus a charset byte (9).
  std::size_t head = 0;
  int version = 0;
  if (pos >= 9 && f.bytes[pos - 9] == 3 && f.u16(pos - 7) == len) {
    head = pos - 9;
    version = 3;
  } else if (pos >= 8 && (f.bytes[pos - 8] == 1 || f.bytes[pos - 8] == 2) &&
             f.u16(pos - 6) == len) {
    head = pos - 8;
    version = f.bytes[pos - 8];
  } else {
    return "";
  }
  const std::size_t dt = f.u16(head + 4), ds = f.u16(head + 6);
  const bool pad = version == 1;
  const std::size_t type_at = pos + (pad ? align8(len) : len);
  const std::size_t data_at = type_at + (pad ? align8(dt) : dt) + (pad ? align8(ds) : ds);
  // A variable-length string type: class 9 (low nibble of the first byte), type 1 string.
  if (dt < 8 || type_at + 8 > f.size || (f.bytes[type_at] & 0x0f) != 9 ||
      (f.bytes[type_at + 1] & 0x0f) != 1 || data_at + 16 > f.size)
    return "";
  if (dt >= 20 && f.u32(type_at + 12) != 1) {
    return std::string("attribute ") + name + " has a damaged string type (characters of " +
           std::to_string(f.u32(type_at + 12)) + " bytes)";
  }
  const std::uint32_t length = f.u32(data_at);
  const std::uint64_t address = f.u64(data_at + 4);
  const std::uint32_t index = f.u32(data_at + 12);
  if (length == 0 && address == 0) return "";  // an empty string stores no heap object
  const auto it = objects.find({static_cast<std::size_t>(address), index});
  if (it == objects.end() || length > it->second) {
    return std::string("attribute ") + name + " refers to " + std::to_string(length) +
           " bytes of object " + std::to_string(index) + " of a global heap at byte " +
           std::to_string(address) + " that does not hold them";
  }
  return "";
}

// The references of the string attributes this reader reads: libhdf5 copies `length` bytes of
// object `index` of the collection at `address` without checking any of the three. Each
// attribute message (versions 1 to 3) holding one of these names is found by its name.
std::string check_string_references(const MappedFile& f, const HeapObjects& objects) {
  static const char* const names[] = {"format", "length_unit", "created_by", "command_line",
                                      "stage", "scene", "contact_law"};
  for (const char* name : names) {
    const std::size_t len = std::strlen(name) + 1;  // with its terminating null
    for (std::size_t from = 8; from + len <= f.size;) {
      const auto* hit =
          static_cast<const unsigned char*>(::memmem(f.bytes + from, f.size - from, name, len));
      if (!hit) break;
      const std::size_t pos = static_cast<std::size_t>(hit - f.bytes);
      from = pos + 1;
      const std::string problem = check_string_reference(f, name, len, pos, objects);
      if (!problem.empty()) return problem;
    }
  }
  return "";
}

// The value of an attribute message (its datatype at dt_at, dt bytes; its dataspace at ds_at,
// ds bytes): dataspace points x datatype size must fit the message's `length` after its
// `need` bytes of header, name, datatype and dataspace.
std::string check_attribute_value(const MappedFile& f, const std::string& object,
                                  std::size_t dt_at, std::size_t ds_at, std::size_t ds,
                                  std::size_t need, std::size_t length) {
  const std::uint64_t type_size = f.u64(dt_at + 4) & 0xffffffffu;
  const unsigned ds_version = f.bytes[ds_at], rank = f.bytes[ds_at + 1];
  const std::size_t dims_at = ds_at + (ds_version == 1 ? 8 : 4);
  double points = (ds_version == 2 && f.bytes[ds_at + 3] == 2) ? 0.0 : 1.0;  // null space
  if (dims_at + 8 * std::size_t{rank} > ds_at + ds) {
    return object + ": a damaged attribute dataspace";
  }
  for (unsigned r = 0; r < rank; ++r) points *= static_cast<double>(f.u64(dims_at + 8 * r));
  if (static_cast<double>(need) + points * static_cast<double>(type_size) >
      static_cast<double>(length)) {
    return object + ": an attribute value larger than its message";
  }
  return "";
}

// The attribute message whose data (`length` bytes) starts at byte `data`: a terminated name
// and parts that fit the message, a datatype class a bed uses, a value that fits.
std::string check_attribute(const MappedFile& f, const std::string& object, std::size_t data,
                            std::size_t length) {
  const unsigned version = f.bytes[data];
  const std::size_t name = f.u16(data + 2), dt = f.u16(data + 4), ds = f.u16(data + 6);
  const std::size_t head = version == 3 ? 9 : 8;
  const std::size_t need = version == 1 ? head + align8(name) + align8(dt) + align8(ds)
                                        : head + name + dt + ds;
  if (version < 1 || version > 3 || name == 0 || need > length ||
      f.bytes[data + head + name - 1] != 0) {
    return object + ": a damaged attribute message (name or parts do not fit)";
  }
  const std::size_t dt_at = data + head + (version == 1 ? align8(name) : name);
  const std::size_t ds_at = dt_at + (version == 1 ? align8(dt) : dt);
  // Only the classes a bed's attributes have: integer 0, float 1, string 3, variable-length 9
  // over integer characters (libhdf5 decodes compound and enum member names unchecked).
  const unsigned cls = f.bytes[dt_at] & 0x0f;
  if (dt < 8 || (cls != 0 && cls != 1 && cls != 3 && cls != 9) ||
      (cls == 9 && (dt < 16 || (f.bytes[dt_at + 8] & 0x0f) != 0))) {
    return object + ": an attribute of a datatype a bed does not use (class " +
           std::to_string(cls) + ")";
  }
  if (ds < 4) return "";
  return check_attribute_value(f, object, dt_at, ds_at, ds, need, length);
}

using Blocks = std::vector<std::pair<std::size_t, std::size_t>>;

// The messages of one header block [begin, end): type u16, size u16, flags, 3 reserved, data.
// A continuation message adds its block to `more`.
std::string check_header_block(const MappedFile& f, const std::string& object, std::size_t begin,
                               std::size_t end, Blocks& more) {
  for (std::size_t m = begin; m + 8 <= end;) {
    const std::size_t type = f.u16(m), length = f.u16(m + 2);
    const std::size_t data = m + 8;
    if (data + length > end) return object + ": a header message runs past its block";
    if (type == 0x10 && length >= 16) {  // continuation: offset, length
      const std::uint64_t at = f.u64(data), n = f.u64(data + 8);
      if (at >= f.size || n > f.size - at) {
        return object + ": a header continuation points past the end of the file";
      }
      more.emplace_back(static_cast<std::size_t>(at), static_cast<std::size_t>(at + n));
    }
    if (type == 0x0C && length >= 8) {
      const std::string problem = check_attribute(f, object, data, length);
      if (!problem.empty()) return problem;
    }
    m = data + length;
  }
  return "";
}

// The object header of group `name` ("." for the root), if it is a version 1 header (version 2
// headers are not checked), with up to 64 blocks.
std::string check_object_header(const MappedFile& f, hid_t file, const char* name) {
  if (std::string(name) != "." && H5Lexists(file, name, H5P_DEFAULT) <= 0) return "";
  H5O_info_t info{};
  if (H5Oget_info_by_name2(file, name, &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0) return "";
  const std::string object = std::string("/") + (std::string(name) == "." ? "" : name);
  const auto addr = static_cast<std::size_t>(info.addr);
  if (addr + 16 > f.size || f.bytes[addr] != 1) return "";
  const std::size_t header = static_cast<std::size_t>(f.u64(addr + 8) & 0xffffffffu);
  Blocks blocks{{addr + 16, addr + 16 + header}};
  if (blocks[0].second > f.size) return object + ": its header runs past the end of the file";
  for (std::size_t b = 0; b < blocks.size() && b < 64; ++b) {
    const auto [begin, end] = blocks[b];
    const std::string problem = check_header_block(f, object, begin, end, blocks);
    if (!problem.empty()) return problem;
  }
  return "";
}

}  // namespace

// libhdf5 1.10 trusts the sizes in a global heap collection: a damaged collection size makes it
// allocate gigabytes, a damaged object size makes it read past the collection (tests/fuzz).
std::string damaged_global_heaps(const std::string& path) {
  const MappedFile file(path);
  if (!file.bytes) return "";  // H5Fopen reports it
  HeapObjects objects;
  const std::string problem = check_heap_collections(file, objects);
  return problem.empty() ? check_string_references(file, objects) : problem;
}

// libhdf5 1.10 decodes an attribute message (while looking an attribute up by name) without
// checking that its name is terminated or that its parts fit the message (tests/fuzz: a read
// past the header in H5MM_strdup).
std::string damaged_attribute_messages(const std::string& path, hid_t file) {
  const MappedFile mapped(path);
  if (!mapped.bytes) return "";  // H5Fopen reports it
  for (const char* name : {".", "domain", "provenance"}) {
    const std::string problem = check_object_header(mapped, file, name);
    if (!problem.empty()) return problem;
  }
  return "";
}

std::string oversized_dataset(hid_t set, hid_t type, hsize_t rows, hsize_t cols, std::size_t mem_size) {
  constexpr double kMaxCompression = 2048;
  const std::size_t file_size = H5Tget_size(type);
  if (file_size == 0 || file_size > 16) {
    return fmt::format("has {}-byte numbers (damaged file?; accepted: 1 to 16 bytes)", file_size);
  }
  const double values = static_cast<double>(rows) * static_cast<double>(cols);
  if (values == 0) return "";
  const double declared = values * static_cast<double>(file_size);
  const double stored = static_cast<double>(H5Dget_storage_size(set));
  H5Handle<H5Pclose> plist(H5Dget_create_plist(set));
  const int filters = plist.valid() ? H5Pget_nfilters(plist) : 0;
  const double holds = filters > 0 ? stored * kMaxCompression : stored;
  if (declared > holds) {
    return fmt::format("declares {} rows ({:g} bytes) but the file stores {:g} bytes{} (damaged or "
                       "truncated file?; accepted: a dataset that holds its rows)",
                       rows, declared, stored, filters > 0 ? " compressed" : "");
  }
  const double need = values * static_cast<double>(mem_size);
  const double memory = usable_memory_bytes();
  if (memory > 0 && need > 0.5 * memory) {
    return fmt::format("has {} rows, needing {:g} GB (accepted: up to half of the {:g} GB this "
                       "process may use)",
                       rows, need / 1e9, memory / 1e9);
  }
  return "";
}

}  // namespace powderbed::bed::detail
