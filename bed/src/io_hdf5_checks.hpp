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

// The extent `rows` x `cols` a dataset declares, checked against what the file stores and what
// this machine holds BEFORE anything is allocated (a damaged or hostile 18 KB file can declare
// 2e9 rows): an unfiltered dataset must store every byte it declares; a compressed one cannot be
// more than 2048 times its stored size (deflate's limit is about 1032); and the rows, at
// `mem_size` bytes a value, must fit in half the memory. Every HDF5 reader (beds, /restart)
// calls it before it allocates.
std::string oversized_dataset(hid_t set, hid_t type, hsize_t rows, hsize_t cols, std::size_t mem_size);

}  // namespace powderbed::bed::detail
