// LAMMPS data file import, atom_style sphere (docs/decks.md): ours (write_lammps_data) and what
// LAMMPS's write_data writes. A data file is a title line, a header (counts, box), then
// sections, each a keyword line followed by its numeric lines.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <unordered_map>

#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"

namespace powderbed::bed {

namespace {

using detail::split_words;

// Text before a '#' (LAMMPS data files allow comments at the end of any line).
std::string_view strip_comment(std::string_view line) {
  const auto hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

bool is_number(std::string_view word) {
  double v = 0;
  return detail::parse_double(word, v);
}

class DataReader {
 public:
  DataReader(std::string path, std::string_view text) : path_(std::move(path)), lines_(text) {}

  Bed read() {
    std::string_view line;
    if (!lines_.next(line)) fail("empty file (accepted: a LAMMPS data file)");
    header();
    while (section_) body();
    if (!atoms_) fail("no Atoms section (accepted: a LAMMPS data file with atoms)");
    if (bed_.n() != *count_)
      fail(fmt::format("Atoms has {} of the {} atoms declared (truncated file?)", bed_.n(),
                       *count_));
    if (have_velocities_ != 0 && have_velocities_ != bed_.n())
      fail(fmt::format("Velocities for {} of {} atoms", have_velocities_, bed_.n()));
    if (std::any_of(type_.begin(), type_.end(), [](std::uint16_t t) { return t != 0; }))
      bed_.material = std::move(type_);
    bed_.provenance.printed_digits = digits_;
    bed_.validate(path_);
    bed_.validate_geometry(path_);
    return std::move(bed_);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path_ + ":" + std::to_string(lines_.line_number()) + ": " + what);
  }

  // "# boundary p p f" (write_lammps_data): the periodic axes.
  void boundary_comment(std::string_view line) {
    const auto hash = line.find('#');
    if (hash == std::string_view::npos) return;
    split_words(line.substr(hash + 1), words_);
    if (words_.size() != 4 || words_[0] != "boundary") return;
    for (int a = 0; a < 3; ++a) {
      if (words_[a + 1] != "p" && words_[a + 1] != "f")
        fail("boundary comment '" + std::string(line) + "' (accepted: p or f per axis)");
      periodic_[a] = words_[a + 1] == "p";
    }
  }

  void header() {
    std::string_view line;
    while (lines_.next(line)) {
      boundary_comment(line);
      split_words(strip_comment(line), words_);
      if (words_.empty()) continue;
      if (!is_number(words_[0])) {
        section(line);
        return;
      }
      const std::string_view last = words_.back();
      if (words_.size() == 2 && last == "atoms") {
        count_ = whole(words_[0], "atoms");
      } else if (words_.size() == 3 && words_[1] == "atom" && last == "types") {
        types_ = whole(words_[0], "atom types");
      } else if (words_.size() == 4 && (last == "xhi" || last == "yhi" || last == "zhi")) {
        const int a = last == "xhi" ? 0 : last == "yhi" ? 1 : 2;
        if (!detail::parse_double(words_[0], lower_[a]) ||
            !detail::parse_double(words_[1], upper_[a]))
          fail("box bounds '" + std::string(line) + "' (accepted: two numbers, lo hi)");
        box_[a] = true;
      } else if (words_.size() == 6 && last == "yz") {
        fail("triclinic box (accepted: orthogonal boxes)");
      }
      // Other header lines (bonds, extra/... counts, ellipsoids) carry nothing a bed holds.
    }
  }

  std::uint64_t whole(std::string_view word, const char* what) const {
    std::uint64_t v = 0;
    if (!detail::parse_uint(word, v))
      fail(std::string(what) + " count '" + std::string(word) + "' (accepted: a whole number)");
    return v;
  }

  void section(std::string_view line) {
    const std::string_view body = strip_comment(line);
    split_words(body, words_);
    std::string name;
    for (auto w : words_) {
      if (!name.empty()) name += ' ';
      name.append(w);
    }
    section_ = name;
    style_.clear();
    const auto hash = line.find('#');
    if (hash != std::string_view::npos) {
      split_words(line.substr(hash + 1), words_);
      if (!words_.empty()) style_ = std::string(words_[0]);
    }
  }

  // The numeric lines of the current section, up to the next keyword line.
  void body() {
    const std::string name = *section_;
    section_.reset();
    if (name == "Atoms") start_atoms();
    std::string_view line;
    while (lines_.next(line)) {
      split_words(strip_comment(line), words_);
      if (words_.empty()) continue;
      if (!is_number(words_[0])) {
        section(line);
        return;
      }
      if (name == "Atoms") atom_line(line);
      if (name == "Velocities") velocity_line(line);
    }
  }

  void start_atoms() {
    if (atoms_) fail("a second Atoms section");
    if (!style_.empty() && style_ != "sphere" && style_ != "granular")
      fail("Atoms # " + style_ + " (accepted: atom_style sphere or granular)");
    for (int a = 0; a < 3; ++a) {
      static constexpr const char* kBox[3] = {"xlo xhi", "ylo yhi", "zlo zhi"};
      if (!box_[a]) fail(std::string("no ") + kBox[a] + " line before Atoms");
    }
    if (!count_) fail("no 'N atoms' line before Atoms");
    // Each atom line holds at least 7 numbers of one digit and their separators.
    if (*count_ > lines_.bytes_left() / 14 + 1)
      fail(fmt::format("{} atoms declared but {} bytes follow (truncated file?)", *count_,
                       lines_.bytes_left()));
    atoms_ = true;
    Domain& d = bed_.domain;
    d.dimension = 3;
    d.lower = lower_;
    d.upper = upper_;
    d.periodic = periodic_;
    d.validate((path_ + ": box").c_str());
    bed_.reserve(*count_);
    type_.reserve(*count_);
  }

  double number(std::size_t k, const char* what) const {
    double v = 0;
    if (!detail::parse_double(words_[k], v))
      fail(std::string(what) + " is '" + std::string(words_[k]) + "' (accepted: a number)");
    return v;
  }

  // id type diameter density x y z [ix iy iz]
  void atom_line(std::string_view line) {
    if (words_.size() != 7 && words_.size() != 10)
      fail(std::to_string(words_.size()) + " columns in '" + std::string(line) +
           "' (accepted: id type diameter density x y z [ix iy iz], atom_style sphere)");
    if (bed_.n() == *count_) fail("more atoms than the " + std::to_string(*count_) + " declared");
    const std::uint64_t id = whole(words_[0], "atom id");
    const std::uint64_t type = whole(words_[1], "atom type");
    if (id == 0) fail("atom id 0 (accepted: LAMMPS ids >= 1)");
    if (type == 0 || (types_ && type > *types_) || type > 65536)
      fail("atom type " + std::to_string(type) + " (accepted: 1 to the declared atom types)");
    const double diameter = number(2, "diameter");
    // The bed keeps no density, but a data file whose density is not a mass density is not
    // one LAMMPS would run: refused rather than dropped unseen.
    if (const double density = number(3, "density"); !(std::isfinite(density) && density > 0))
      fail("density is '" + std::string(words_[3]) + "' (accepted: a finite number > 0, kg/m^3)");
    for (std::size_t k : {2u, 4u, 5u, 6u})
      digits_ = std::max(digits_, detail::significant_digits(words_[k]));
    bed_.x.push_back(number(4, "x"));
    bed_.y.push_back(number(5, "y"));
    bed_.z.push_back(number(6, "z"));
    bed_.radius.push_back(0.5 * diameter);
    bed_.id.push_back(id - 1);  // inverse of write_lammps_data's id + 1
    type_.push_back(static_cast<std::uint16_t>(type - 1));
    index_[id] = bed_.n() - 1;
  }

  // id vx vy vz [wx wy wz]
  void velocity_line(std::string_view line) {
    if (!atoms_) fail("Velocities before Atoms");
    if (words_.size() != 4 && words_.size() != 7)
      fail(std::to_string(words_.size()) + " columns in '" + std::string(line) +
           "' (accepted: id vx vy vz [wx wy wz])");
    if (bed_.vx.empty()) {
      bed_.vx.assign(bed_.n(), 0.0);
      bed_.vy.assign(bed_.n(), 0.0);
      bed_.vz.assign(bed_.n(), 0.0);
    }
    const auto it = index_.find(whole(words_[0], "atom id"));
    if (it == index_.end()) fail("Velocities of atom " + std::string(words_[0]) + ", not in Atoms");
    bed_.vx[it->second] = number(1, "vx");
    bed_.vy[it->second] = number(2, "vy");
    bed_.vz[it->second] = number(3, "vz");
    ++have_velocities_;
  }

  std::string path_;
  detail::LineCursor lines_;
  std::vector<std::string_view> words_;
  std::optional<std::uint64_t> count_, types_;
  std::array<double, 3> lower_{}, upper_{};
  std::array<bool, 3> box_{false, false, false}, periodic_{false, false, false};
  std::optional<std::string> section_;
  std::string style_;
  bool atoms_ = false;
  std::size_t have_velocities_ = 0;
  std::vector<std::uint16_t> type_;
  std::unordered_map<std::uint64_t, std::size_t> index_;
  int digits_ = 0;
  Bed bed_;
};

}  // namespace

Bed read_lammps_data(const std::string& path) {
  const std::string text = detail::read_text(path);
  return DataReader(path, text).read();
}

}  // namespace powderbed::bed
