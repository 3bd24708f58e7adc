// A spreading deck (deck.hpp write_spread_deck, docs/decks.md "Spreading decks"): the drop deck's
// laws (deck_detail.hpp) plus the recoater, the supply of later layers and the layer loop. LIGGGHTS:
// the tool as an STL moved by fix move/mesh, the solid under the powder as an STL; LAMMPS: the tool
// as a moving region under fix wall/gran/region, the plate as the box's zplane wall.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "deck_detail.hpp"
#include "powderbed/bed/deck.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/bed/temp_files.hpp"

namespace powderbed::bed {

using namespace deck_detail;

namespace {

using Vertex = std::array<double, 3>;
using Triangle = std::array<Vertex, 3>;

// Chords per quarter of a rounded edge or of the roller: the polygon lies inside the arc by at
// most rho (1 - cos(pi / 64)) = 1.2e-3 rho, and its lowest vertex is the arc's lowest point.
constexpr int kArcChords = 16;
// LIGGGHTS 3.8 aborts (MPI_ABORT, no message) on a mesh vertex on a periodic face and drops
// elements outside the box: the meshes keep this fraction of the box's length from its faces
// across (y) and the floor from the end walls (bench/liggghts/blade_stl.py found it).
constexpr double kInset = 1e-3;

struct Point {
  double x = 0, z = 0;
};

// The tool's cross-section (x from its centre, z absolute) as a convex polygon, counter-clockwise
// seen from -y: the points within `rounding` of the rectangle |x| <= half_width,
// bottom + rounding <= z <= top - rounding (a roller: the circle about bottom + R).
std::vector<Point> tool_section(const DeckTool& t, double bottom, double top) {
  const double rho = t.rounding, w = t.half_width;
  const double low = bottom + rho, high = t.roller ? low : top - rho;
  if (rho == 0) return {{-w, low}, {w, low}, {w, high}, {-w, high}};
  const std::array<Point, 4> centres{{{w, low}, {w, high}, {-w, high}, {-w, low}}};
  std::vector<Point> p;
  for (int c = 0; c < 4; ++c) {
    for (int k = 0; k <= kArcChords; ++k) {
      const double a = (c - 1 + static_cast<double>(k) / kArcChords) * std::numbers::pi / 2;
      const Point q{centres[static_cast<std::size_t>(c)].x + rho * std::cos(a),
                    centres[static_cast<std::size_t>(c)].z + rho * std::sin(a)};
      // a roller's four centres coincide: each quarter starts where the last one ended
      if (p.empty() || std::hypot(q.x - p.back().x, q.z - p.back().z) > 1e-9 * rho) p.push_back(q);
    }
  }
  if (std::hypot(p.front().x - p.back().x, p.front().z - p.back().z) <= 1e-9 * rho) p.pop_back();
  return p;
}

// The section swept across y0..y1 at x offset `x`: a closed prism (sides and two fan caps).
std::vector<Triangle> extrude(const std::vector<Point>& section, double x, double y0, double y1) {
  std::vector<Triangle> tris;
  const std::size_t n = section.size();
  auto at = [&](std::size_t i, double y) { return Vertex{x + section[i % n].x, y, section[i % n].z}; };
  for (std::size_t i = 0; i < n; ++i) {
    tris.push_back({at(i, y0), at(i + 1, y0), at(i + 1, y1)});
    tris.push_back({at(i, y0), at(i + 1, y1), at(i, y1)});
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    tris.push_back({at(0, y0), at(i + 1, y0), at(i, y0)});
    tris.push_back({at(0, y1), at(i, y1), at(i + 1, y1)});
  }
  return tris;
}

// The floor z = floor.at(x, y) over the box (inset), on the height map's nodes and the box's
// edges (beyond its nodes the map holds its edge values, as the spread's floor does).
std::vector<Triangle> floor_mesh(const HeightMap& floor, const Domain& d) {
  auto axis = [](double lo, double hi, double first, double step, std::size_t n) {
    const double margin = kInset * (hi - lo);
    std::vector<double> v{lo + margin};
    for (std::size_t i = 0; i < n; ++i) {
      const double c = first + static_cast<double>(i) * step;
      if (c > v.back() && c < hi - margin) v.push_back(c);
    }
    v.push_back(hi - margin);
    return v;
  };
  const std::vector<double> xs = axis(d.lower[0], d.upper[0], floor.x0, floor.dx, floor.nx);
  const std::vector<double> ys = axis(d.lower[1], d.upper[1], floor.y0, floor.dy, floor.ny);
  auto v = [&](std::size_t i, std::size_t j) { return Vertex{xs[i], ys[j], floor.at(xs[i], ys[j])}; };
  std::vector<Triangle> tris;
  for (std::size_t j = 0; j + 1 < ys.size(); ++j)
    for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
      tris.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      tris.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  return tris;
}

std::string stl_text(const std::vector<Triangle>& tris, const std::string& name) {
  std::string s = "solid " + name + "\n";
  for (const Triangle& t : tris) {
    const Vertex u{t[1][0] - t[0][0], t[1][1] - t[0][1], t[1][2] - t[0][2]};
    const Vertex w{t[2][0] - t[0][0], t[2][1] - t[0][1], t[2][2] - t[0][2]};
    Vertex n{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double len = std::hypot(n[0], n[1], n[2]);
    for (double& c : n) c = len > 0 ? c / len : 0.0;
    s += fmt::format("  facet normal {} {} {}\n    outer loop\n", num(n[0]), num(n[1]), num(n[2]));
    for (const Vertex& p : t) s += fmt::format("      vertex {} {} {}\n", num(p[0]), num(p[1]), num(p[2]));
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid " + name + "\n";
}

// The smallest prime >= n (LIGGGHTS takes only primes > 10000 as seeds).
std::uint64_t prime_at_least(std::uint64_t n) {
  auto prime = [](std::uint64_t v) {
    for (std::uint64_t d = 2; d * d <= v; ++d)
      if (v % d == 0) return false;
    return v > 1;
  };
  while (!prime(n)) ++n;
  return n;
}

std::uint64_t steps_of(double seconds, double dt) {  // as run_spread counts them
  return static_cast<std::uint64_t>(std::ceil(seconds / dt - 1e-9));
}

double tool_top(const Domain& d, const SpreadDeck& s) {  // the blade's STL top at layer 1
  const double lz = d.upper[2] - d.lower[2];
  return d.upper[2] - static_cast<double>(s.layers - 1) * s.layer_thickness - kInset * lz;
}

void check_spread(const Bed& bed, const DeckLaws& laws, const SpreadDeck& s) {
  const Domain& d = bed.domain;
  const DeckTool& t = s.tool;
  const double half = t.half_width + t.rounding;
  if (d.periodic[0])
    throw InputError("deck: a spread box periodic along x (accepted: periodic y or none)");
  if (s.engine == DeckEngine::liggghts && (t.start - half < d.lower[0] || t.end + half > d.upper[0]))
    throw InputError(fmt::format("recoater.start, recoater.end: the tool spans x = {:g} to {:g} m, beyond the "
                                 "box [{:g}, {:g}] m (LIGGGHTS drops mesh elements outside the box; accepted "
                                 "for a deck: a tool inside it)",
                                 t.start - half, t.end + half, d.lower[0], d.upper[0]));
  const double bottom = d.lower[2] + t.gap;
  const double needed = t.roller ? bottom + 2 * t.rounding : bottom + 2 * t.rounding + 1e-9;
  if (s.layers == 0 || !(tool_top(d, s) > needed))
    throw InputError(fmt::format("--layers: the tool of layer {} rises above the box's top {:g} m (accepted: "
                                 "a taller box or fewer layers)", s.layers, d.upper[2]));
  if (!(t.speed > 0) || !(t.end > t.start))
    throw InputError("recoater.speed, recoater.end: the tool must move forwards (accepted: speed > 0, end > start)");
  if (s.layers > 1) {
    const double base = bottom + static_cast<double>(s.layers - 2) * s.layer_thickness;
    if (s.psd_bins.empty() || !(s.supply_x1 > s.supply_x0) || base + s.supply_height > d.upper[2])
      throw InputError(fmt::format("supply.height: the supply of layer {} ({:g} m tall from z = {:g} m) does not fit "
                                   "the box (accepted: supply.height <= {:g} m)",
                                   s.layers, s.supply_height, base, d.upper[2] - base));
  }
  if (!laws.rotation) throw InputError("deck: a spreading deck integrates rotation (laws.rotation)");
}

struct Names {
  std::string tool, floor;  // STL names relative to the deck's folder
};

// The wall/gran of the meshes (the tool, and the floor when there is one: LIGGGHTS 3.8 takes one
// mesh wall/gran fix only), with the model and settings of the box's walls.
std::string mesh_wall(const SpreadDeck& s, const LiggghtsContact& c) {
  return "fix            tool_wall all wall/gran " + c.model +
         (s.floor.empty() ? " mesh n_meshes 1 meshes tool" : " mesh n_meshes 2 meshes floor tool") +
         c.settings + "\n";
}

// Particle templates and their number-based distribution (layers after the first).
void supply_templates(std::ostringstream& out, const SpreadDeck& s, const DeckLaws& laws) {
  double total = 0;
  for (const auto& [r, w] : s.psd_bins) total += w;
  out << "# The supply of layers 2..: the PSD in " << s.psd_bins.size()
      << " bins of equal width in radius, each at its middle radius with its number fraction\n";
  std::uint64_t seed = prime_at_least(15485863 + 1009 * s.seed);
  std::string dist = fmt::format("fix            supply_psd all particledistribution/discrete/numberbased {} {}",
                                 seed, s.psd_bins.size());
  for (std::size_t k = 0; k < s.psd_bins.size(); ++k) {
    seed = prime_at_least(seed + 1);
    out << "fix            supply_t" << k + 1 << " all particletemplate/sphere " << seed
        << " atom_type 1 volume_limit 1e-20 density constant " << num(laws.density.front())
        << " radius constant " << num(s.psd_bins[k].first) << "\n";
    dist += fmt::format(" supply_t{} {}", k + 1, num(s.psd_bins[k].second / total));
  }
  out << dist << "\n";
}

void supply_of_layer(std::ostringstream& out, const Bed& bed, const SpreadDeck& s) {
  const Domain& d = bed.domain;
  const double base = d.lower[2] + s.tool.gap - s.layer_thickness;  // + (L - 1) t: RAISE
  const std::string fill =
      s.supply_count > 0
          ? fmt::format("particles_in_region {}", s.supply_count)
          : fmt::format("volumefraction_region {}", num(s.supply_volume / ((s.supply_x1 - s.supply_x0) *
                                                                         (d.upper[1] - d.lower[1]) * s.supply_height)));
  // equal-style variables: a quoted command of `if` is substituted only when it runs
  out << "  # layer 2..: the supply on the powder the tool of the layer before left, by insert/pack\n"
      << "  variable       SUPPLY_LO equal " << num(base) << "+v_RAISE\n"
      << "  variable       SUPPLY_HI equal " << num(base + s.supply_height) << "+v_RAISE\n"
      << "  if \"${L} > 1\" then &\n"
      << "    \"region supply${L} block " << num(s.supply_x0) << " " << num(s.supply_x1) << " "
      << num(d.lower[1]) << " " << num(d.upper[1]) << " ${SUPPLY_LO} ${SUPPLY_HI} units box volume_limit 1e-20\" &\n"
      << "    \"fix supply all insert/pack seed " << prime_at_least(10007 + 7919 * s.seed)
      << " distributiontemplate supply_psd maxattempt 1000 insert_every once overlapcheck yes all_in "
         "yes " << fill << " region supply${L}\" &\n"
      << "    \"run 1\" \"unfix supply\"\n";
}

// One layer's tool: the STL raised by the plate's descent, its wall, its motion.
void layer_body(std::ostringstream& out, const Bed& bed, const DeckLaws& laws, const SpreadDeck& s,
                const LiggghtsContact& c, const Names& names) {
  const DeckTool& t = s.tool;
  const Domain& d = bed.domain;
  out << "  fix            tool all mesh/surface file " << names.tool << " type " << type_count(bed) + 1
      << " move 0 0 ${RAISE}\n"
      << "  " << mesh_wall(s, c)
      << "  run            " << steps_of(t.delay, laws.dt) << "  # recoater.delay: the supply settles\n"
      << "  fix            push all move/mesh mesh tool linear " << num(t.speed) << " 0 0\n";
  if (t.roller && t.omega != 0) {
    out << "  variable       AXIS_Z equal " << num(d.lower[2] + t.gap + t.rounding) << "+v_RAISE\n";
    // deposit's spin is about +y (right-handed); LIGGGHTS's rotate turns about `axis` with the
    // period, superposed on the translation defined before it
    out << "  fix            spin all move/mesh mesh tool rotate origin " << num(t.start) << " "
        << num(0.5 * (d.lower[1] + d.upper[1])) << " ${AXIS_Z} axis 0 " << (t.omega > 0 ? 1 : -1) << " 0 period "
        << num(2 * std::numbers::pi / std::abs(t.omega)) << "\n";
  }
  out << "  run            " << steps_of((t.end - t.start) / t.speed, laws.dt)
      << "  # the travel from recoater.start to recoater.end\n";
  if (t.roller && t.omega != 0) out << "  unfix          spin\n";
  out << "  unfix          push\n"
      << "  run            " << steps_of(t.settle, laws.dt) << "  # recoater.settle\n";
  if (s.remove_overflow) {
    out << "  # the overflow: centres past the tool's front where it stopped\n"
        << "  region         overflow${L} block " << num(t.end + t.half_width + t.rounding) << " "
        << num(d.upper[0]) << " " << num(d.lower[1]) << " " << num(d.upper[1]) << " " << num(d.lower[2])
        << " " << num(d.upper[2]) << " units box\n"
        << "  delete_atoms   region overflow${L}\n";
  }
  out << "  write_dump     all custom ${LAYER_DUMP}-${L}.lammpstrj id type x y z vx vy vz radius modify "
         "sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"\n"
      << "  unfix          tool_wall\n"
      << "  unfix          tool\n";
}

// The thermo output and the head of the layer loop both engines' decks share (the same LAMMPS
// input syntax): about ten thermo rows a layer, and the rise of the tool and supply per layer.
void layer_loop_head(std::ostringstream& out, const DeckLaws& laws, const SpreadDeck& s,
                     const std::string& layer_dump) {
  out << "thermo_style   custom step atoms ke\n"
      << "thermo         " << std::max<std::uint64_t>(1, steps_of((s.tool.end - s.tool.start) / s.tool.speed, laws.dt) / 10)
      << "\nthermo_modify  lost ignore norm no\n\n"
      << "variable       NLAYERS index " << s.layers << "\n"
      << "variable       LAYER_DUMP index " << layer_dump << "\n"
      << "variable       L loop ${NLAYERS}\n"
      << "label          layer\n"
      << "  # the plate's descent: the tool (and the supply) rise instead, as in deposit\n"
      << "  variable       RAISE equal (${L}-1)*" << num(s.layer_thickness) << "\n";
}

std::string spread_body(const Bed& bed, const DeckLaws& laws, const SpreadDeck& s,
                        const LiggghtsContact& c, const Names& names, const DeckFiles& files,
                        const std::string& layer_dump) {
  std::ostringstream out;
  if (!s.floor.empty()) {
    out << "# The solid the powder is spread on (the fused top of the layers before), as an STL\n"
        << "fix            floor all mesh/surface file " << names.floor << " type " << type_count(bed) + 1 << "\n";
  }
  body_forces(out, laws);
  if (s.layers > 1) supply_templates(out, s, laws);
  layer_loop_head(out, laws, s, layer_dump);
  if (s.layers > 1) supply_of_layer(out, bed, s);
  layer_body(out, bed, laws, s, c, names);
  out << "next           L\n"
      << "jump           SELF layer\n"
      << "write_data     " << files.final_data << "\n";
  return out.str();
}


// ---- LAMMPS (29 Sep 2021): the tool as a region, its motion a function of the step ----

// The tool's travel and spin as equal-style variables of the step: at rest until step S0, then
// recoater.speed (and omega) for the NMOVE steps of the travel, then at rest at recoater.end
// (deposit's tool stops there). LAMMPS 29 Sep 2021 has no two-argument min/max: the clamp is
// made of its 0/1 comparisons.
void lammps_tool_motion(std::ostringstream& out, const DeckLaws& laws, const SpreadDeck& s) {
  const DeckTool& t = s.tool;
  const std::uint64_t moving = steps_of((t.end - t.start) / t.speed, laws.dt);
  out << "  variable       S0 equal $(step+" << steps_of(t.delay, laws.dt) << ")  # the travel's first step\n"
      << "  variable       S1 equal ${S0}+" << moving << "  # its end\n"
      << "  variable       MOVED equal (step>${S0})*(step<${S1})*(step-${S0})+(step>=${S1})*" << moving << "\n"
      << "  variable       TX equal (step<${S1})*" << num(t.speed * laws.dt) << "*v_MOVED+(step>=${S1})*"
      << num(t.end - t.start) << "\n";
  // deposit's spin is about +y (right-handed), as the region's rotate about (0 1 0); it turns
  // while the roller travels, as the LIGGGHTS deck's move/mesh rotate
  if (t.roller && t.omega != 0) out << "  variable       SPIN equal " << num(t.omega * laws.dt) << "*v_MOVED\n";
}

// The tool of one layer as a region (side out: the particles stay outside it) raised by RAISE:
// the blade a block from the gap up through the box's top, the roller a cylinder along y.
void lammps_tool_region(std::ostringstream& out, const Bed& bed, const SpreadDeck& s) {
  const DeckTool& t = s.tool;
  const Domain& d = bed.domain;
  const double bottom = d.lower[2] + t.gap;
  if (t.roller) {
    const double axis = bottom + t.rounding;
    out << "  region         tool cylinder y " << num(t.start) << " $(" << num(axis) << "+v_RAISE) "
        << num(t.rounding) << " INF INF side out units box move v_TX NULL NULL";
    if (t.omega != 0)
      out << " rotate v_SPIN " << num(t.start) << " " << num(0.5 * (d.lower[1] + d.upper[1])) << " $("
          << num(axis) << "+v_RAISE) 0 1 0";
    out << "\n";
    return;
  }
  out << "  region         tool block " << num(t.start - t.half_width) << " " << num(t.start + t.half_width)
      << " INF INF $(" << num(bottom) << "+v_RAISE) INF side out units box move v_TX NULL NULL\n";
}

// The supply of layers 2.. by fix pour (LAMMPS 29 Sep 2021's create_atoms random has no overlap
// check): the PSD's bins as its poly diameters (number fractions), all in one insertion (pour
// counts a box thinner than 1 length unit as 1 thick, so in SI units its volume fraction never
// limits the count), then `run 1` as the LIGGGHTS deck's insert/pack. Pour draws each particle's
// height towards the region's top and ends the insertion at the first particle that finds no room
// at its height: it may insert fewer than asked (LAMMPS warns "Less insertions than requested";
// docs/decks.md has the count on the test scene), and it starts them at the speed of a fall from
// the region's top.
constexpr int kPourAttempts = 1000;

void lammps_supply(std::ostringstream& out, const Bed& bed, const DeckLaws& laws, const SpreadDeck& s) {
  const Domain& d = bed.domain;
  double total = 0, mean_volume = 0;
  for (const auto& [r, w] : s.psd_bins) total += w;
  for (const auto& [r, w] : s.psd_bins) mean_volume += w / total * sphere_volume(r);
  const auto count = s.supply_count > 0 ? s.supply_count
                                        : static_cast<std::size_t>(std::llround(s.supply_volume / mean_volume));
  const double base = d.lower[2] + s.tool.gap - s.layer_thickness;  // + (L - 1) t: RAISE
  std::string poly = fmt::format("diam poly {}", s.psd_bins.size());
  for (const auto& [r, w] : s.psd_bins) poly += fmt::format(" {} {}", num(2 * r), num(w / total));
  out << "  # layer 2..: the supply on the powder the tool of the layer before left, by fix pour\n"
      << "  variable       SUPPLY_LO equal " << num(base) << "+v_RAISE\n"
      << "  variable       SUPPLY_HI equal " << num(base + s.supply_height) << "+v_RAISE\n"
      << "  if \"${L} > 1\" then &\n"
      << "    \"region supply block " << num(s.supply_x0) << " " << num(s.supply_x1) << " " << num(d.lower[1]) << " "
      << num(d.upper[1]) << " ${SUPPLY_LO} ${SUPPLY_HI} units box\" &\n"
      << "    \"fix supply all pour " << count << " 1 $(" << 10007 + 7919 * s.seed << "+v_L) region supply " << poly
      << " dens " << num(laws.density.front()) << " " << num(laws.density.front()) << " vol 1 " << kPourAttempts
      << "\" &\n"
      << "    \"run 1\" \"unfix supply\" \"region supply delete\"\n";
}

void lammps_layer_body(std::ostringstream& out, const Bed& bed, const DeckLaws& laws, const SpreadDeck& s,
                       const std::string& wall_contact) {
  const DeckTool& t = s.tool;
  const Domain& d = bed.domain;
  lammps_tool_motion(out, laws, s);
  lammps_tool_region(out, bed, s);
  out << "  fix            tool_wall all wall/gran/region granular " << wall_contact << " region tool\n"
      << "  run            " << steps_of(t.delay, laws.dt) << "  # recoater.delay: the supply settles\n"
      << "  run            " << steps_of((t.end - t.start) / t.speed, laws.dt)
      << "  # the travel from recoater.start to recoater.end\n"
      << "  run            " << steps_of(t.settle, laws.dt) << "  # recoater.settle\n";
  if (s.remove_overflow) {
    out << "  # the overflow: centres past the tool's front where it stopped\n"
        << "  region         overflow block " << num(t.end + t.half_width + t.rounding) << " " << num(d.upper[0])
        << " INF INF INF INF units box\n"
        << "  delete_atoms   region overflow\n"
        << "  region         overflow delete\n";
  }
  out << "  write_dump     all custom ${LAYER_DUMP}-${L}.lammpstrj id type x y z vx vy vz radius modify sort id "
         "format float %.17g\n"
      << "  unfix          tool_wall\n"
      << "  region         tool delete\n";
}

std::string lammps_spread_body(const Bed& bed, const DeckLaws& laws, const SpreadDeck& s,
                               const std::string& wall_contact, const DeckFiles& files,
                               const std::string& layer_dump) {
  std::ostringstream out;
  body_forces(out, laws);
  layer_loop_head(out, laws, s, layer_dump);
  if (s.layers > 1) lammps_supply(out, bed, laws, s);
  lammps_layer_body(out, bed, laws, s, wall_contact);
  out << "next           L\n"
      << "jump           SELF layer\n"
      << "write_data     " << files.final_data << "\n";
  return out.str();
}

// What a LAMMPS spread cannot take, refused (InputError) rather than approximated.
void check_lammps_spread(const SpreadDeck& s) {
  if (!s.floor.empty())
    throw InputError("--export-deck: lammps with a raised floor (the fused top of a spread layer file; accepted: "
                     "liggghts, which takes it as an STL: LAMMPS 29 Sep 2021 has no granular wall of a height map)");
  if (!s.tool.roller && s.tool.rounding > 0)
    throw InputError(fmt::format("recoater.edge-radius: {:g} m with --export-deck lammps (accepted: 0, or "
                                 "--export-deck liggghts: the LAMMPS deck's blade is a sharp-edged region block)",
                                 s.tool.rounding));
}
}  // namespace

std::string spread_tool_stl(const std::string& data_path) {
  return folder_of(data_path) + stem_of(data_path) + ".tool.stl";
}

std::string spread_floor_stl(const std::string& data_path) {
  return folder_of(data_path) + stem_of(data_path) + ".floor.stl";
}

std::string spread_layer_dump(const std::string& data_path, std::uint64_t layer, DeckEngine engine) {
  return fmt::format("{}{}.{}.layer-{}.lammpstrj", folder_of(data_path), stem_of(data_path),
                     deck_engine_name(engine), layer);
}

namespace {

// The LIGGGHTS deck's body and its meshes, committed with the deck and the data file.
void write_liggghts_spread(const Bed& bed, const DeckLaws& laws, const SpreadDeck& s, const std::string& data_path,
                           const DeckFiles& files, std::ostringstream& deck) {
  const Names names{name_of(spread_tool_stl(data_path)), name_of(spread_floor_stl(data_path))};
  const LiggghtsContact contact = liggghts_laws(deck, bed, laws);
  deck << spread_body(bed, laws, s, contact, names, files, stem_of(data_path) + ".liggghts.layer");
  const Domain& d = bed.domain;
  const double margin = kInset * (d.upper[1] - d.lower[1]);
  const std::vector<Triangle> tool =
      extrude(tool_section(s.tool, d.lower[2] + s.tool.gap, tool_top(d, s)), s.tool.start,
              d.lower[1] + margin, d.upper[1] - margin);
  CommitTogether together;  // the deck, the data file and the meshes, or none of them
  write_text_file(spread_tool_stl(data_path), stl_text(tool, "tool"));
  if (!s.floor.empty()) write_text_file(spread_floor_stl(data_path), stl_text(floor_mesh(s.floor, d), "floor"));
  write_deck_files(bed, laws, data_path, files.input, deck.str());
  together.commit();
}

}  // namespace

void write_spread_deck(const Bed& bed, const DeckLaws& laws, const SpreadDeck& s,
                       const std::string& data_path) {
  check(bed, laws, data_path);
  check_spread(bed, laws, s);
  const bool lammps = s.engine == DeckEngine::lammps;
  if (lammps) check_lammps_spread(s);
  const char* engine = deck_engine_name(s.engine);
  DeckFiles files = deck_files(data_path, s.engine);
  files.dump.clear();  // each layer's dump instead (spread_layer_dump)
  std::ostringstream deck;
  header(deck, bed, laws, s.engine, name_of(data_path), files);
  deck << "# A spread (docs/decks.md \"Spreading decks\"): the recoater "
       << (lammps ? "(a moving region, fix wall/gran/region)" : name_of(spread_tool_stl(data_path)))
       << " moves along +x at recoater.speed, layer after layer;\n#   each layer's bed is written to "
       << stem_of(data_path) << "." << engine << ".layer-L.lammpstrj (id type x y z vx vy vz radius at %.17g), the\n#   end to "
       << files.final_data << ". SI units.\n";
  setup(deck, bed, laws, s.engine, name_of(data_path), files);
  if (!lammps) return write_liggghts_spread(bed, laws, s, data_path, files, deck);
  const std::string wall_contact = lammps_laws(deck, bed, laws);
  deck << lammps_spread_body(bed, laws, s, wall_contact, files, stem_of(data_path) + ".lammps.layer");
  write_deck_files(bed, laws, data_path, files.input, deck.str());
}

}  // namespace powderbed::bed
