#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <fmt/format.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/input_file.hpp"
#include "powderbed/bed/io.hpp"

namespace powderbed::bed::detail {

namespace {

// The two magic bytes of a gzip member (RFC 1952 section 2.3.1).
bool is_gzip(std::string_view bytes) {
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
         static_cast<unsigned char>(bytes[1]) == 0x8b;
}

// The text of a gzipped file (concatenated members too, as gunzip reads them), capped like an
// uncompressed file at `cap` bytes: inflating stops there, so a small damaged or hostile file
// (a few MB of zeros declaring gigabytes) cannot ask for more.
std::string gunzip(const std::string& path, const std::string& bytes, double cap) {
  if (bytes.size() > 0xffffffffu)
    throw InputError(path + ": gzip file above 4 GB (accepted: smaller; gunzip it first)");
  z_stream z{};
  if (inflateInit2(&z, 15 + 32) != Z_OK) throw InputError(path + ": zlib cannot start");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  z.avail_in = static_cast<uInt>(bytes.size());
  std::string out;
  char chunk[1 << 16];
  int rc = Z_OK;
  while (true) {
    z.next_out = reinterpret_cast<Bytef*>(chunk);
    z.avail_out = sizeof chunk;
    rc = inflate(&z, Z_NO_FLUSH);
    out.append(chunk, sizeof chunk - z.avail_out);
    if (static_cast<double>(out.size()) > cap) {
      inflateEnd(&z);
      throw InputError(fmt::format("{}: more than {:.0f} bytes once gunzipped, the reader's "
                                   "memory guard (accepted: smaller files, up to a quarter of "
                                   "the memory this process may use; convert it on a larger "
                                   "machine)", path, cap));
    }
    const std::string_view rest(reinterpret_cast<const char*>(z.next_in), z.avail_in);
    if (rc == Z_STREAM_END && is_gzip(rest)) {
      inflateReset(&z);  // a further gzip member
      continue;
    }
    if (rc != Z_OK) break;
  }
  inflateEnd(&z);
  if (rc != Z_STREAM_END) {
    throw InputError(path + ": damaged gzip data (" + (z.msg ? std::string(z.msg) : "truncated") +
                     "; accepted: a whole .gz file)");
  }
  return out;
}

}  // namespace

// The smallest of the machine's memory, the control group's limit (a container's) and the
// process's address-space and data limits (ulimit -v, -d): a guard on the machine's memory
// alone lets a reader in a 4 GB container allocate its way to bad_alloc.
double usable_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page = ::sysconf(_SC_PAGE_SIZE);
  double memory = pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
  const auto lower = [&](double limit) {
    if (limit > 0 && (memory == 0 || limit < memory)) memory = limit;
  };
  for (const char* file : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(file);
    double limit = 0;
    if (in >> limit) lower(limit);  // "max" (no limit) does not parse: left alone
  }
  for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    struct rlimit r {};
    if (::getrlimit(resource, &r) == 0 && r.rlim_cur != RLIM_INFINITY)
      lower(static_cast<double>(r.rlim_cur));
  }
  return memory;
}

double text_guard_bytes() {
  const double memory = usable_memory_bytes();
  return memory > 0 ? 0.25 * memory : 1e12;
}

std::string read_text(const std::string& path) { return read_text(path, text_guard_bytes()); }

std::string read_text(const std::string& path, double limit_bytes) {
  require_regular_file(path, "bed file");
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && static_cast<double>(st.st_size) > limit_bytes) {
    throw InputError(fmt::format("{}: {} bytes, too large to read into memory (accepted: up to "
                                 "{:.0f} bytes, a quarter of the memory this process may use; "
                                 "convert it to .h5 on a larger machine)",
                                 path, st.st_size, limit_bytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open: " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": read error");
  std::string bytes = std::move(text).str();
  if (is_gzip(bytes)) return gunzip(path, bytes, limit_bytes);
  return bytes;
}

void split_words(std::string_view line, std::vector<std::string_view>& words) {
  words.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
}

bool LineCursor::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const auto end = text_.find('\n', pos_);
  const auto stop = end == std::string_view::npos ? text_.size() : end;
  line = text_.substr(pos_, stop - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = stop + 1;
  ++number_;
  return true;
}

}  // namespace powderbed::bed::detail

namespace powderbed::bed {

std::string extension_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string readable_extension_of(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext != ".gz") return ext;
  return extension_of(path.substr(0, path.size() - 3));
}

}  // namespace powderbed::bed
