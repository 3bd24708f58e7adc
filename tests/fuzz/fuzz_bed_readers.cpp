// libFuzzer target over the bed readers (docs/hardening.md): the first byte picks the reader
// (HDF5, CSV with a fixed domain, LAMMPS dump; in the "foreign" mode LAMMPS data, YADE text,
// GenGeo .geo, every snapshot of a dump that may be gzipped), the rest is the file. A reader may refuse its
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

// POWDERBED_FUZZ_READERS=text restricts the run to the CSV and dump readers, =foreign to the
// readers of docs/decks.md (ctest runs every mode: tests/fuzz/CMakeLists.txt); unset or "all":
// the first three.
std::string mode() {
  static const std::string m = [] {
    const char* v = std::getenv("POWDERBED_FUZZ_READERS");
    return std::string(v ? v : "all");
  }();
  return m;
}
bool text_only() { return mode() == "text"; }

std::string scratch(const char* ext) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir && *dir ? dir : "/tmp") + "/powderbed_fuzz_" + std::to_string(::getpid()) + ext;
}

}  // namespace

// Writes the input after its selector byte to a scratch file with extension `ext`.
std::string scratch_file(const std::uint8_t* data, std::size_t size, const char* ext) {
  const std::string path = scratch(ext);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  std::fwrite(data + 1, 1, size - 1, f);
  std::fclose(f);
  return path;
}

int foreign(const std::uint8_t* data, std::size_t size) {
  static const char* const ext[4] = {".data", ".txt", ".geo", ".dump.gz"};
  const int kind = data[0] % 4;
  const std::string path = scratch_file(data, size, ext[kind]);
  try {
    if (kind == 0) powderbed::bed::read_lammps_data(path);
    if (kind == 1) powderbed::bed::read_yade_text(path);
    if (kind == 2) powderbed::bed::read_gengeo(path);
    if (kind == 3) powderbed::bed::read_lammps_dump_all(path);
  } catch (const powderbed::InputError&) {
    // the promised refusal
  }
  std::remove(path.c_str());
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  if (mode() == "foreign") return foreign(data, size);
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
