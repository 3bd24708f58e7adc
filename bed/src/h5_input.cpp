#include "powderbed/bed/h5_input.hpp"

#include "io_hdf5_checks.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_handle.hpp"
#include "powderbed/bed/input_file.hpp"

namespace powderbed::bed {

struct H5Input::Impl {
  std::string path;
  H5File file;

  [[noreturn]] void fail(const std::string& object, const std::string& what) const {
    throw InputError(path + ": " + object + ": " + what);
  }

  template <class T>
  std::vector<T> read(const std::string& name, std::size_t cols, hid_t type) const {
    if (!exists(name)) fail(name, "missing");
    H5Dataset set(H5Dopen2(file, name.c_str(), H5P_DEFAULT));
    if (!set.valid()) fail(name, "not a dataset");
    H5Space space(H5Dget_space(set));
    hsize_t dims[2] = {0, 0};
    if (H5Sget_simple_extent_ndims(space) != 2 ||
        H5Sget_simple_extent_dims(space, dims, nullptr) < 0 || dims[1] != cols) {
      fail(name, "not an N x " + std::to_string(cols) + " array");
    }
    H5Type file_type(H5Dget_type(set));
    if (const std::string why = detail::oversized_dataset(set, file_type, dims[0], dims[1], sizeof(T));
        !why.empty())
      fail(name, why);
    std::vector<T> data(static_cast<std::size_t>(dims[0] * dims[1]));
    if (!data.empty() && H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
      fail(name, "cannot be read");
    return data;
  }

  template <class T>
  T attribute(const std::string& object, const std::string& name, hid_t type) const {
    if (!exists(object)) fail(object, "missing");
    H5Attr attr(H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT));
    T value{};
    if (!attr.valid() || H5Aread(attr, type, &value) < 0)
      fail(object, "attribute " + name + " is missing");
    return value;
  }

  // Each link on the way is tested in turn: H5Lexists fails, rather than answering false, when
  // a group above the last one is missing.
  bool exists(const std::string& name) const {
    for (std::size_t end = name.find('/', 1);; end = name.find('/', end + 1)) {
      const std::string prefix = name.substr(0, end);
      if (prefix != "/" && H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
      if (end == std::string::npos) return true;
    }
  }
};

H5Input::H5Input(const std::string& path) : impl_(std::make_unique<Impl>()) {
  silence_hdf5_errors();
  impl_->path = path;
  require_regular_file(path, "HDF5 file");  // a FIFO would block H5Fopen
  impl_->file = H5File(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  if (!impl_->file.valid()) impl_->fail("/", "cannot open as an HDF5 file");
}

H5Input::~H5Input() = default;

bool H5Input::exists(const std::string& name) const { return impl_->exists(name); }

std::vector<double> H5Input::read_doubles(const std::string& name, std::size_t cols) const {
  return impl_->read<double>(name, cols, H5T_NATIVE_DOUBLE);
}
std::vector<std::uint64_t> H5Input::read_uint64s(const std::string& name, std::size_t cols) const {
  return impl_->read<std::uint64_t>(name, cols, H5T_NATIVE_UINT64);
}
double H5Input::double_attribute(const std::string& object, const std::string& name) const {
  return impl_->attribute<double>(object, name, H5T_NATIVE_DOUBLE);
}
std::uint64_t H5Input::uint64_attribute(const std::string& object, const std::string& name) const {
  return impl_->attribute<std::uint64_t>(object, name, H5T_NATIVE_UINT64);
}

}  // namespace powderbed::bed
