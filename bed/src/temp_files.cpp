// Registry of this process's temporary files, emptied by SIGINT/SIGTERM (temp_files.hpp).
#include "powderbed/bed/temp_files.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <cstdio>
#include <cstring>
#include <mutex>

namespace powderbed::bed {

namespace {

constexpr int kSlots = 64;
constexpr std::size_t kPathMax = 4096;

struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being written, 2 holds a path
  char path[kPathMax];
};

Slot g_slots[kSlots];
std::once_flag g_install_once;

extern "C" void remove_and_die(int sig) {
  for (Slot& s : g_slots) {
    if (s.state.load(std::memory_order_acquire) == 2) ::unlink(s.path);  // async-signal-safe
  }
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void install_handlers() {
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) != 0) continue;
    // Leave a handler of the program's own (or an ignored signal, e.g. under nohup) alone.
    if (old.sa_handler != SIG_DFL) continue;
    struct sigaction act {};
    act.sa_handler = remove_and_die;
    sigemptyset(&act.sa_mask);
    act.sa_flags = SA_RESETHAND;
    ::sigaction(sig, &act, nullptr);
  }
}

}  // namespace

std::string temp_path_for(const std::string& path) {
  return path + ".tmp." + std::to_string(::getpid());
}

void register_temp_file(const std::string& temp) {
  std::call_once(g_install_once, install_handlers);
  if (temp.size() >= kPathMax) return;
  for (Slot& s : g_slots) {
    int expected = 0;
    if (s.state.compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) {
      std::memcpy(s.path, temp.c_str(), temp.size() + 1);
      s.state.store(2, std::memory_order_release);
      return;
    }
  }
}

void unregister_temp_file(const std::string& temp) {
  for (Slot& s : g_slots) {
    int expected = 2;
    if (s.state.load(std::memory_order_acquire) == 2 && temp == s.path &&
        s.state.compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) {
      s.state.store(0, std::memory_order_release);
      return;
    }
  }
}

namespace {

// Removes the files of `folder` named `<prefix...>.tmp.<pid>` whose process no longer exists on
// this machine (`prefix` empty: any such name); returns how many.
int remove_stale_in(const std::filesystem::path& folder, const std::string& prefix) {
  namespace fs = std::filesystem;
  int removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const auto tmp = name.rfind(".tmp.");
    if (tmp == std::string::npos || name.compare(0, prefix.size(), prefix) != 0) continue;
    if (!prefix.empty() && tmp + 5 != prefix.size()) continue;  // another file's temporary
    const std::string digits = name.substr(tmp + 5);
    if (digits.empty() || digits.size() > 9 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      continue;
    const long pid = std::stol(digits);
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // alive or not ours
    std::error_code rm;
    if (fs::remove(it->path(), rm)) ++removed;
  }
  return removed;
}

}  // namespace

int remove_stale_temp_files(const std::string& path) {
  const std::filesystem::path p(path);
  return remove_stale_in(p.has_parent_path() ? p.parent_path() : std::filesystem::path("."),
                         p.filename().string() + ".tmp.");
}

int remove_stale_temp_files_in(const std::string& folder) { return remove_stale_in(folder, ""); }

void remove_temp_files() {
  for (Slot& s : g_slots) {
    if (s.state.load(std::memory_order_acquire) == 2) ::unlink(s.path);
  }
}

TempFile::TempFile(std::string temp) : path_(std::move(temp)) { register_temp_file(path_); }

TempFile::~TempFile() {
  if (!released_) std::remove(path_.c_str());
  unregister_temp_file(path_);
}

void TempFile::release() {
  released_ = true;
  unregister_temp_file(path_);
}

}  // namespace powderbed::bed
