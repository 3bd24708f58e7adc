// YADE's text export (yade.export.text, docs/decks.md): "x y z r" per sphere under a
// "#format x_y_z_r" header; every line starting with '#' is a comment.
#include <algorithm>
#include <limits>

#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"

namespace powderbed::bed {

namespace {

// The spheres' bounding box, centre +- radius on every axis (a file without a domain).
Domain bounding_box(const Bed& bed) {
  Domain d;
  d.lower.fill(std::numeric_limits<double>::infinity());
  d.upper.fill(-std::numeric_limits<double>::infinity());
  const std::vector<double>* c[3] = {&bed.x, &bed.y, &bed.z};
  for (std::size_t i = 0; i < bed.n(); ++i) {
    for (int a = 0; a < 3; ++a) {
      d.lower[a] = std::min(d.lower[a], (*c[a])[i] - bed.radius[i]);
      d.upper[a] = std::max(d.upper[a], (*c[a])[i] + bed.radius[i]);
    }
  }
  return d;
}

}  // namespace

Bed read_yade_text(const std::string& path, const Domain* domain) {
  const std::string text = detail::read_text(path);
  detail::LineCursor lines(text);
  std::vector<std::string_view> words;
  std::string_view line;
  Bed bed;
  int digits = 0;
  auto fail = [&](const std::string& what) {
    throw InputError(path + ":" + std::to_string(lines.line_number()) + ": " + what);
  };
  while (lines.next(line)) {
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string_view::npos) continue;
    if (line[start] == '#') {
      detail::split_words(line.substr(start + 1), words);
      if (words.size() == 1 && words[0].substr(0, 6) == "format" && line.find("x_y_z_r") == std::string_view::npos)
        fail(detail::quoted(line) + " (accepted: #format x_y_z_r; export with yade.export.text)");
      continue;
    }
    detail::split_words(line, words);
    if (words.size() != 4)
      fail(std::to_string(words.size()) + " columns (accepted: x y z r, as yade.export.text writes)");
    double v[4];
    for (int k = 0; k < 4; ++k) {
      if (!detail::parse_double(words[k], v[k]))
        fail(detail::quoted(words[k]) + " (accepted: a number)");
      digits = std::max(digits, detail::significant_digits(words[k]));
    }
    bed.add(v[0], v[1], v[2], v[3]);
  }
  if (bed.n() == 0) throw InputError(path + ": no spheres (accepted: YADE text, x y z r per line)");
  bed.validate(path);
  bed.domain = domain ? *domain : bounding_box(bed);
  bed.domain.validate((path + ": domain").c_str());
  bed.validate_geometry(path);
  bed.provenance.printed_digits = digits;
  return bed;
}

}  // namespace powderbed::bed
