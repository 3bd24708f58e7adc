#pragma once
// Helpers shared by the bed readers and writers (io_*.cpp); not part of the public interface.
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "powderbed/bed/bed.hpp"

namespace powderbed::bed::detail {

// A file written atomically (docs/bed-format.md: a crash never leaves half a bed).
// The constructor creates `<path>.tmp.<pid>` (throws InputError naming `path` with the system's
// reason when it cannot); the caller writes temp_path(); commit() renames it over `path`. The
// destructor removes the temporary unless commit() succeeded, so any failure leaves an existing
// file at `path` untouched.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& path() const { return path_; }
  const std::string& temp_path() const { return temp_; }
  // Renames the temporary over `path` (or, while a CommitTogether lives on this thread, hands
  // it to that to rename with the run's other outputs); throws InputError naming `path`.
  void commit();

 private:
  std::string path_;
  std::string temp_;
  bool committed_ = false;
  bool handed_over_ = false;  // to the CommitTogether alive at commit()
};

// Writes `text` to `temp_path` in one go; throws InputError naming `path` on failure.
void write_text(const std::string& temp_path, const std::string& path, std::string_view text);

// The whole file, gunzipped when it is gzip data; throws InputError naming `path` when it is not
// a regular file (require_regular_file), cannot be read, or holds more than `limit_bytes`
// (stored, or once gunzipped: inflating stops at the limit). The one-argument form takes the
// readers' memory guard, text_guard_bytes().
std::string read_text(const std::string& path);
std::string read_text(const std::string& path, double limit_bytes);

// The memory this process may use, in bytes (0 when unknown): the least of the machine's
// memory, its control group's limit and the process's address-space and data limits. The
// readers refuse a declared size that could not fit before allocating it.
double usable_memory_bytes();
// The text readers' guard: a quarter of usable_memory_bytes() (1e12 when it is unknown).
double text_guard_bytes();

// The XDMF sidecar of an HDF5 bed: `<path minus .h5>.xmf`.
std::string xdmf_path(const std::string& h5_path);
// XDMF 3 text describing `bed` as stored in the HDF5 file named `h5_file_name` (no folder, so
// the pair can be moved together).
std::string xdmf_text(const Bed& bed, const std::string& h5_file_name);

// Whole-token number parsing (std::from_chars: locale-free, exact round trip).
inline bool parse_double(std::string_view text, double& value) {
  const char* end = text.data() + text.size();
  const auto res = std::from_chars(text.data(), end, value);
  return res.ec == std::errc() && res.ptr == end;
}
inline bool parse_uint(std::string_view text, std::uint64_t& value) {
  const char* end = text.data() + text.size();
  const auto res = std::from_chars(text.data(), end, value);
  return res.ec == std::errc() && res.ptr == end;
}

// Significant digits printed in a number token ("2.0000999994058125e-05": 17, "2.5e-05": 2,
// "0.0100": 3): the mantissa's digits from the first non-zero one on.
inline int significant_digits(std::string_view token) {
  int digits = 0;
  bool leading = true;
  for (const char c : token) {
    if (c == 'e' || c == 'E') break;
    if (c < '0' || c > '9') continue;
    if (leading && c == '0') continue;
    leading = false;
    ++digits;
  }
  return digits;
}

// 'text' in quotes, for error messages (built by append: GCC 12's -Wrestrict misreads
// "'" + std::string).
inline std::string quoted(std::string_view text) {
  std::string q;
  q.reserve(text.size() + 2);
  q += '\'';
  q.append(text);
  q += '\'';
  return q;
}

// Splits a line at spaces and tabs into `words` (views into `line`).
void split_words(std::string_view line, std::vector<std::string_view>& words);

// Text lines split from a whole file, with their 1-based numbers for error messages.
// Trailing '\r' (CRLF files) is dropped. `first_line` is the number of the text's first line.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text, std::size_t first_line = 1)
      : text_(text), number_(first_line - 1) {}
  // The next line, or false at the end of the text.
  bool next(std::string_view& line);
  std::size_t line_number() const { return number_; }
  std::size_t bytes_left() const { return pos_ >= text_.size() ? 0 : text_.size() - pos_; }

 private:
  std::string_view text_;
  std::size_t number_;
  std::size_t pos_ = 0;
};

}  // namespace powderbed::bed::detail
