#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

#include "io_detail.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/errors.hpp"

namespace powderbed::bed::detail {

double physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

std::string read_text(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw InputError(path + ": is a folder (accepted: a bed file)");
    const double memory = physical_memory_bytes();
    if (memory > 0 && static_cast<double>(st.st_size) > 0.25 * memory) {
      throw InputError(path + ": " + std::to_string(st.st_size) +
                       " bytes, too large to read into memory (accepted: up to a quarter of this "
                       "machine's memory; convert it to .h5 on a larger machine)");
    }
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open: " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": read error");
  return std::move(text).str();
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

}  // namespace powderbed::bed
