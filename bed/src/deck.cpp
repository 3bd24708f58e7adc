// LAMMPS and LIGGGHTS input decks for a bed (deck.hpp, docs/decks.md).
#include "powderbed/bed/deck.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <numbers>
#include <sstream>

#include "deck_detail.hpp"
#include "io_detail.hpp"
#include "powderbed/bed/critical_damping.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/bed/deck_damping.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/softening.hpp"

namespace powderbed::bed {

DeckEngine parse_deck_engine(const std::string& text, const std::string& option) {
  if (text == "lammps") return DeckEngine::lammps;
  if (text == "liggghts") return DeckEngine::liggghts;
  throw InputError(option + ": '" + text + "' (accepted: lammps, liggghts)");
}

const char* deck_engine_name(DeckEngine engine) {
  return engine == DeckEngine::lammps ? "lammps" : "liggghts";
}

namespace deck_detail {

std::string folder_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

std::string name_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// The data file's name without its extension.
std::string stem_of(const std::string& path) {
  const std::string name = name_of(path);
  const auto dot = name.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

// %.17g: every double in a deck reads back as the same double.
std::string num(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

namespace {

// E* of two bodies (hertz_normal.hpp's effective_modulus; bed/ does not depend on dem/).
double effective_modulus(double e1, double nu1, double e2, double nu2) {
  return 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
}

}  // namespace

std::size_t type_count(const Bed& bed) {
  if (bed.material.empty()) return 1;
  return static_cast<std::size_t>(*std::max_element(bed.material.begin(), bed.material.end())) + 1;
}

void check(const Bed& bed, const DeckLaws& laws, const std::string& data_path) {
  bed.validate(data_path);
  if (bed.domain.dimension != 3)
    throw InputError(data_path + ": a 2D bed (accepted for a deck: 3D beds)");
  if (bed.n() == 0) throw InputError(data_path + ": an empty bed (accepted: one particle or more)");
  if (!(laws.dt > 0) || !std::isfinite(laws.dt))
    throw InputError("deck: time step " + num(laws.dt) + " (accepted: dt > 0 s)");
  if (laws.law != "hertz" && laws.law != "linear")
    throw InputError("deck: contact law '" + laws.law + "' (accepted: hertz, linear)");
  const bool hertz = laws.law == "hertz";
  if (hertz && (!(laws.young > 0) || !(laws.wall_young > 0) || !(laws.young_scale > 0)))
    throw InputError("deck: Hertz law needs E > 0, wall E > 0 and young-scale > 0");
  if (!hertz && !(laws.stiffness > 0))
    throw InputError("deck: linear law needs contact.stiffness > 0 (N/m)");
  const std::size_t types = type_count(bed);
  if (laws.density.size() != 1 && laws.density.size() != types)
    throw InputError(
        fmt::format("deck: {} densities for {} materials (accepted: one, or one per material)",
                    laws.density.size(), types));
  if (laws.steps == 0) throw InputError("deck: 0 steps (accepted: N >= 1)");
}

namespace {

// G* of two bodies (mindlin_tangential.hpp's effective_shear_modulus; bed/ does not depend on dem/).
double effective_shear(double e1, double nu1, double e2, double nu2) {
  auto g = [](double e, double nu) { return e / (2.0 * (1.0 + nu)); };
  return 1.0 / ((2.0 - nu1) / g(e1, nu1) + (2.0 - nu2) / g(e2, nu2));
}

struct Stiffness {
  double pair = 0;  // LAMMPS hertz / hooke coefficient: 4/3 E* (Pa) or k_n (N/m)
  double wall = 0;
  double pair_shear = 0, wall_shear = 0;  // Mindlin's 8 G* (Pa; Hertz law only)
};

Stiffness stiffness(const DeckLaws& laws) {
  if (laws.law == "linear") return {laws.stiffness, laws.stiffness, 0, 0};
  const double e = softened_modulus(laws.young, laws.young_scale);
  const double ew = softened_modulus(laws.wall_young, laws.young_scale);
  return {4.0 / 3.0 * effective_modulus(e, laws.poisson, e, laws.poisson),
          4.0 / 3.0 * effective_modulus(e, laws.poisson, ew, laws.wall_poisson),
          8.0 * effective_shear(e, laws.poisson, e, laws.poisson),
          8.0 * effective_shear(e, laws.poisson, ew, laws.wall_poisson)};
}

double max_diameter(const Bed& bed) {
  return 2 * *std::max_element(bed.radius.begin(), bed.radius.end());
}

}  // namespace

void header(std::ostringstream& out, const Bed& bed, const DeckLaws& laws, DeckEngine engine,
            const std::string& data_name, const DeckFiles& files) {
  const bool lammps = engine == DeckEngine::lammps;
  const char* exe = lammps ? "lmp" : "liggghts";
  out << "# " << (lammps ? "LAMMPS" : "LIGGGHTS") << " input deck for " << data_name << ", written by "
      << (bed.provenance.created_by.empty() ? "powderbed" : bed.provenance.created_by) << "\n"
      << "# Run in this folder: " << exe << " -in " << name_of(files.input)
      << (files.dump.empty() ? "" : " [-var NSTEPS N] [-var DUMP_EVERY K]") << ", or mpirun -np 4 "
      << exe << " -in " << name_of(files.input) << "\n";
  // a spreading deck (no dump of its own) says what it writes after its loop
  if (!files.dump.empty())
    out << "# Writes " << files.dump << " (id type x y z vx vy vz radius at %.17g: bedconv reads it "
        << "back exactly) and " << files.final_data << ". SI units.\n";
  out << "# Where each number comes from:\n";
  for (const auto& line : laws.origin) out << "#   " << line << "\n";
  out << "# Damping: deposit's dashpot c = 2 zeta sqrt(m* k_n) (k_n = dF/d delta); ";
  if (lammps) {
    out << "LAMMPS's damping tsuji gives eta = alpha(e) sqrt(m* K) with K = 4/3 E* a (hertz) or k "
        << "(hooke),\n#   so alpha(e) = zeta sqrt(6) (hertz) or 2 zeta (hooke); e below solves "
        << "Tsuji's alpha polynomial (docs/decks.md, measured in docs/results/deck-damping.md).\n";
  } else {
    out << "LIGGGHTS's hertz gives gamma_n = 2 sqrt(5/6) |beta| sqrt(m* S_n),\n#   S_n = 2 E* a = "
        << "k_n, so beta = zeta / sqrt(5/6) and e = exp(-pi b / sqrt(1 - b^2)), b = zeta / "
        << "sqrt(5/6) (docs/decks.md, measured in docs/results/deck-damping.md).\n";
  }
  if (laws.rotation) {
    out << "# Rotation (fix nve/sphere) as deposit's spread; tangential force: "
        << (laws.tangential_history ? "the history spring capped at mu F_n (friction.model = history)"
                                    : "viscous, capped at Coulomb mu F_n (deposit's regularised sliding)")
        << (laws.rolling > 0 ? (lammps ? "; rolling resistance: sds, deposit's EPSD (Ai et al. 2011) with its spring "
                                         "at a 1e-3 R overlap (docs/decks.md)"
                                       : "; rolling resistance: epsd (Ai et al. 2011), deposit's model")
                             : "")
        << ".\n";
    return;
  }
  out << "# Translation only (fix nve): deposit integrates no rotation; tangential force: viscous, "
         "capped at Coulomb mu F_n\n"
         "#   (the closest to deposit's regularised sliding; identical while sliding).\n";
}

// Deck variables and the system set-up up to read_data.
void setup(std::ostringstream& out, const Bed& bed, const DeckLaws& laws, DeckEngine engine,
           const std::string& data_name, const DeckFiles& files) {
  const bool lammps = engine == DeckEngine::lammps;
  const Domain& d = bed.domain;
  if (!files.dump.empty())  // the run's length and snapshots (a spreading deck's are its tool's)
    out << "\nvariable NSTEPS     index " << laws.steps << "\n"
        << "variable DUMP_EVERY index ${NSTEPS}\n"
        << "variable DUMP       index " << files.dump << "\n"
        << "variable FINAL      index " << files.final_data << "\n";
  out << "\nunits          si\n"
      << "atom_style     " << (lammps ? "sphere" : "granular") << "\n"
      << "atom_modify    map array\n"
      << "dimension      3\n"
      << "boundary       " << (d.periodic[0] ? "p" : "f") << " " << (d.periodic[1] ? "p" : "f")
      << " " << (d.periodic[2] ? "p" : "f") << "\n";
  if (lammps) {
    out << "comm_modify    vel yes\n";
  } else {
    out << "newton         off\ncommunicate    single vel yes\n"
        << "hard_particles yes  # E above 1 GPa\n";
    // LIGGGHTS refuses E < 5 MPa in SI units unless told (a young-scale of 1e5 softens 316L to 1.9 MPa)
    if (laws.law == "hertz" && softened_modulus(std::min(laws.young, laws.wall_young), laws.young_scale) < 5e6)
      out << "soft_particles yes  # E / young-scale below 5 MPa\n";
  }
  out << "read_data      " << data_name << "\n"
      << "neighbor       " << num(0.1 * max_diameter(bed)) << " bin  # skin 0.1 x the largest diameter\n"
      << "neigh_modify   delay 0\n\n";
}

namespace {

// The overlap at which a spread deck's rolling spring takes deposit's stiffness (LAMMPS's sds
// spring is constant, deposit's k_r grows with k_n = 2 E* sqrt(R* delta)): 1e-3 of the mean
// radius, the overlap of a particle under some ten others at E / 1e4 (docs/decks.md).
constexpr double kRollingOverlap = 1e-3;

// One side of a contact for LAMMPS: its stiffnesses, and for the rolling spring the reduced
// radius and rolling inertia of two particles of the mean size (or one against a wall).
struct LammpsSide {
  double k = 0, shear = 0;         // Stiffness's pair or wall entries
  double reduced_radius = 0, rolling_inertia = 0;
};

// Static friction (a spread's friction.model = history) as deposit's spring: Mindlin's
// k_t = 8 G* a (Hertz) or 2/7 k_n (linear). LAMMPS's tangential dashpot is x_gamma_t times the
// normal one, which the tsuji mapping makes 2 zeta sqrt(m* k_n); deposit's is 2 zeta sqrt(m* k_t),
// so x_gamma_t = sqrt(k_t / k_n). Sliding friction: the drop deck's viscous, capped force.
std::string lammps_tangential(const DeckLaws& laws, const LammpsSide& side) {
  const std::string mu = num(laws.friction);
  if (!laws.tangential_history) return " tangential linear_nohistory 1 " + mu;
  if (laws.law == "linear")
    return " tangential linear_history " + num(2.0 / 7.0 * laws.stiffness) + " " + num(std::sqrt(2.0 / 7.0)) + " " + mu;
  return " tangential mindlin " + num(side.shear) + " " + num(std::sqrt(side.shear / (1.5 * side.k))) + " " + mu;
}

// deposit's EPSD rolling resistance as LAMMPS's sds: the torque is R* times the sds force of the
// rolling displacement R* theta, so k_roll = k_r / R*^2 = 2.25 mu_r^2 k_n (k_n at kRollingOverlap
// for Hertz), the cap mu_r R* F_n is deposit's, and gamma_roll = C_r / R*^2 =
// 2 zeta sqrt(I_r k_r) / R*^2 for particles of the mean size.
std::string lammps_rolling(const DeckLaws& laws, const LammpsSide& side, double mean_radius) {
  if (laws.rolling <= 0) return "";
  const double k_n = laws.law == "linear"
                         ? laws.stiffness
                         : 2.0 * 0.75 * side.k * std::sqrt(side.reduced_radius * kRollingOverlap * mean_radius);
  const double k_roll = 2.25 * laws.rolling * laws.rolling * k_n;
  const double r = side.reduced_radius;
  const double gamma = 2.0 * laws.damping_ratio * std::sqrt(side.rolling_inertia * k_roll * r * r) / (r * r);
  return " rolling sds " + num(k_roll) + " " + num(gamma) + " " + num(laws.rolling);
}

// LAMMPS pair_style granular / fix wall/gran granular arguments after the style: the normal
// law with its damping, the tangential law (and a spread's rolling resistance) and the clamp.
std::string lammps_contact(const DeckLaws& laws, const LammpsSide& side, double mean_radius) {
  const bool hertz = laws.law == "hertz";
  std::string s = std::string(hertz ? "hertz " : "hooke ") + num(side.k) + " ";
  if (laws.damping_ratio > 0) {
    s += num(lammps_tsuji_input(laws.damping_ratio, hertz, "material.damping")) + " damping tsuji";
  } else {
    s += "0 damping velocity";
  }
  s += lammps_tangential(laws, side) + lammps_rolling(laws, side, mean_radius);
  if (hertz) s += " limit_damping";  // deposit's Hertz force never pulls; its linear one may
  return s;
}

}  // namespace

MeanParticle mean_particle(const Bed& bed, const DeckLaws& laws) {
  double mass = 0, radius = 0;
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const std::size_t t = bed.material.empty() ? 0 : bed.material[i];
    const double rho = laws.density.size() == 1 ? laws.density[0] : laws.density[t];
    mass += rho * sphere_volume(bed.radius[i]);
    radius += bed.radius[i];
  }
  const double n = static_cast<double>(bed.n());
  return {mass / n, radius / n};
}

std::string lammps_laws(std::ostringstream& out, const Bed& bed, const DeckLaws& laws) {
  const Stiffness k = stiffness(laws);
  const MeanParticle p = mean_particle(bed, laws);
  // rolling_resistance.hpp's I_r: 1.4 m r^2 per particle, halved for two alike, none of a wall's
  const LammpsSide pair{k.pair, k.pair_shear, 0.5 * p.radius, 0.7 * p.mass * p.radius * p.radius};
  const LammpsSide wall{k.wall, k.wall_shear, p.radius, 1.4 * p.mass * p.radius * p.radius};
  if (laws.contact) {
    out << "pair_style     granular\n"
        << "pair_coeff     * * " << lammps_contact(laws, pair, p.radius) << "\n";
  } else {
    out << "pair_style     none  # particle-particle contact is off in the scene\n";
  }
  const std::string wall_contact = lammps_contact(laws, wall, p.radius);
  if (!laws.walls) return wall_contact;
  const Domain& d = bed.domain;
  for (int a = 0; a < 3; ++a) {
    if (d.periodic[a]) continue;
    const char axis = "xyz"[a];
    out << "fix            wall_" << axis << " all wall/gran granular " << wall_contact
        << " " << axis << "plane " << num(d.lower[a]) << " " << num(d.upper[a]) << "\n";
  }
  return wall_contact;
}

// LIGGGHTS: per-type properties (the walls are the last type) and gran / wall/gran styles;
// returns the model and settings every wall/gran (primitive or mesh) takes.
LiggghtsContact liggghts_laws(std::ostringstream& out, const Bed& bed, const DeckLaws& laws) {
  const std::size_t types = type_count(bed) + 1;
  const std::string n = std::to_string(types);
  const bool hertz = laws.law == "hertz";
  auto per_type = [&](const char* name, double particles, double wall) {
    out << "fix            prop_" << name << " all property/global " << name << " peratomtype";
    for (std::size_t t = 0; t + 1 < types; ++t) out << " " << num(particles);
    out << " " << num(wall) << "\n";
  };
  // A type-pair matrix: `pair` between particle types, `wall` between a particle type and the
  // walls' (the last) type.
  auto per_pair_wall = [&](const char* name, double pair, double wall) {
    out << "fix            prop_" << name << " all property/global " << name << " peratomtypepair " << n;
    for (std::size_t i = 0; i < types; ++i)
      for (std::size_t j = 0; j < types; ++j) out << " " << num(i + 1 == types || j + 1 == types ? wall : pair);
    out << "\n";
  };
  auto per_pair = [&](const char* name, double value) { per_pair_wall(name, value, value); };
  // LIGGGHTS's wall/gran takes the normal model's settings after the wall's geometry, its pair
  // style before it.
  std::string model, settings;
  if (hertz) {
    per_type("youngsModulus", softened_modulus(laws.young, laws.young_scale),
             softened_modulus(laws.wall_young, laws.young_scale));
    per_type("poissonsRatio", laws.poisson, laws.wall_poisson);
    per_pair("coefficientRestitution", liggghts_hertz_restitution(laws.damping_ratio, "material.damping"));
    model = "model hertz";
    settings = " limitForce on";  // deposit's Hertz force never pulls
  } else {
    // hooke/stiffness has one absolute dashpot per type pair: 2 zeta sqrt(m* k_n) for the
    // reduced mass of two particles of the mean mass, and of one against a wall (m* = m), exact
    // for equal particles.
    const double mean = mean_particle(bed, laws).mass;
    const double gamma = critical_damping(laws.damping_ratio, 0.5 * mean, laws.stiffness);
    const double gamma_wall = critical_damping(laws.damping_ratio, mean, laws.stiffness);
    out << "# linear law: one dashpot per type pair, " << num(gamma) << " N s/m for two particles of "
        << "the mean mass " << num(mean) << " kg, " << num(gamma_wall) << " N s/m against a wall; "
        << "deposit's varies with each pair's m*\n";
    per_pair("kn", laws.stiffness);
    per_pair("kt", laws.stiffness);
    per_pair_wall("gamman_abs", gamma, gamma_wall);
    per_pair_wall("gammat_abs", gamma, gamma_wall);
    model = "model hooke/stiffness";
    settings = " absolute_damping on";
  }
  per_pair("coefficientFriction", laws.friction);
  model += laws.tangential_history ? " tangential history" : " tangential no_history";
  if (laws.rolling > 0) {
    // epsd: C_r = eta_r 2 sqrt(I_r k_r), deposit's 2 zeta sqrt(I_r k_r) for eta_r = zeta
    per_pair("coefficientRollingFriction", laws.rolling);
    per_pair("coefficientRollingViscousDamping", laws.damping_ratio);
    model += " rolling_friction epsd";
  }
  if (laws.contact) {
    out << "pair_style     gran " << model << settings << "\n"
        << "pair_coeff     * *\n";
  } else {
    out << "pair_style     none  # particle-particle contact is off in the scene\n";
  }
  if (!laws.walls) return {model, settings};
  const Domain& d = bed.domain;
  for (int a = 0; a < 3; ++a) {
    if (d.periodic[a]) continue;
    const char axis = "xyz"[a];
    for (int side = 0; side < 2; ++side) {
      out << "fix            wall_" << axis << (side ? "hi" : "lo") << " all wall/gran " << model
          << " primitive type " << types << " " << axis << "plane "
          << num(side ? d.upper[a] : d.lower[a]) << settings << "\n";
    }
  }
  return {model, settings};
}

void body_forces(std::ostringstream& out, const DeckLaws& laws) {
  if (laws.gravity > 0)
    out << "fix            gravity all gravity " << num(laws.gravity) << " vector 0 0 -1\n";
  if (laws.viscosity > 0) {
    const double c = 6 * std::numbers::pi * laws.viscosity;
    out << "# Stokes drag -6 pi mu_f r v on each particle (mu_f = " << num(laws.viscosity) << " Pa s)\n"
        << "compute        radius all property/atom radius\n"
        << "variable       drag_x atom " << num(-c) << "*c_radius*vx\n"
        << "variable       drag_y atom " << num(-c) << "*c_radius*vy\n"
        << "variable       drag_z atom " << num(-c) << "*c_radius*vz\n"
        << "fix            drag all addforce v_drag_x v_drag_y v_drag_z\n";
  }
  out << "fix            move all " << (laws.rotation ? "nve/sphere" : "nve") << "\n"
      << "timestep       " << num(laws.dt) << "\n\n";
}

namespace {

void forces_and_run(std::ostringstream& out, const DeckLaws& laws, DeckEngine engine) {
  const bool lammps = engine == DeckEngine::lammps;
  body_forces(out, laws);
  out << "dump           snapshots all custom ${DUMP_EVERY} ${DUMP} id type x y z vx vy vz radius\n";
  // Each snapshot's time for `bedconv DUMP --all-snapshots`: LAMMPS writes it (ITEM: TIME);
  // LIGGGHTS 3.8 cannot, and bedconv takes the `timestep` above from this deck (its DUMP).
  if (lammps) {
    out << "dump_modify    snapshots sort id format float %.17g time yes\n";
  } else {
    out << "dump_modify    snapshots sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"\n"
        << "# LIGGGHTS 3.8 prints a dump's box bounds with %g; ${FINAL} has them exactly\n"
        << "# and no ITEM: TIME: bedconv DUMP --all-snapshots reads the timestep above\n";
  }
  out << "thermo_style   custom step atoms ke\n"
      << "thermo         ${NSTEPS}\n"
      << "run            ${NSTEPS}\n"
      << "write_data     ${FINAL}\n";
}

}  // namespace

}  // namespace deck_detail

using namespace deck_detail;

DeckFiles deck_files(const std::string& data_path, DeckEngine engine) {
  const std::string stem = stem_of(data_path);
  const std::string e = deck_engine_name(engine);
  return {folder_of(data_path) + "in." + stem + "." + e, stem + "." + e + ".lammpstrj",
          stem + "." + e + ".final.data"};
}

void write_deck(const Bed& bed, const DeckLaws& laws, DeckEngine engine,
                const std::string& data_path) {
  check(bed, laws, data_path);
  const DeckFiles files = deck_files(data_path, engine);
  const std::string data_name = name_of(data_path);
  std::ostringstream deck;
  header(deck, bed, laws, engine, data_name, files);
  setup(deck, bed, laws, engine, data_name, files);
  if (engine == DeckEngine::lammps) lammps_laws(deck, bed, laws);
  else liggghts_laws(deck, bed, laws);
  forces_and_run(deck, laws, engine);
  write_deck_files(bed, laws, data_path, files.input, deck.str());
}

namespace deck_detail {

void write_deck_files(const Bed& bed, const DeckLaws& laws, const std::string& data_path,
                      const std::string& input_path, const std::string& text) {
  LammpsDataOptions data;
  data.type_density = laws.density;
  data.extra_types = 1;
  data.comments = {"atom type " + std::to_string(type_count(bed) + 1) +
                   " holds no atoms: the walls' material (LIGGGHTS wall/gran primitive type)"};
  detail::AtomicFile input(input_path);
  detail::write_text(input.temp_path(), input_path, text);
  write_lammps_data(bed, data_path, data);
  input.commit();
}

}  // namespace deck_detail

}  // namespace powderbed::bed
