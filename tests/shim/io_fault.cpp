// An LD_PRELOAD'd fault injector for the full-disk and rename-window tests
// (tests/apps/test_full_disk.cpp, docs/hardening.md "Full disk and the rename window"). A tmpfs
// mount needs privileges CI does not have; this needs none and fails at a chosen byte.
//
//   POWDERBED_FAULT_PATH   fnmatch pattern ('*' also matches '/') of the files that fill up,
//                          matched against the path of the descriptor written to
//   POWDERBED_FAULT_BYTES  bytes those files may take in all, summed over every write of the
//                          process; the write that crosses it is cut short, the next one fails
//                          with ENOSPC, like a disk that fills (write, pwrite, writev, pwritev,
//                          fallocate, posix_fallocate)
//   POWDERBED_FAULT_STOP_RENAME  fnmatch pattern of rename() targets; the process stops itself
//                          (SIGSTOP) just before the POWDERBED_FAULT_STOP_AT-th (default 1)
//                          matching rename, so a test can kill it exactly in the rename window
//   POWDERBED_FAULT_LOG    a file that gets one line "rename NEW" per matching rename
//   POWDERBED_FAULT_CLOCK  set: every clock reads the same instant (time, clock_gettime,
//                          gettimeofday), so two runs write the same bytes (HDF5 stores
//                          objects' modification times; the programs their wall times)
//
// Nothing else changes: unmatched files and every other call go straight to the C library.
#include <dlfcn.h>
#include <fcntl.h>
#include <fnmatch.h>
#include <signal.h>
#include <sys/time.h>
#include <sys/types.h>
#include <time.h>
#include <sys/uio.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

std::atomic<long long> g_left{-1};  // bytes the matching files may still take; -1: no limit
const char* g_path = nullptr;
const char* g_stop_rename = nullptr;
const char* g_log = nullptr;
long g_stop_at = 1;
bool g_frozen = false;
constexpr time_t kInstant = 1000000000;  // 2001-09-09, any fixed second will do
std::atomic<long> g_renames{0};

__attribute__((constructor)) void read_environment() {
  g_path = std::getenv("POWDERBED_FAULT_PATH");
  if (const char* b = std::getenv("POWDERBED_FAULT_BYTES")) g_left = std::atoll(b);
  g_stop_rename = std::getenv("POWDERBED_FAULT_STOP_RENAME");
  if (const char* k = std::getenv("POWDERBED_FAULT_STOP_AT")) g_stop_at = std::atol(k);
  g_log = std::getenv("POWDERBED_FAULT_LOG");
  g_frozen = std::getenv("POWDERBED_FAULT_CLOCK") != nullptr;
}

template <class F>
F next(const char* name) {
  return reinterpret_cast<F>(::dlsym(RTLD_NEXT, name));
}

bool fills(int fd) {
  if (!g_path || g_left.load() < 0) return false;
  char link[64], target[4096];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = ::readlink(link, target, sizeof target - 1);
  if (n <= 0) return false;
  target[n] = '\0';
  return ::fnmatch(g_path, target, 0) == 0;
}

// How many of `want` bytes the disk still takes (0: none, the caller fails with ENOSPC).
size_t take(size_t want) {
  long long left = g_left.load();
  long long give = 0;
  do {
    give = left < static_cast<long long>(want) ? left : static_cast<long long>(want);
  } while (!g_left.compare_exchange_weak(left, left - give));
  return static_cast<size_t>(give);
}

ssize_t no_space() {
  errno = ENOSPC;
  return -1;
}

// The first `bytes` of `iov` as `out` (at most `cnt` entries); returns the count used.
int cut(const struct iovec* iov, int cnt, size_t bytes, struct iovec* out) {
  int used = 0;
  for (int i = 0; i < cnt && bytes > 0; ++i, ++used) {
    out[i] = iov[i];
    if (out[i].iov_len > bytes) out[i].iov_len = bytes;
    bytes -= out[i].iov_len;
  }
  return used;
}

size_t total(const struct iovec* iov, int cnt) {
  size_t sum = 0;
  for (int i = 0; i < cnt; ++i) sum += iov[i].iov_len;
  return sum;
}

}  // namespace

// writev, pwritev and pwritev64 alike: the buffers up to the disk's remaining room reach the real
// call (`real(fd, iov, cnt, at...)`), the rest fails with ENOSPC.
template <class Real, class... At>
ssize_t vector_write(Real real, int fd, const struct iovec* iov, int cnt, At... at) {
  const size_t n = total(iov, cnt);
  if (n == 0 || cnt > IOV_MAX || !fills(fd)) return real(fd, iov, cnt, at...);
  const size_t ok = take(n);
  if (ok == 0) return no_space();
  struct iovec part[IOV_MAX];
  return real(fd, part, cut(iov, cnt, ok, part), at...);
}

extern "C" {

ssize_t write(int fd, const void* buf, size_t n) {
  static auto real = next<ssize_t (*)(int, const void*, size_t)>("write");
  if (n == 0 || !fills(fd)) return real(fd, buf, n);
  const size_t ok = take(n);
  return ok == 0 ? no_space() : real(fd, buf, ok);
}

ssize_t pwrite(int fd, const void* buf, size_t n, off_t at) {
  static auto real = next<ssize_t (*)(int, const void*, size_t, off_t)>("pwrite");
  if (n == 0 || !fills(fd)) return real(fd, buf, n, at);
  const size_t ok = take(n);
  return ok == 0 ? no_space() : real(fd, buf, ok, at);
}

ssize_t pwrite64(int fd, const void* buf, size_t n, off64_t at) {
  static auto real = next<ssize_t (*)(int, const void*, size_t, off64_t)>("pwrite64");
  if (n == 0 || !fills(fd)) return real(fd, buf, n, at);
  const size_t ok = take(n);
  return ok == 0 ? no_space() : real(fd, buf, ok, at);
}

ssize_t writev(int fd, const struct iovec* iov, int cnt) {
  static auto real = next<ssize_t (*)(int, const struct iovec*, int)>("writev");
  return vector_write(real, fd, iov, cnt);
}

ssize_t pwritev(int fd, const struct iovec* iov, int cnt, off_t at) {
  static auto real = next<ssize_t (*)(int, const struct iovec*, int, off_t)>("pwritev");
  return vector_write(real, fd, iov, cnt, at);
}

ssize_t pwritev64(int fd, const struct iovec* iov, int cnt, off64_t at) {
  static auto real = next<ssize_t (*)(int, const struct iovec*, int, off64_t)>("pwritev64");
  return vector_write(real, fd, iov, cnt, at);
}

int fallocate(int fd, int mode, off_t at, off_t len) {
  static auto real = next<int (*)(int, int, off_t, off_t)>("fallocate");
  if (len <= 0 || !fills(fd)) return real(fd, mode, at, len);
  if (take(static_cast<size_t>(len)) < static_cast<size_t>(len)) return static_cast<int>(no_space());
  return real(fd, mode, at, len);
}

int fallocate64(int fd, int mode, off64_t at, off64_t len) {
  static auto real = next<int (*)(int, int, off64_t, off64_t)>("fallocate64");
  if (len <= 0 || !fills(fd)) return real(fd, mode, at, len);
  if (take(static_cast<size_t>(len)) < static_cast<size_t>(len)) return static_cast<int>(no_space());
  return real(fd, mode, at, len);
}

// posix_fallocate reports its error as the return value, not through errno.
int posix_fallocate(int fd, off_t at, off_t len) {
  static auto real = next<int (*)(int, off_t, off_t)>("posix_fallocate");
  if (len <= 0 || !fills(fd)) return real(fd, at, len);
  if (take(static_cast<size_t>(len)) < static_cast<size_t>(len)) return ENOSPC;
  return real(fd, at, len);
}

int posix_fallocate64(int fd, off64_t at, off64_t len) {
  static auto real = next<int (*)(int, off64_t, off64_t)>("posix_fallocate64");
  if (len <= 0 || !fills(fd)) return real(fd, at, len);
  if (take(static_cast<size_t>(len)) < static_cast<size_t>(len)) return ENOSPC;
  return real(fd, at, len);
}

time_t time(time_t* out) {
  static auto real = next<time_t (*)(time_t*)>("time");
  if (!g_frozen) return real(out);
  if (out) *out = kInstant;
  return kInstant;
}

int clock_gettime(clockid_t clock, struct timespec* ts) {
  static auto real = next<int (*)(clockid_t, struct timespec*)>("clock_gettime");
  if (!g_frozen) return real(clock, ts);
  ts->tv_sec = kInstant;
  ts->tv_nsec = 0;
  return 0;
}

int gettimeofday(struct timeval* tv, void* tz) {
  static auto real = next<int (*)(struct timeval*, void*)>("gettimeofday");
  if (!g_frozen) return real(tv, tz);
  tv->tv_sec = kInstant;
  tv->tv_usec = 0;
  return 0;
}

int rename(const char* from, const char* to) {
  static auto real = next<int (*)(const char*, const char*)>("rename");
  if (g_stop_rename && ::fnmatch(g_stop_rename, to, 0) == 0) {
    if (g_log) {
      static auto real_write = next<ssize_t (*)(int, const void*, size_t)>("write");
      const int fd = ::open(g_log, O_WRONLY | O_APPEND | O_CREAT, 0644);
      if (fd >= 0) {
        char line[4200];
        const int len = std::snprintf(line, sizeof line, "rename %s\n", to);
        if (len > 0) real_write(fd, line, static_cast<size_t>(len));
        ::close(fd);
      }
    }
    if (++g_renames == g_stop_at) ::raise(SIGSTOP);  // the test kills or continues us here
  }
  return real(from, to);
}

}  // extern "C"
