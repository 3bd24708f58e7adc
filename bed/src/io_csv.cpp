// CSV beds "x,y,z,r" (SI units), docs/bed-format.md: full precision out, strict checks in.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "io_detail.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"

namespace powderbed::bed {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

void write_bed_csv(const Bed& bed, const std::string& path) {
  bed.validate(path);
  detail::AtomicFile file(path);
  std::string text = "x,y,z,r\n";
  text.reserve(text.size() + bed.n() * 4 * 25);
  char line[128];
  for (std::size_t i = 0; i < bed.n(); ++i) {
    // %.17g: every double reads back bit for bit.
    const int len = std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g\n", bed.x[i],
                                  bed.y[i], bed.z[i], bed.radius[i]);
    text.append(line, static_cast<std::size_t>(len));
  }
  detail::write_text(file.temp_path(), path, text);
  file.commit();
}

Bed read_bed_csv(const std::string& path, const Domain& domain) {
  domain.validate((path + ": domain").c_str());
  const std::string text = detail::read_text(path);
  detail::LineCursor lines(text);
  auto fail = [&](const std::string& what) {
    throw InputError(path + ":" + std::to_string(lines.line_number()) + ": " + what);
  };
  std::string_view line;
  if (!lines.next(line) || trim(line) != "x,y,z,r")
    fail("header is '" + std::string(line) + "' (accepted: x,y,z,r)");

  Bed bed;
  bed.domain = domain;
  static const char* const names[4] = {"x", "y", "z", "r"};
  while (lines.next(line)) {
    if (trim(line).empty()) continue;
    std::string_view fields[4];
    std::size_t count = 0;
    std::size_t start = 0;
    while (true) {
      const auto comma = line.find(',', start);
      const auto field = line.substr(start, comma == std::string_view::npos ? comma : comma - start);
      if (count < 4) fields[count] = trim(field);
      ++count;
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (count != 4) fail(std::to_string(count) + " fields, expected 4 (x,y,z,r)");
    double v[4];
    for (int k = 0; k < 4; ++k) {
      if (!detail::parse_double(fields[k], v[k])) {
        fail(std::string(names[k]) + " is '" + std::string(fields[k]) + "' (accepted: a number)");
      }
      if (!std::isfinite(v[k]))
        fail(std::string(names[k]) + " is " + std::string(fields[k]) + " (accepted: finite)");
    }
    if (!(v[3] > 0)) fail("r is " + std::string(fields[3]) + " (accepted: > 0)");
    if (domain.dimension == 2 && v[2] != 0.0)
      fail("z is " + std::string(fields[2]) + " but the domain is 2D (accepted: 0)");
    bed.x.push_back(v[0]);
    bed.y.push_back(v[1]);
    bed.z.push_back(v[2]);
    bed.radius.push_back(v[3]);
    bed.id.push_back(bed.id.size());
  }
  bed.validate(path);
  bed.validate_geometry(path);  // inside --domain, radii plausible for it
  return bed;
}

}  // namespace powderbed::bed
