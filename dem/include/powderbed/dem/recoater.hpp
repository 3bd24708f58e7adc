#pragma once
// The recoater tool of a spreading run (docs/deposit-spread.md): a blade or a roller, a rigid
// wall with the scene's contact law that moves along x at a prescribed speed, infinitely long
// across (y). Its cross-section in the x–z plane is a rounded box: the set of points within
// `rounding` of the rectangle |x - x_c| <= half_width, z_low <= z <= z_high (x_c the tool's
// position). A blade is a flat-bottomed box of its thickness (sharp edges: rounding 0; rounded
// ones: rounding = the edge radius) reaching up without end; a roller is the circle of its
// radius (a rectangle shrunk to its axis, rounded by the radius).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include "powderbed/bed/option_words.hpp"

namespace powderbed::dem {

enum class ToolShape { blade, roller };
inline constexpr bed::OptionWord<ToolShape> kToolShapeWords[] = {{"blade", ToolShape::blade},
                                                              {"roller", ToolShape::roller}};
// "blade" | "roller"; throws InputError naming `option` otherwise.
ToolShape parse_tool_shape(const std::string& text, const std::string& option = "recoater.tool");

struct Recoater {
  ToolShape shape = ToolShape::blade;
  double thickness = 500e-6;  // blade: extent along x, m
  double edge_radius = 0;     // blade: radius of its two bottom edges (0: sharp), m
  double radius = 1e-3;       // roller: m
  // Roller spin about +y (right-handed), rad/s: its surface moves at omega ey x (p - axis), so
  // omega > 0 turns the bottom backwards (-x), as a wheel rolling forwards; the counter-rotating
  // rollers of spreading machines turn with omega < 0.
  double omega = 0;
  double gap = 100e-6;        // height of the tool's lowest point above the plate, m
  double speed = 0.1;         // m/s along +x
  double start = 0;           // x of the tool's centre (blade mid-plane, roller axis) at the start, m
  double end = 0;             // ... where it stops, m
  double delay = 0;           // s at the start before it moves (the supply settles)
  double settle = 0;          // s after it stopped (the layer settles)
};

struct ToolProfile {
  double half_width = 0;
  double z_low = 0;
  double z_high = 0;
  double rounding = 0;
};

// The tool's cross-section with its lowest point at `bottom` (the plate plus the gap).
inline ToolProfile tool_profile(const Recoater& tool, double bottom) {
  if (tool.shape == ToolShape::roller) {
    return {0.0, bottom + tool.radius, bottom + tool.radius, tool.radius};
  }
  const double r = tool.edge_radius;
  return {0.5 * tool.thickness - r, bottom + r, std::numeric_limits<double>::infinity(), r};
}

// The half extent of the tool along x (its front face is at x_c + this).
inline double tool_half_extent(const ToolProfile& p) { return p.half_width + p.rounding; }

struct ToolContact {
  double delta = 0;                // overlap, m (> 0 in contact)
  double n[3] = {0, 0, 0};         // unit normal from the particle's centre towards the tool
  double surface[3] = {0, 0, 0};   // contact point on the tool's surface, relative to (x_c, 0, 0)
};

// Contact of a sphere (centre px, pz relative to the tool's position in x; radius r) with the
// tool; false when they do not touch. A centre inside the core rectangle (a particle already
// deep inside the tool, which the set-up refuses) is pushed out through the nearest side.
inline bool tool_contact(const ToolProfile& p, double px, double pz, double r, ToolContact& c) {
  // Beside or below the tool by more than the sphere's reach: no contact, without the root
  // (the spread loop asks this of every particle every step; most are far from the tool).
  const double reach = r + p.rounding;
  if (std::abs(px) - p.half_width >= reach || p.z_low - pz >= reach) return false;
  const double qx = std::clamp(px, -p.half_width, p.half_width);
  const double qz = std::clamp(pz, p.z_low, p.z_high);
  double ex = px - qx, ez = pz - qz;  // from the core rectangle to the centre
  double d = std::sqrt(ex * ex + ez * ez);
  if (d == 0.0) {  // inside the core: out through the nearest face
    const double to_side = p.half_width - std::abs(px), to_bottom = pz - p.z_low;
    if (to_side < to_bottom) {
      ex = px >= 0 ? 1.0 : -1.0;
      ez = 0;
      d = -to_side;
    } else {
      ex = 0;
      ez = -1.0;
      d = -to_bottom;
    }
    c.delta = r + p.rounding - d;
    c.n[0] = -ex;
    c.n[2] = -ez;
  } else {
    c.delta = r + p.rounding - d;
    if (c.delta <= 0) return false;
    c.n[0] = -ex / d;
    c.n[2] = -ez / d;
  }
  c.n[1] = 0;
  c.surface[0] = qx - c.n[0] * p.rounding;
  c.surface[1] = 0;
  c.surface[2] = qz - c.n[2] * p.rounding;
  return c.delta > 0;
}

}  // namespace powderbed::dem
