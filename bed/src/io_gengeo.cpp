// GenGeo's LSMGeometry file (.geo, docs/decks.md), as its writeGeometry writes it:
//   LSMGeometry 1.2
//   BoundingBox xmin ymin zmin xmax ymax zmax
//   PeriodicBoundaries px py pz
//   Dimension 3D | 2D
//   BeginParticles
//   Simple
//   N
//   x y z r id tag        (N lines)
//   EndParticles
//   BeginConnect ... EndConnect   (bonds: ignored)
#include <algorithm>
#include <fmt/format.h>

#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"

namespace powderbed::bed {

namespace {

class GeoReader {
 public:
  GeoReader(std::string path, std::string_view text) : path_(std::move(path)), lines_(text) {}

  Bed read() {
    expect("LSMGeometry");
    if (words_.size() != 2 || (words_[1] != "1.2" && words_[1] != "1.1"))
      fail(detail::quoted(line_) + " (accepted: LSMGeometry 1.2)");
    expect("BoundingBox");
    if (words_.size() != 7) fail(detail::quoted(line_) + " (accepted: BoundingBox xmin ymin zmin xmax ymax zmax)");
    Domain& d = bed_.domain;
    for (int a = 0; a < 3; ++a) {
      d.lower[a] = number(1 + a);
      d.upper[a] = number(4 + a);
    }
    expect("PeriodicBoundaries");
    if (words_.size() != 4) fail(detail::quoted(line_) + " (accepted: PeriodicBoundaries px py pz, each 0 or 1)");
    for (int a = 0; a < 3; ++a) {
      if (words_[1 + a] != "0" && words_[1 + a] != "1")
        fail(detail::quoted(line_) + " (accepted: PeriodicBoundaries px py pz, each 0 or 1)");
      d.periodic[a] = words_[1 + a] == "1";
    }
    next_words();
    if (words_.empty() || (words_[0] != "Dimension" && words_[0] != "Dimensions") || words_.size() != 2 ||
        (words_[1] != "3D" && words_[1] != "2D"))
      fail(detail::quoted(line_) + " (accepted: Dimension 3D or 2D)");
    d.dimension = words_[1] == "3D" ? 3 : 2;
    if (d.dimension == 2) {
      d.lower[2] = d.upper[2] = 0;  // GenGeo's 2D box is +-0.1 thick in z; beds are flat
      d.periodic[2] = false;
    }
    d.validate((path_ + ": BoundingBox").c_str());
    expect("BeginParticles");
    expect("Simple");
    next_words();
    std::uint64_t count = 0;
    if (words_.size() != 1 || !detail::parse_uint(words_[0], count))
      fail(detail::quoted(line_) + " (accepted: the particle count)");
    if (count > lines_.bytes_left() / 12 + 1)
      fail(fmt::format("{} particles declared but {} bytes follow (truncated file?)", count,
                       lines_.bytes_left()));
    bed_.reserve(count);
    int digits = 0;
    for (std::uint64_t i = 0; i < count; ++i) {
      next_words();
      if (words_.size() != 6) fail(detail::quoted(line_) + " (accepted: x y z r id tag)");
      bed_.x.push_back(number(0));
      bed_.y.push_back(number(1));
      bed_.z.push_back(d.dimension == 2 ? 0.0 : number(2));
      bed_.radius.push_back(number(3));
      std::uint64_t id = 0;
      if (!detail::parse_uint(words_[4], id)) fail("id '" + std::string(words_[4]) + "' (accepted: a whole number >= 0)");
      bed_.id.push_back(id);
      for (int k = 0; k < 4; ++k) digits = std::max(digits, detail::significant_digits(words_[k]));
    }
    expect("EndParticles");
    bed_.provenance.printed_digits = digits;
    bed_.validate(path_);
    bed_.validate_geometry(path_);
    return std::move(bed_);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path_ + ":" + std::to_string(lines_.line_number()) + ": " + what);
  }

  void next_words() {
    std::string_view line;
    while (lines_.next(line)) {
      detail::split_words(line, words_);
      if (!words_.empty()) {
        line_ = std::string(line);
        return;
      }
    }
    fail("file ends early (truncated GenGeo file?)");
  }

  void expect(const char* keyword) {
    next_words();
    if (words_[0] != keyword) fail(detail::quoted(line_) + " where '" + keyword + "' belongs");
  }

  double number(std::size_t k) const {
    double v = 0;
    if (!detail::parse_double(words_[k], v)) fail(detail::quoted(words_[k]) + " (accepted: a number)");
    return v;
  }

  std::string path_;
  detail::LineCursor lines_;
  std::vector<std::string_view> words_;
  std::string line_;
  Bed bed_;
};

}  // namespace

Bed read_gengeo(const std::string& path) {
  const std::string text = detail::read_text(path);
  return GeoReader(path, text).read();
}

}  // namespace powderbed::bed
