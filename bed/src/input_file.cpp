#include "powderbed/bed/input_file.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include "powderbed/bed/errors.hpp"

namespace powderbed::bed {

namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "folder";
  if (S_ISFIFO(mode)) return "FIFO (named pipe)";
  if (S_ISCHR(mode)) return "character device";
  if (S_ISBLK(mode)) return "block device";
  if (S_ISSOCK(mode)) return "socket";
  return "special file";
}

// The length of the well-formed UTF-8 sequence of a printable character (U+00A0 on) at text[i],
// or 0: such characters (um, degree signs in a source field) are kept, every other byte escaped.
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto lead = static_cast<unsigned char>(text[i]);
  const std::size_t n = lead >= 0xc2 && lead <= 0xdf ? 2 : lead >= 0xe0 && lead <= 0xef ? 3
                      : lead >= 0xf0 && lead <= 0xf4 ? 4 : 0;
  if (n == 0 || i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(text[i + k]) & 0xc0) != 0x80) return 0;
  if (lead == 0xc2 && static_cast<unsigned char>(text[i + 1]) < 0xa0) return 0;  // C1 controls
  return n;
}

}  // namespace

void require_regular_file(const std::string& path, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return;
  throw InputError(fmt::format("{}: '{}' is a {}, not a file (accepted: a regular file)", what,
                               path, kind_of(st.st_mode)));
}

std::string quoted_excerpt(std::string_view text, std::size_t max_chars) {
  std::string out = "'";
  std::size_t shown = 0;
  for (std::size_t i = 0; i < text.size(); ++shown) {
    if (shown == max_chars) {
      out += "...";
      break;
    }
    const auto byte = static_cast<unsigned char>(text[i]);
    const std::size_t n = utf8_length(text, i);
    if (byte >= 0x20 && byte < 0x7f) out += text[i];
    else if (n > 0) out.append(text.substr(i, n));
    else out += fmt::format("\\x{:02x}", byte);
    i += n > 0 ? n : 1;
  }
  out += '\'';
  return out;
}

}  // namespace powderbed::bed
