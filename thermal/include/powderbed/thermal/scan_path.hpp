#pragma once
// The laser's scan path: straight segments, each at its own power and speed, with the laser off
// while the scanner jumps from the end of one segment to the start of the next. The jump takes
// time (its length over the jump speed): the bed cools between tracks as on a machine, whose
// galvanometer mirrors jump at a finite speed (a few m/s) with the beam off.
//
// A path comes from a hatch (parallel tracks across a rectangular region, spacing h, one-way or
// alternating, rotated by k × rotation about the region's centre on layer k: 67° per layer is
// the usual choice, since 67 and 180 have no common factor and no two of 180 successive layers
// scan along the same line), or from a CSV of segments (header x0,y0,x1,y1,power,speed; SI).
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "powderbed/bed/option_words.hpp"

namespace powderbed::thermal {

struct ScanSegment {
  double x0, y0, x1, y1;  // m
  double power;           // W
  double speed;           // m/s
  double length() const;
};

enum class HatchDirection { one_way, alternating };
inline constexpr bed::OptionWord<HatchDirection> kHatchDirectionWords[] = {
    {"one-way", HatchDirection::one_way}, {"alternating", HatchDirection::alternating}};

struct Hatch {
  double spacing = 0;          // h between track centre lines, m
  std::size_t tracks = 0;      // 0: as many as the region holds at spacing h
  HatchDirection direction = HatchDirection::alternating;
  double rotation = 67;        // degrees per layer, about the region's centre
  std::size_t layer = 0;       // k: the tracks run at k × rotation from +x
  std::array<double, 4> region{};  // x0, x1, y0, y1, m
  double power = 0, speed = 0;     // of every track
};

// The tracks of a hatch: lines at angle k × rotation through the region's centre offset by
// (m - (N - 1)/2) h across, each clipped to the region (a line that misses it is no track).
// Throws InputError naming scan.hatch, scan.region or scan.tracks when it holds no track.
std::vector<ScanSegment> hatch_segments(const Hatch& hatch);

// Reads x0,y0,x1,y1,power,speed rows (the header line first; '#' lines and blank lines are
// skipped). Throws InputError naming the file, the line and what is wrong.
std::vector<ScanSegment> read_scan_csv(const std::string& path);
// The same format (17 significant digits: a path read back is the same path).
std::string scan_csv(const std::vector<ScanSegment>& segments);

// Throws InputError when a segment has a power < 0, a speed <= 0, zero length or an end outside
// [x0, x1] × [y0, y1] (the plate under the bed), or the jump speed is not > 0.
void check_scan_path(const std::vector<ScanSegment>& segments, double jump_speed, double x0,
                     double x1, double y0, double y1);

// Where the beam is at time t: segment m runs from start(m) for length/speed; between segments
// the laser is off for the jump.
class ScanSchedule {
 public:
  struct Beam {
    bool on = false;
    std::size_t segment = 0;  // the segment running, or the last one begun
    double x = 0, y = 0;      // m
    double along = 0;         // distance from the segment's start, m
    double power = 0;         // W (0 when off)
  };
  ScanSchedule() = default;
  ScanSchedule(std::vector<ScanSegment> segments, double jump_speed);
  Beam at(double t) const;
  // Where the beam of segment m is at time t on the segment's line, whether it runs then or not
  // (on = false outside the segment's time).
  Beam on_segment(std::size_t m, double t) const;
  double start(std::size_t m) const { return start_[m]; }
  double end(std::size_t m) const { return end_[m]; }
  double finish() const { return end_.empty() ? 0.0 : end_.back(); }
  const std::vector<ScanSegment>& segments() const { return segments_; }
  // Unit vector along segment m.
  std::array<double, 2> direction(std::size_t m) const;
  // Σ P_m × (the time segment m runs within [0, t]), J: the beam's energy up to t.
  double beam_energy(double t) const;

 private:
  std::vector<ScanSegment> segments_;
  std::vector<double> start_, end_;
};

}  // namespace powderbed::thermal
