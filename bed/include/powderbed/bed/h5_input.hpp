#pragma once
// Reading back what a stage wrote with H5Output (the spread's /restart group): datasets and
// attributes by path, each checked, so the stages need not use the HDF5 C API. Bed files have
// their own reader (io.hpp read_bed_h5), which checks a bed's every field.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace powderbed::bed {

class H5Input {
 public:
  // Opens `path` read-only; throws InputError naming it when it is not a readable HDF5 file.
  explicit H5Input(const std::string& path);
  ~H5Input();
  H5Input(const H5Input&) = delete;
  H5Input& operator=(const H5Input&) = delete;

  // Whether a group or dataset exists at `name` ("/a/b"; every group on the way must exist).
  bool exists(const std::string& name) const;
  // The two-dimensional dataset `name` of `cols` columns, row-major. Throws InputError naming
  // the file and the dataset when it is missing, has another shape or cannot be read.
  std::vector<double> read_doubles(const std::string& name, std::size_t cols) const;
  std::vector<std::uint64_t> read_uint64s(const std::string& name, std::size_t cols) const;
  // The scalar attribute `name` of the group or dataset `object`; throws InputError naming the
  // file, the object and the attribute when it is missing or cannot be read as that type.
  double double_attribute(const std::string& object, const std::string& name) const;
  std::uint64_t uint64_attribute(const std::string& object, const std::string& name) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace powderbed::bed
