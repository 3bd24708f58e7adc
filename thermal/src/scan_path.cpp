#include "powderbed/thermal/scan_path.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <sstream>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/input_file.hpp"

namespace powderbed::thermal {

double ScanSegment::length() const { return std::hypot(x1 - x0, y1 - y0); }

namespace {

// The part of the line c + s d (|d| = 1) inside the rectangle [x0, x1] × [y0, y1] (Liang–Barsky),
// as the parameters [s_lo, s_hi]; empty when s_lo >= s_hi.
std::pair<double, double> clip_line(const std::array<double, 2>& c, const std::array<double, 2>& d,
                                    const std::array<double, 4>& box) {
  double lo = -std::numeric_limits<double>::infinity(), hi = -lo;
  const double lower[2] = {box[0], box[2]}, upper[2] = {box[1], box[3]};
  for (int a = 0; a < 2; ++a) {
    if (std::abs(d[a]) < 1e-15) {
      if (c[a] < lower[a] || c[a] > upper[a]) return {0, 0};
      continue;
    }
    double s0 = (lower[a] - c[a]) / d[a], s1 = (upper[a] - c[a]) / d[a];
    if (s0 > s1) std::swap(s0, s1);
    lo = std::max(lo, s0);
    hi = std::min(hi, s1);
  }
  return {lo, hi};
}

}  // namespace

std::vector<ScanSegment> hatch_segments(const Hatch& h) {
  require_in_range(h.spacing > 0 && std::isfinite(h.spacing), "scan.hatch", h.spacing,
                   "a spacing h > 0 m");
  const auto& box = h.region;
  if (!(box[1] > box[0] && box[3] > box[2])) {
    throw InputError(fmt::format(
        "scan.region: {:g},{:g},{:g},{:g} is empty (accepted: x0,x1,y0,y1 with x0 < x1 and y0 < "
        "y1, m)",
        box[0], box[1], box[2], box[3]));
  }
  const double angle = static_cast<double>(h.layer) * h.rotation * M_PI / 180;
  const std::array<double, 2> d{std::cos(angle), std::sin(angle)}, n{-d[1], d[0]};
  const std::array<double, 2> centre{0.5 * (box[0] + box[1]), 0.5 * (box[2] + box[3])};
  // The region's width across the tracks, and the number of lines that fit in it.
  const double across = std::abs(n[0]) * (box[1] - box[0]) + std::abs(n[1]) * (box[3] - box[2]);
  const double fit = std::floor(across / h.spacing) + 1;  // lines the region holds
  const auto too_many = [&](std::size_t count, double fits) {
    return InputError(fmt::format(
        "scan.tracks: {} tracks at spacing {:g} m span {:g} m, wider than the region ({:g} m "
        "across the tracks) (accepted: tracks <= {:g}, a smaller scan.hatch, or scan.tracks = 0 to "
        "fill the region)",
        count, h.spacing, static_cast<double>(count - 1) * h.spacing, across, fits));
  };
  // Refused before the lines are made: a count of 1e12 would run for hours first.
  if (h.tracks > 0 && static_cast<double>(h.tracks) > fit) throw too_many(h.tracks, fit);
  const std::size_t count = h.tracks > 0 ? h.tracks : static_cast<std::size_t>(fit);
  std::vector<ScanSegment> out;
  for (std::size_t m = 0; m < count; ++m) {
    const double offset = (static_cast<double>(m) - 0.5 * static_cast<double>(count - 1)) * h.spacing;
    const std::array<double, 2> c{centre[0] + offset * n[0], centre[1] + offset * n[1]};
    auto [lo, hi] = clip_line(c, d, box);
    if (!(hi > lo)) continue;
    if (h.direction == HatchDirection::alternating && out.size() % 2 == 1) std::swap(lo, hi);
    // On the region's edge exactly (the clip's round-off must not put an end outside it).
    const auto x = [&](double t) { return std::clamp(c[0] + t * d[0], box[0], box[1]); };
    const auto y = [&](double t) { return std::clamp(c[1] + t * d[1], box[2], box[3]); };
    out.push_back({x(lo), y(lo), x(hi), y(hi), h.power, h.speed});
  }
  // A line exactly on the region's edge may clip to nothing in round-off.
  if (out.size() < count) throw too_many(count, static_cast<double>(out.size()));
  return out;
}

std::vector<ScanSegment> read_scan_csv(const std::string& path) {
  bed::require_regular_file(path, "--scan-path");  // a FIFO would block, /dev/zero never end
  std::ifstream in(path);
  if (!in) throw InputError("--scan-path: cannot open " + path);
  std::vector<ScanSegment> out;
  bool header = false;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    const std::string where = "--scan-path: " + path + ":" + std::to_string(number);
    std::vector<std::string> fields;
    std::stringstream row(line);
    for (std::string f; std::getline(row, f, ',');) {
      const auto a = f.find_first_not_of(" \t\r"), b = f.find_last_not_of(" \t\r");
      fields.push_back(a == std::string::npos ? "" : f.substr(a, b - a + 1));
    }
    if (!header) {
      if (fields != std::vector<std::string>{"x0", "y0", "x1", "y1", "power", "speed"})
        throw InputError(where + ": header '" + line + "' (accepted: x0,y0,x1,y1,power,speed)");
      header = true;
      continue;
    }
    if (fields.size() != 6)
      throw InputError(where + ": " + std::to_string(fields.size()) +
                       " fields (accepted: 6: x0,y0,x1,y1 in m, power in W, speed in m/s)");
    double v[6];
    for (int c = 0; c < 6; ++c) {
      std::size_t used = 0;
      try {
        v[c] = std::stod(fields[static_cast<std::size_t>(c)], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != fields[static_cast<std::size_t>(c)].size() || !std::isfinite(v[c]))
        throw InputError(where + ": '" + fields[static_cast<std::size_t>(c)] +
                         "' is not a finite number (accepted: SI numbers, e.g. 1.5e-4)");
    }
    out.push_back({v[0], v[1], v[2], v[3], v[4], v[5]});
  }
  if (out.empty())
    throw InputError("--scan-path: " + path + " has no segment (accepted: the header "
                     "x0,y0,x1,y1,power,speed and at least one row)");
  return out;
}

std::string scan_csv(const std::vector<ScanSegment>& segments) {
  std::ostringstream out;
  out.precision(17);
  out << "x0,y0,x1,y1,power,speed\n";
  for (const auto& s : segments)
    out << s.x0 << ',' << s.y0 << ',' << s.x1 << ',' << s.y1 << ',' << s.power << ',' << s.speed
        << '\n';
  return out.str();
}

void check_scan_path(const std::vector<ScanSegment>& segments, double jump_speed, double x0,
                     double x1, double y0, double y1) {
  require_in_range(jump_speed > 0 && std::isfinite(jump_speed), "scan.jump-speed", jump_speed,
                   "a jump speed > 0 m/s");
  for (std::size_t m = 0; m < segments.size(); ++m) {
    const ScanSegment& s = segments[m];
    const std::size_t which = m + 1;
    if (!(s.power >= 0)) {
      throw InputError(fmt::format(
          "scan path segment {}: power {:g} W (accepted: power >= 0 W)", which, s.power));
    }
    if (!(s.speed > 0)) {
      throw InputError(fmt::format(
          "scan path segment {}: speed {:g} m/s (accepted: speed > 0 m/s)", which, s.speed));
    }
    if (!(s.length() > 0)) {
      throw InputError(fmt::format(
          "scan path segment {}: starts where it ends (accepted: a segment of length > 0)",
          which));
    }
    const auto inside = [&](double x, double y) {
      return x >= x0 && x <= x1 && y >= y0 && y <= y1;
    };
    if (inside(s.x0, s.y0) && inside(s.x1, s.y1)) continue;
    throw InputError(fmt::format(
        "scan path segment {}: ({:g}, {:g}) to ({:g}, {:g}) m leaves the plate (accepted: ends "
        "within x {:g} to {:g} m, y {:g} to {:g} m)",
        which, s.x0, s.y0, s.x1, s.y1, x0, x1, y0, y1));
  }
}

ScanSchedule::ScanSchedule(std::vector<ScanSegment> segments, double jump_speed)
    : segments_(std::move(segments)) {
  double t = 0;
  for (std::size_t m = 0; m < segments_.size(); ++m) {
    if (m > 0) {
      const ScanSegment& a = segments_[m - 1];
      const ScanSegment& b = segments_[m];
      t += std::hypot(b.x0 - a.x1, b.y0 - a.y1) / jump_speed;  // laser off
    }
    start_.push_back(t);
    t += segments_[m].length() / segments_[m].speed;
    end_.push_back(t);
  }
}

std::array<double, 2> ScanSchedule::direction(std::size_t m) const {
  const ScanSegment& s = segments_[m];
  const double l = s.length();
  return {(s.x1 - s.x0) / l, (s.y1 - s.y0) / l};
}

ScanSchedule::Beam ScanSchedule::at(double t) const {
  // The last segment begun at t (segments are in time order).
  const auto it = std::upper_bound(start_.begin(), start_.end(), t);
  if (it == start_.begin()) return {};
  const auto m = static_cast<std::size_t>(it - start_.begin()) - 1;
  if (t >= end_[m]) {
    Beam off;
    off.segment = m;
    return off;
  }
  return on_segment(m, t);
}

ScanSchedule::Beam ScanSchedule::on_segment(std::size_t m, double t) const {
  const ScanSegment& s = segments_[m];
  const auto d = direction(m);
  const double travel = s.speed * (t - start_[m]);
  Beam b;
  b.segment = m;
  b.on = t >= start_[m] && t < end_[m];
  b.x = s.x0 + travel * d[0];
  b.y = s.y0 + travel * d[1];
  // Measured from the position as the kernels use it (on a segment along x this is the
  // difference start_x + v t - start_x of the single-track solver, bit for bit).
  b.along = (b.x - s.x0) * d[0] + (b.y - s.y0) * d[1];
  b.power = b.on ? s.power : 0.0;
  return b;
}

double ScanSchedule::beam_energy(double t) const {
  double e = 0;
  for (std::size_t m = 0; m < segments_.size(); ++m)
    e += segments_[m].power * std::max(0.0, std::min(t, end_[m]) - start_[m]);
  return e;
}

}  // namespace powderbed::thermal
