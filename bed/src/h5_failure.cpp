// What every HDF5 writer (write_bed_h5, H5Output) needs when a write fails: the system's reason,
// and a library that does not crash afterwards (docs/hardening.md "Full disk").
#include <hdf5.h>

#include <string>

#include "powderbed/bed/h5_handle.hpp"

namespace powderbed::bed {

namespace {

// libhdf5 1.10 (Debian 12) frees a file whose closing flush failed (a full disk) but leaves its
// identifier in the table; the library's atexit handler closes that identifier again and reads
// freed memory: "right message, old file intact, then SIGSEGV". Our writers close every object
// themselves and a failed file is a removed temporary, so nothing is lost by not registering the
// handler. It must be declined before the library initialises, hence at static initialisation
// of this file, which every writer links (it calls hdf5_failure_reason()).
const bool g_no_hdf5_atexit = H5dont_atexit() >= 0;

herr_t find_reason(unsigned /*n*/, const H5E_error2_t* e, void* data) {
  auto* reason = static_cast<std::string*>(data);
  if (!reason->empty() || !e->desc) return 0;
  // The sec2 driver's message: "file write failed: ..., errno = 28, error message = 'No space
  // left on device', ...".
  const std::string desc = e->desc;
  const std::string key = "error message = '";
  const auto at = desc.find(key);
  if (at == std::string::npos) return 0;
  const auto end = desc.find('\'', at + key.size());
  if (end != std::string::npos) *reason = desc.substr(at + key.size(), end - at - key.size());
  return 0;
}

}  // namespace

std::string hdf5_failure_reason() {
  (void)g_no_hdf5_atexit;
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, find_reason, &reason);
  return reason.empty() ? "an input/output error (disk full?)" : reason;
}

}  // namespace powderbed::bed
