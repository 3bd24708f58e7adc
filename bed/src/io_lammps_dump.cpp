// LAMMPS/LIGGGHTS text dump import (docs/bed-format.md): the last snapshot becomes a bed,
// its box bounds the domain (pp -> periodic). Lines starting with '#' are skipped as comments.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>
#include <vector>

#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"

namespace powderbed::bed {

namespace {

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

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

// Byte offset and line number of the last line that begins with "ITEM: TIMESTEP".
std::optional<std::pair<std::size_t, std::size_t>> last_snapshot(std::string_view text) {
  constexpr std::string_view key = "ITEM: TIMESTEP";
  std::size_t pos = text.rfind(key);
  while (pos != std::string_view::npos && pos > 0 && text[pos - 1] != '\n')
    pos = text.rfind(key, pos - 1);
  if (pos == std::string_view::npos) return std::nullopt;
  const auto line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + pos, '\n'));
  return std::make_pair(pos, line);
}

// Column indices of one ITEM: ATOMS header.
struct Columns {
  int id = -1;
  std::array<int, 3> position{-1, -1, -1};
  std::array<bool, 3> scaled{false, false, false};
  std::array<int, 3> velocity{-1, -1, -1};
  int size = -1;  // radius or diameter
  bool diameter = false;
};

class DumpReader {
 public:
  DumpReader(std::string path, std::string_view text, std::size_t first_line)
      : path_(std::move(path)), lines_(text, first_line) {}

  Bed read() {
    std::optional<std::uint64_t> count;
    bool have_box = false;
    std::string_view line;
    while (next(line)) {
      if (starts_with(line, "ITEM: TIMESTEP")) {
        number_line("timestep");
      } else if (starts_with(line, "ITEM: NUMBER OF ATOMS")) {
        count = number_line("number of atoms");
      } else if (starts_with(line, "ITEM: BOX BOUNDS")) {
        box(line);
        have_box = true;
      } else if (starts_with(line, "ITEM: ATOMS")) {
        if (!count) fail("ITEM: ATOMS before ITEM: NUMBER OF ATOMS");
        if (!have_box) fail("ITEM: ATOMS before ITEM: BOX BOUNDS");
        atoms(line, *count);
        if (next(line)) fail("unexpected line after the " + std::to_string(*count) + " atoms");
        bed_.validate(path_);
        bed_.validate_geometry(path_);  // inside the box bounds, radii plausible for them
        return std::move(bed_);
      } else if (starts_with(line, "ITEM:")) {
        skip_section();  // e.g. ITEM: UNITS, ITEM: TIME
      } else {
        fail("found '" + std::string(line) + "' where an ITEM: line belongs");
      }
    }
    fail("the last snapshot has no ITEM: ATOMS section (truncated dump?)");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path_ + ":" + std::to_string(lines_.line_number()) + ": " + what);
  }

  // Next line that is neither blank nor a comment; a pushed-back line comes first.
  bool next(std::string_view& line) {
    if (pushed_) {
      line = *pushed_;
      pushed_.reset();
      return true;
    }
    while (lines_.next(line)) {
      const auto start = line.find_first_not_of(" \t");
      if (start != std::string_view::npos && line[start] != '#') return true;
    }
    return false;
  }

  std::uint64_t number_line(const char* what) {
    std::string_view line;
    if (!next(line)) fail(std::string("dump ends before the ") + what);
    split_words(line, words_);
    std::uint64_t value = 0;
    if (words_.size() != 1 || !detail::parse_uint(words_[0], value))
      fail(std::string(what) + " is '" + std::string(line) + "' (accepted: a whole number)");
    return value;
  }

  void skip_section() {
    std::string_view line;
    while (next(line)) {
      if (starts_with(line, "ITEM:")) {
        pushed_ = line;
        return;
      }
    }
  }

  void box(std::string_view header) {
    split_words(header, words_);  // ITEM: BOX BOUNDS [xy xz yz] [flags x3]
    const std::vector<std::string_view> flags(words_.begin() + 3, words_.end());
    if (!flags.empty() && flags[0] == "xy") fail("triclinic box (accepted: orthogonal boxes)");
    if (!flags.empty() && flags.size() != 3)
      fail("box bounds have " + std::to_string(flags.size()) + " boundary flags (accepted: 3)");
    Domain& d = bed_.domain;
    d.dimension = 3;
    for (int a = 0; a < 3; ++a) {
      std::string_view line;
      if (!next(line)) fail("dump ends inside ITEM: BOX BOUNDS");
      split_words(line, words_);
      if (words_.size() != 2 || !detail::parse_double(words_[0], d.lower[a]) ||
          !detail::parse_double(words_[1], d.upper[a]))
        fail("box bounds '" + std::string(line) + "' (accepted: two numbers, lo hi)");
      d.periodic[a] = !flags.empty() && flags[a] == "pp";
    }
    d.validate((path_ + ":" + std::to_string(lines_.line_number()) + ": box bounds").c_str());
  }

  Columns columns(const std::vector<std::string_view>& names) const {
    Columns c;
    static constexpr std::array<std::string_view, 3> axis = {"x", "y", "z"};
    static constexpr std::array<std::string_view, 3> scaled = {"xs", "ys", "zs"};
    static constexpr std::array<std::string_view, 3> unwrapped = {"xu", "yu", "zu"};
    static constexpr std::array<std::string_view, 3> velocity = {"vx", "vy", "vz"};
    for (int k = 0; k < static_cast<int>(names.size()); ++k) {
      const auto name = names[k];
      if (name == "id") c.id = k;
      if (name == "radius" || name == "diameter") {
        c.size = k;
        c.diameter = name == "diameter";
      }
      for (int a = 0; a < 3; ++a) {
        if (name == axis[a] || name == unwrapped[a]) c.position[a] = k;
        if (name == scaled[a]) {
          c.position[a] = k;
          c.scaled[a] = true;
        }
        if (name == velocity[a]) c.velocity[a] = k;
      }
    }
    const bool has_position = std::all_of(c.position.begin(), c.position.end(),
                                          [](int k) { return k >= 0; });
    if (c.id < 0 || c.size < 0 || !has_position) {
      fail("ITEM: ATOMS columns lack id, x|xs|xu, y|ys|yu, z|zs|zu or radius|diameter");
    }
    return c;
  }

  void atoms(std::string_view header, std::uint64_t count) {
    split_words(header, words_);
    const std::vector<std::string_view> names(words_.begin() + 2, words_.end());
    const Columns c = columns(names);
    const bool velocity = std::all_of(c.velocity.begin(), c.velocity.end(),
                                      [](int k) { return k >= 0; });
    std::string column_list;
    for (auto n : names) {
      if (!column_list.empty()) column_list += ' ';
      column_list.append(n);
    }
    const Domain& d = bed_.domain;
    // A declared count is checked against the text left before anything is allocated: each
    // atom line holds at least one character per column and a separator (a damaged or hostile
    // dump can declare 2e9 atoms in a few bytes).
    const std::uint64_t min_line = 2 * names.size();
    const std::uint64_t left = lines_.bytes_left();
    if (count > left / min_line + 1) {
      fail("NUMBER OF ATOMS is " + std::to_string(count) + " but " + std::to_string(left) +
           " bytes follow (accepted: one line of " + std::to_string(names.size()) +
           " columns per atom; truncated dump?)");
    }
    bed_.reserve(count);
    for (std::uint64_t i = 0; i < count; ++i) {
      std::string_view line;
      if (!next(line) || starts_with(line, "ITEM:"))
        fail("snapshot ends after " + std::to_string(i) + " of " + std::to_string(count) + " atoms");
      split_words(line, words_);
      if (words_.size() != names.size()) {
        fail(std::to_string(words_.size()) + " columns, expected " +
             std::to_string(names.size()) + " (" + column_list + ")");
      }
      auto number = [&](int k) {
        double v = 0;
        if (!detail::parse_double(words_[k], v)) {
          fail("column " + std::string(names[k]) + " is '" + std::string(words_[k]) +
               "' (accepted: a number)");
        }
        return v;
      };
      std::uint64_t id = 0;
      if (!detail::parse_uint(words_[c.id], id) || id == 0)
        fail("id is '" + std::string(words_[c.id]) + "' (accepted: LAMMPS ids >= 1)");
      std::array<double, 3> p{};
      for (int a = 0; a < 3; ++a) {
        p[a] = number(c.position[a]);
        if (c.scaled[a]) p[a] = d.lower[a] + p[a] * d.length(a);
      }
      const double size = number(c.size);
      bed_.x.push_back(p[0]);
      bed_.y.push_back(p[1]);
      bed_.z.push_back(p[2]);
      bed_.radius.push_back(c.diameter ? 0.5 * size : size);
      bed_.id.push_back(id - 1);  // inverse of write_lammps_data's id + 1
      if (velocity) {
        bed_.vx.push_back(number(c.velocity[0]));
        bed_.vy.push_back(number(c.velocity[1]));
        bed_.vz.push_back(number(c.velocity[2]));
      }
    }
  }

  std::string path_;
  detail::LineCursor lines_;
  std::optional<std::string_view> pushed_;
  std::vector<std::string_view> words_;
  Bed bed_;
};

}  // namespace

Bed read_lammps_dump(const std::string& path) {
  const std::string text = detail::read_text(path);
  const auto start = last_snapshot(text);
  if (!start) throw InputError(path + ": no 'ITEM: TIMESTEP' line (accepted: a LAMMPS text dump)");
  return DumpReader(path, std::string_view(text).substr(start->first), start->second).read();
}

}  // namespace powderbed::bed
