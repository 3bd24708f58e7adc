#pragma once
// A results file in HDF5 for the stages' time series (sinter runs, trajectories): datasets and
// attributes by path, intermediate groups created on the way. Written under a temporary name
// and renamed by commit(), so a failed run never leaves half a file under the requested name
// (docs/architecture.md "Command-line programs"). The HDF5 C API stays behind this interface.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace powderbed::bed {

class H5Output {
 public:
  // create: a new file, written as `<path>.tmp.<pid>` and renamed by commit(). append: adds to
  // the existing HDF5 file `path` in place; used only on a temporary that is not yet renamed
  // into place (write_bed_h5's `extra`: the spread's /restart beside the bed), never on a user's
  // file, which a failure would leave half-written.
  enum class Mode { create, append };
  // Throws InputError naming `path` (or `shown_as`, the name the user knows a temporary by) when
  // it cannot create (or open) the file or write to it.
  explicit H5Output(const std::string& path, Mode mode = Mode::create,
                    const std::string& shown_as = "");
  ~H5Output();  // removes the temporary unless commit() succeeded
  H5Output(const H5Output&) = delete;
  H5Output& operator=(const H5Output&) = delete;

  // Dataset at `name` ("/a/b/c") with shape `dims` (row-major; the product must equal the size
  // of `data`) and its SI unit as the attribute `units` ("1": a number without unit). Throws
  // InputError naming the file and dataset on failure.
  void write(const std::string& name, const std::vector<double>& data,
             const std::vector<std::size_t>& dims, const std::string& units);
  void write(const std::string& name, const std::vector<float>& data,
             const std::vector<std::size_t>& dims, const std::string& units);
  void write(const std::string& name, const std::vector<std::uint8_t>& data,
             const std::vector<std::size_t>& dims, const std::string& units);
  void write(const std::string& name, const std::vector<std::uint64_t>& data,
             const std::vector<std::size_t>& dims, const std::string& units);
  // Attributes of the group or dataset `object` (created as a group when missing).
  void attribute(const std::string& object, const std::string& name, double value);
  void attribute(const std::string& object, const std::string& name,
                 const std::vector<double>& values);
  void attribute(const std::string& object, const std::string& name, std::uint64_t value);
  void attribute(const std::string& object, const std::string& name, const std::string& value);

  // Closes the file and renames it into place (create); throws InputError on failure.
  void commit();
  const std::string& path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The group of time step `step` in a time series: "/steps/" and the step in 12 digits, so that
// the groups' lexical order (h5py, h5ls) is their time order.
std::string step_group(std::uint64_t step);

// The XDMF sidecar of an HDF5 file: `<path minus .h5>.xmf` (docs/bed-format.md).
std::string xdmf_sidecar_path(const std::string& h5_path);
// The last component of a path: how an XDMF file names the HDF5 file beside it.
std::string file_name_of(const std::string& path);

// Writes `text` to `path` atomically (temporary file + rename); throws InputError naming `path`.
void write_text_file(const std::string& path, std::string_view text);

}  // namespace powderbed::bed
