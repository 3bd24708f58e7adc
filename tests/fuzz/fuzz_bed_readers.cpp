// libFuzzer target over the bed readers (docs/hardening.md): the first byte picks the reader
// (HDF5, CSV with a fixed domain, LAMMPS dump), the rest is the file. A reader may refuse its
// input only with powderbed::InputError; any other exception, a crash, a sanitizer report, an
// allocation above -malloc_limit_mb or a run above -timeout is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"

namespace {

// POWDERBED_FUZZ_READERS=text restricts the run to the CSV and dump readers (ctest runs both
// modes: tests/fuzz/CMakeLists.txt); unset or "all": all three.
bool text_only() {
  static const bool only = [] {
    const char* v = std::getenv("POWDERBED_FUZZ_READERS");
    return v && std::string(v) == "text";
  }();
  return only;
}

std::string scratch(const char* ext) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir && *dir ? dir : "/tmp") + "/powderbed_fuzz_" + std::to_string(::getpid()) + ext;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  int kind = data[0] % 3;
  if (text_only() && kind == 0) kind = 1 + data[0] / 3 % 2;
  static const char* const ext[3] = {".h5", ".csv", ".dump"};
  const std::string path = scratch(ext[kind]);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  std::fwrite(data + 1, 1, size - 1, f);
  std::fclose(f);
  try {
    powderbed::bed::Domain domain;
    domain.upper = {1e-3, 1e-3, 1e-3};
    if (kind == 0) powderbed::bed::read_bed_h5(path);
    if (kind == 1) powderbed::bed::read_bed_csv(path, domain);
    if (kind == 2) powderbed::bed::read_lammps_dump(path);
  } catch (const powderbed::InputError&) {
    // the promised refusal
  }
  std::remove(path.c_str());
  return 0;
}
