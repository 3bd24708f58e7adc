#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

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
  if (handed_over_) return;  // the CommitTogether renames or removes it, and unregisters it
  if (!committed_) std::remove(temp_.c_str());
  unregister_temp_file(temp_);
}

void AtomicFile::commit() {
  if (CommitTogether* together = CommitTogether::active()) {
    together->add(temp_, path_);  // renamed (or removed) with the run's other outputs
    handed_over_ = true;
    return;
  }
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
  // POSIX calls rather than a stream: every short write and the close (where some file systems
  // report a full disk) is checked, and the message carries the system's reason.
  const auto fail = [&](int err) {
    throw InputError(path + ": cannot write '" + temp_path + "': " + std::strerror(err));
  };
  const int fd = ::open(temp_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) fail(errno);
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : EIO;
      ::close(fd);
      fail(err);
    }
    text.remove_prefix(static_cast<std::size_t>(n));
  }
  if (::close(fd) != 0) fail(errno);
}

}  // namespace powderbed::bed::detail

namespace powderbed::bed {

namespace {
thread_local CommitTogether* g_together = nullptr;
}  // namespace

CommitTogether::CommitTogether() : outer_(g_together) { g_together = this; }

CommitTogether::~CommitTogether() {
  g_together = outer_;
  for (const auto& [temp, path] : waiting_) {
    std::remove(temp.c_str());
    unregister_temp_file(temp);
  }
}

CommitTogether* CommitTogether::active() { return g_together; }

void CommitTogether::add(std::string temp, std::string path) {
  // A file written again while it waits (deposit's --log, rewritten at every thermo row) has
  // the same temporary, now holding its latest text: it waits once.
  for (const auto& [waiting, ignored] : waiting_)
    if (waiting == temp) return;
  waiting_.emplace_back(std::move(temp), std::move(path));
}

void CommitTogether::commit() {
  g_together = outer_;  // nothing more joins
  while (!waiting_.empty()) {
    const auto [temp, path] = waiting_.front();
    if (std::rename(temp.c_str(), path.c_str()) != 0)
      throw InputError(path + ": cannot replace with '" + temp + "': " + std::strerror(errno));
    unregister_temp_file(temp);
    waiting_.erase(waiting_.begin());
  }
}

}  // namespace powderbed::bed
