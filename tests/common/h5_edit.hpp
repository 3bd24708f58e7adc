#pragma once
// Damages a bed file through the HDF5 C API (the writer refuses bad beds), so tests can check
// that readers refuse it.
#include <hdf5.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace powderbed::test {

// Opens a bed read-write with the HDF5 C API to damage it (the writer refuses bad beds).
class H5Edit {
 public:
  explicit H5Edit(const std::string& path)
      : file_(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)) {
    EXPECT_GE(file_, 0);
  }
  ~H5Edit() { H5Fclose(file_); }
  H5Edit(const H5Edit&) = delete;
  H5Edit& operator=(const H5Edit&) = delete;
  hid_t file() const { return file_; }

  void remove(const char* name) { EXPECT_GE(H5Ldelete(file_, name, H5P_DEFAULT), 0); }

  // Replaces a float64 dataset by `values` shaped rows x cols (cols 0: one-dimensional).
  void replace(const char* name, const std::vector<double>& values, hsize_t cols) {
    remove(name);
    const hsize_t dims[2] = {cols == 0 ? values.size() : values.size() / cols, cols};
    const hid_t space = H5Screate_simple(cols == 0 ? 1 : 2, dims, nullptr);
    const hid_t set = H5Dcreate2(file_, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT,
                                 H5P_DEFAULT);
    EXPECT_GE(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
    H5Dclose(set);
    H5Sclose(space);
  }

  // Rewrites a root string attribute as fixed-length (as some writers store strings).
  void set_fixed_string_attr(const char* name, const std::string& value) {
    EXPECT_GE(H5Adelete(file_, name), 0);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, value.size());
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attr = H5Acreate2(file_, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    EXPECT_GE(H5Awrite(attr, type, value.data()), 0);
    H5Aclose(attr);
    H5Sclose(space);
    H5Tclose(type);
  }

  void set_int_attr(const char* name, int value) {
    const hid_t attr = H5Aopen(file_, name, H5P_DEFAULT);
    EXPECT_GE(H5Awrite(attr, H5T_NATIVE_INT, &value), 0);
    H5Aclose(attr);
  }

 private:
  hid_t file_;
};

}  // namespace powderbed::test
