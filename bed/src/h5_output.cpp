#include "powderbed/bed/h5_output.hpp"

#include <cstdio>
#include <optional>

#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_handle.hpp"

namespace powderbed::bed {

using H5Plist = H5Handle<H5Pclose>;

struct H5Output::Impl {
  std::string path;
  std::string shown_as;  // the name in messages
  std::optional<detail::AtomicFile> atomic;  // Mode::create: the temporary and its rename
  H5File file;
  H5Plist make_groups{H5Pcreate(H5P_LINK_CREATE)};

  Impl(const std::string& destination, Mode mode, const std::string& name)
      : path(destination), shown_as(name.empty() ? destination : name) {
    silence_hdf5_errors();
    if (mode == Mode::create) {
      atomic.emplace(path);
      file = H5File(H5Fcreate(atomic->temp_path().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
      if (!file.valid()) fail_io("/", "cannot create HDF5 file");
    } else {
      file = H5File(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
      if (!file.valid()) fail_io("/", "cannot open the HDF5 file to add to it");
    }
    H5Pset_create_intermediate_group(make_groups, 1);
  }

  [[noreturn]] void fail(const std::string& object, const std::string& what) const {
    throw InputError(shown_as + ": " + object + ": " + what);
  }
  // A failed write (a full disk, EIO): the system's reason, read before any other HDF5 call.
  [[noreturn]] void fail_io(const std::string& object, const std::string& what) const {
    fail(object, what + ": " + hdf5_failure_reason());
  }

  void dataset(const std::string& name, hid_t file_type, hid_t mem_type, const void* data,
               std::size_t size, const std::vector<std::size_t>& dims) {
    std::vector<hsize_t> shape(dims.begin(), dims.end());
    std::size_t count = 1;
    for (const auto d : dims) count *= d;
    if (count != size || dims.empty()) fail(name, "shape does not match the data size");
    H5Space space(H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr));
    H5Dataset set(H5Dcreate2(file, name.c_str(), file_type, space, make_groups, H5P_DEFAULT,
                             H5P_DEFAULT));
    if (!set.valid()) fail_io(name, "cannot create dataset");
    if (size > 0 && H5Dwrite(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
      fail_io(name, "cannot write dataset");
    // A small dataset waits in HDF5's sieve buffer until closed; a failed flush there loses it
    // and a later file close still succeeds, so the close is checked too.
    if (!set.close()) fail_io(name, "cannot write dataset");
  }

  // The object `name`, opened (a group is created when nothing exists there yet).
  hid_t open_object(const std::string& name) {
    if (name != "/" && H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0) {
      H5Group created(H5Gcreate2(file, name.c_str(), make_groups, H5P_DEFAULT, H5P_DEFAULT));
      if (!created.valid() || !created.close()) fail_io(name, "cannot create group");
    }
    const hid_t id = H5Oopen(file, name.c_str(), H5P_DEFAULT);
    if (id < 0) fail(name, "cannot open object");
    return id;
  }

  void attribute(const std::string& object, const std::string& name, hid_t file_type,
                 hid_t mem_type, const void* data, hsize_t count) {
    H5Handle<H5Oclose> where(open_object(object));
    H5Space space(count == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr));
    H5Attr attr(H5Acreate2(where, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT));
    if (!attr.valid() || H5Awrite(attr, mem_type, data) < 0 || !attr.close())
      fail_io(object, "cannot write attribute " + name);
  }
};

H5Output::H5Output(const std::string& path, Mode mode, const std::string& shown_as)
    : impl_(std::make_unique<Impl>(path, mode, shown_as)) {}
H5Output::~H5Output() = default;

void H5Output::write(const std::string& name, const std::vector<double>& data,
                     const std::vector<std::size_t>& dims, const std::string& units) {
  impl_->dataset(name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data.data(), data.size(), dims);
  attribute(name, "units", units);
}
void H5Output::write(const std::string& name, const std::vector<float>& data,
                     const std::vector<std::size_t>& dims, const std::string& units) {
  impl_->dataset(name, H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, data.data(), data.size(), dims);
  attribute(name, "units", units);
}
void H5Output::write(const std::string& name, const std::vector<std::uint8_t>& data,
                     const std::vector<std::size_t>& dims, const std::string& units) {
  impl_->dataset(name, H5T_STD_U8LE, H5T_NATIVE_UINT8, data.data(), data.size(), dims);
  attribute(name, "units", units);
}
void H5Output::write(const std::string& name, const std::vector<std::uint64_t>& data,
                     const std::vector<std::size_t>& dims, const std::string& units) {
  impl_->dataset(name, H5T_STD_U64LE, H5T_NATIVE_UINT64, data.data(), data.size(), dims);
  attribute(name, "units", units);
}

void H5Output::attribute(const std::string& object, const std::string& name, double value) {
  impl_->attribute(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, 1);
}
void H5Output::attribute(const std::string& object, const std::string& name,
                         const std::vector<double>& values) {
  impl_->attribute(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, values.data(), values.size());
}
void H5Output::attribute(const std::string& object, const std::string& name,
                         std::uint64_t value) {
  impl_->attribute(object, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value, 1);
}
void H5Output::attribute(const std::string& object, const std::string& name,
                         const std::string& value) {
  // Variable-length UTF-8 (h5py reads it as str, not bytes).
  H5Type type(H5Tcopy(H5T_C_S1));
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const char* text = value.c_str();
  impl_->attribute(object, name, type, type, &text, 1);
}

void H5Output::commit() {
  if (!impl_->file.close()) impl_->fail_io("/", "cannot finish the HDF5 file");
  if (impl_->atomic) impl_->atomic->commit();
}

const std::string& H5Output::path() const { return impl_->path; }

std::string step_group(std::uint64_t step) {
  char digits[32];
  std::snprintf(digits, sizeof digits, "%012llu", static_cast<unsigned long long>(step));
  return std::string("/steps/") + digits;
}

std::string xdmf_sidecar_path(const std::string& h5_path) { return detail::xdmf_path(h5_path); }

std::string file_name_of(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

void write_text_file(const std::string& path, std::string_view text) {
  detail::AtomicFile atomic(path);
  detail::write_text(atomic.temp_path(), path, text);
  atomic.commit();
}

}  // namespace powderbed::bed
