#pragma once
// Checks on the raw bytes of an HDF5 bed file for what libhdf5 1.10 decodes without checking
// (found by tests/fuzz; docs/hardening.md): the bed reader (io_hdf5_read.cpp) runs them before
// libhdf5 reads the parts concerned. Each returns "" for a file that passes, else what is wrong
// (one phrase, for "<file>: <phrase> (damaged file...)").
#include <hdf5.h>

#include <string>

namespace powderbed::bed::detail {

// The global heap collections (where variable-length strings such as /format live) and the
// references to them of the string attributes the reader reads. Run before H5Fopen.
std::string damaged_global_heaps(const std::string& path);

// The attribute messages of the groups whose attributes the reader reads ("/", /domain,
// /provenance) in version 1 object headers and their continuation blocks. `file`: the same file
// open in libhdf5 (to find the headers), before any attribute is looked up.
std::string damaged_attribute_messages(const std::string& path, hid_t file);

}  // namespace powderbed::bed::detail
