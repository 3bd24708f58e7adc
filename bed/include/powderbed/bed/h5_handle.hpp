#pragma once
// RAII ownership of HDF5 C API identifiers (hid_t), one small type per close function: bed's
// files, H5Output and H5Input close what they open on every path, errors included. Including it
// needs HDF5's headers (HDF5_INCLUDE_DIRS), which only bed has: the stages go through H5Output
// and H5Input.
#include <hdf5.h>

#include <string>
#include <utility>

namespace powderbed::bed {

template <herr_t (*Close)(hid_t)>
class H5Handle {
 public:
  H5Handle() = default;
  explicit H5Handle(hid_t id) : id_(id) {}
  ~H5Handle() { reset(); }
  H5Handle(H5Handle&& other) noexcept : id_(std::exchange(other.id_, -1)) {}
  H5Handle& operator=(H5Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, -1);
    }
    return *this;
  }
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;

  bool valid() const { return id_ >= 0; }
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }  // NOLINT: passes straight into the C API

  // Closes now and reports whether closing succeeded (a file's final flush happens here).
  bool close() {
    const bool ok = id_ < 0 || Close(id_) >= 0;
    id_ = -1;
    return ok;
  }

 private:
  void reset() {
    if (id_ >= 0) Close(id_);
    id_ = -1;
  }
  hid_t id_ = -1;
};

using H5File = H5Handle<H5Fclose>;
using H5Group = H5Handle<H5Gclose>;
using H5Dataset = H5Handle<H5Dclose>;
using H5Space = H5Handle<H5Sclose>;
using H5Attr = H5Handle<H5Aclose>;
using H5Type = H5Handle<H5Tclose>;

// HDF5 prints its error stack to stderr by default; we report our own one-line errors instead.
inline void silence_hdf5_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

// The system's reason for the HDF5 write that just failed ("No space left on device"), read
// from HDF5's error stack, so call it before any other HDF5 call (each clears the stack); a
// generic reason when HDF5 recorded none (h5_failure.cpp, which also keeps libhdf5 from crashing
// at exit after such a failure).
std::string hdf5_failure_reason();

}  // namespace powderbed::bed
