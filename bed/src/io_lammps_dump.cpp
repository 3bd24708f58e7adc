// LAMMPS/LIGGGHTS text dump import (docs/decks.md): each snapshot becomes a bed, its box
// bounds the domain (pp -> periodic). Lines starting with '#' are skipped as comments.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <sstream>
#include <vector>

#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"

namespace powderbed::bed {

namespace {

using detail::split_words;

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
  int type = -1;
};

class DumpReader {
 public:
  DumpReader(std::string path, std::string_view text, std::size_t first_line)
      : path_(std::move(path)), lines_(text, first_line) {}

  // The next snapshot: ITEM sections (TIME, TIMESTEP, NUMBER OF ATOMS, BOX BOUNDS, others
  // skipped) up to ITEM: ATOMS and its atoms; nothing when only blank or comment lines are
  // left.
  std::optional<DumpSnapshot> next_snapshot() {
    std::optional<std::uint64_t> count;
    bool have_box = false, have_step = false;
    DumpSnapshot snap;
    bed_ = Bed{};
    std::string_view line;
    while (next(line)) {
      if (starts_with(line, "ITEM: TIMESTEP")) {
        snap.step = number_line("timestep");
        have_step = true;
      } else if (starts_with(line, "ITEM: TIME")) {
        snap.time = real_line("time");
      } else if (starts_with(line, "ITEM: NUMBER OF ATOMS")) {
        count = number_line("number of atoms");
      } else if (starts_with(line, "ITEM: BOX BOUNDS")) {
        box(line);
        have_box = true;
      } else if (starts_with(line, "ITEM: ATOMS")) {
        if (!have_step) fail("ITEM: ATOMS before ITEM: TIMESTEP");
        if (!count) fail("ITEM: ATOMS before ITEM: NUMBER OF ATOMS");
        if (!have_box) fail("ITEM: ATOMS before ITEM: BOX BOUNDS");
        atoms(line, *count);
        if (next(line)) {
          if (!starts_with(line, "ITEM:"))
            fail("unexpected line after the " + std::to_string(*count) + " atoms");
          pushed_ = line;
        }
        bed_.validate(path_);
        bed_.validate_geometry(path_);  // inside the box bounds, radii plausible for them
        snap.bed = std::move(bed_);
        return snap;
      } else if (starts_with(line, "ITEM:")) {
        skip_section();  // e.g. ITEM: UNITS
      } else {
        fail("found '" + std::string(line) + "' where an ITEM: line belongs");
      }
    }
    if (have_step || count || have_box)
      fail("the last snapshot has no ITEM: ATOMS section (truncated dump?)");
    return std::nullopt;
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

  double real_line(const char* what) {
    std::string_view line;
    if (!next(line)) fail(std::string("dump ends before the ") + what);
    split_words(line, words_);
    double value = 0;
    if (words_.size() != 1 || !detail::parse_double(words_[0], value) || !std::isfinite(value))
      fail(std::string(what) + " is '" + std::string(line) + "' (accepted: a number)");
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
      if (name == "type") c.type = k;
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
      fail(fmt::format(
          "NUMBER OF ATOMS is {} but {} bytes follow (accepted: one line of {} columns per atom; "
          "truncated dump?)",
          count, left, names.size()));
    }
    bed_.reserve(count);
    std::vector<std::uint16_t> types;
    int digits = 0;
    for (std::uint64_t i = 0; i < count; ++i) {
      std::string_view line;
      if (!next(line) || starts_with(line, "ITEM:"))
        fail(fmt::format("snapshot ends after {} of {} atoms", i, count));
      split_words(line, words_);
      if (words_.size() != names.size()) {
        fail(fmt::format("{} columns, expected {} ({})", words_.size(), names.size(),
                         column_list));
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
        digits = std::max(digits, detail::significant_digits(words_[c.position[a]]));
      }
      const double size = number(c.size);
      digits = std::max(digits, detail::significant_digits(words_[c.size]));
      if (c.type >= 0) {
        std::uint64_t type = 0;
        if (!detail::parse_uint(words_[c.type], type) || type == 0 || type > 65536)
          fail("type is '" + std::string(words_[c.type]) + "' (accepted: 1 to 65536)");
        types.push_back(static_cast<std::uint16_t>(type - 1));
      }
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
    // One type is one material: no material array (as a bed without materials writes).
    if (std::any_of(types.begin(), types.end(), [](std::uint16_t t) { return t != 0; }))
      bed_.material = std::move(types);
    bed_.provenance.printed_digits = digits;
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
  DumpReader reader(path, std::string_view(text).substr(start->first), start->second);
  return std::move(reader.next_snapshot()->bed);
}

std::vector<DumpSnapshot> read_lammps_dump_all(const std::string& path) {
  const std::string text = detail::read_text(path);
  if (!last_snapshot(text))
    throw InputError(path + ": no 'ITEM: TIMESTEP' line (accepted: a LAMMPS text dump)");
  DumpReader reader(path, text, 1);
  std::vector<DumpSnapshot> snapshots;
  while (auto snap = reader.next_snapshot()) snapshots.push_back(std::move(*snap));
  return snapshots;
}

}  // namespace powderbed::bed
