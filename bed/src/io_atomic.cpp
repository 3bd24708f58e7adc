#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/temp_files.hpp"

namespace powderbed::bed::detail {

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), temp_(temp_path_for(path_)) {
  remove_stale_temp_files(path_);  // left by a run of this path that was SIGKILLed
  // Registered before it exists, so a SIGINT/SIGTERM from here on removes it (temp_files.hpp).
  register_temp_file(temp_);
  // Create the temporary now, so an unwritable folder is reported with the system's reason.
  std::FILE* f = std::fopen(temp_.c_str(), "wb");
  if (!f) {
    const int err = errno;
    unregister_temp_file(temp_);
    errno = err;
    throw InputError(path_ + ": cannot create temporary file '" + temp_ + "': " +
                     std::strerror(errno));
  }
  std::fclose(f);
}

AtomicFile::~AtomicFile() {
  if (!committed_) std::remove(temp_.c_str());
  unregister_temp_file(temp_);
}

void AtomicFile::commit() {
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    std::remove(temp_.c_str());
    unregister_temp_file(temp_);
    committed_ = true;  // nothing left to remove
    throw InputError(path_ + ": cannot replace with '" + temp_ + "': " + std::strerror(err));
  }
  committed_ = true;
  unregister_temp_file(temp_);
}

void write_text(const std::string& temp_path, const std::string& path, std::string_view text) {
  std::ofstream out(temp_path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw InputError(path + ": cannot write '" + temp_path + "' (disk full?)");
}

}  // namespace powderbed::bed::detail
