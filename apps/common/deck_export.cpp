// Deposit scenes as LAMMPS / LIGGGHTS deck laws (deck_export.hpp).
#include "common/deck_export.hpp"

#include <algorithm>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "powderbed/bed/deck_damping.hpp"
#include "powderbed/bed/errors.hpp"

namespace powderbed::app {

namespace {

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

double to_number(const std::string& key, const std::string& value, const std::string& source) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != value.size() || value.empty())
    throw InputError(fmt::format("{}: {} = '{}' (accepted: a number)", source, key, value));
  return v;
}

bool to_bool(const std::string& key, const std::string& value, const std::string& source) {
  if (value == "true" || value == "1" || value == "on" || value == "yes") return true;
  if (value == "false" || value == "0" || value == "off" || value == "no") return false;
  throw InputError(fmt::format("{}: {} = '{}' (accepted: true, false)", source, key, value));
}

void note(DeckScene& s, const std::string& key, const std::string& source) {
  auto it = std::find_if(s.origin.begin(), s.origin.end(), [&](auto& kv) { return kv.first == key; });
  if (it == s.origin.end()) s.origin.emplace_back(key, source);
  else it->second = source;
}

std::string origin_of(const DeckScene& s, const std::string& key) {
  for (const auto& [k, v] : s.origin)
    if (k == key) return v;
  return "default of deposit (316L, Ganeriwala & Zohdi 2016 Table 2; argon)";
}

std::string g17(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

}  // namespace

void apply_scene_text(const std::string& ini, const std::string& source, DeckScene& s) {
  std::istringstream in(ini);
  std::string line, section;
  dem::Scene& sc = s.scene;
  while (std::getline(in, line)) {
    line = trim(line.substr(0, std::min(line.find('#'), line.find(';'))));
    if (line.empty()) continue;
    if (line.front() == '[' && line.back() == ']') {
      section = trim(line.substr(1, line.size() - 2));
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    std::string key = trim(line.substr(0, eq));
    if (!section.empty()) key = section + "." + key;
    const std::string value = trim(line.substr(eq + 1));
    auto num = [&] { return to_number(key, value, source); };
    bool used = true;
    if (key == "material.young") sc.material.young = num();
    else if (key == "material.poisson") sc.material.poisson = num();
    else if (key == "material.density") sc.material.density = num();
    else if (key == "material.damping") sc.material.damping = num();
    else if (key == "material.friction") sc.material.friction = num();
    else if (key == "wall.young") sc.wall.young = num();
    else if (key == "wall.poisson") sc.wall.poisson = num();
    else if (key == "fluid.viscosity") sc.fluid_viscosity = num();
    else if (key == "gravity") sc.gravity = num();
    else if (key == "contact.law")
      sc.law = dem::parse_contact_law(value, fmt::format("{}: contact.law", source));
    else if (key == "contact.stiffness") sc.stiffness = num();
    else if (key == "young-scale") s.young_scale = num();
    else if (key == "dt") s.dt = num();
    else if (key.rfind("effects.", 0) == 0) {
      const unsigned bit = dem::effect_bit(std::string_view(key).substr(key.find('.') + 1));
      if (bit == 0) throw InputError(fmt::format("{}: unknown effect '{}'", source, key));
      if (to_bool(key, value, source)) sc.effects |= bit;
      else sc.effects &= ~bit;
    } else {
      used = false;
    }
    if (used) note(s, key, source);
  }
}

bed::DeckLaws deck_laws(const DeckScene& s, const std::vector<double>& density,
                        const std::string& density_origin, double dt, const std::string& dt_origin) {
  s.scene.validate();
  const dem::Scene& sc = s.scene;
  bed::DeckLaws laws;
  laws.law = dem::contact_law_name(sc.law);
  laws.young = sc.material.young;
  laws.poisson = sc.material.poisson;
  laws.wall_young = sc.wall.young;
  laws.wall_poisson = sc.wall.poisson;
  laws.young_scale = s.young_scale;
  laws.stiffness = sc.stiffness;
  laws.contact = sc.has(dem::kHertz);
  laws.walls = sc.has(dem::kWalls);
  laws.damping_ratio = sc.has(dem::kDamping) ? sc.material.damping : 0;
  laws.friction = sc.has(dem::kFriction) ? sc.material.friction : 0;
  laws.gravity = sc.has(dem::kGravity) ? sc.gravity : 0;
  laws.viscosity = sc.has(dem::kDrag) ? sc.fluid_viscosity : 0;
  laws.dt = dt;
  laws.density = density;
  auto line = [&](const std::string& what, const std::string& key) {
    laws.origin.push_back(what + ": " + origin_of(s, key));
  };
  std::string effects;
  for (const dem::EffectRow& effect : dem::kEffects)
    effects += std::string(" ") + effect.name + (sc.has(effect.bit) ? "=on" : "=off");
  laws.origin.push_back("effects" + effects + ": " + origin_of(s, "effects.hertz"));
  line("contact law " + laws.law, "contact.law");
  if (laws.law == "hertz") {
    line("E = " + g17(laws.young) + " Pa (material.young)", "material.young");
    line("nu = " + g17(laws.poisson) + " (material.poisson)", "material.poisson");
    line("wall E = " + g17(laws.wall_young) + " Pa, nu = " + g17(laws.wall_poisson) + " (wall.*)", "wall.young");
    line("young-scale S = " + g17(laws.young_scale) + " (the run's E is E / S)", "young-scale");
  } else {
    line("k_n = " + g17(laws.stiffness) + " N/m (contact.stiffness)", "contact.stiffness");
  }
  line("zeta = " + g17(sc.material.damping) + " (material.damping)", "material.damping");
  line("mu_d = " + g17(sc.material.friction) + " (material.friction)", "material.friction");
  line("g = " + g17(sc.gravity) + " m/s^2 (gravity)", "gravity");
  line("mu_f = " + g17(sc.fluid_viscosity) + " Pa s (fluid.viscosity, Stokes drag)", "fluid.viscosity");
  std::string rho;
  for (double r : density) rho += (rho.empty() ? "" : ", ") + g17(r);
  laws.origin.push_back("density per atom type = " + rho + " kg/m^3: " + density_origin);
  laws.origin.push_back("dt = " + g17(dt) + " s: " + dt_origin);
  laws.origin.push_back("walls: the bed's domain faces that are not periodic; boundary p/f: the bed's domain");
  return laws;
}

namespace {

std::string deck_data_path(const std::string& bed_path) {
  const auto slash = bed_path.find_last_of('/');
  const auto dot = bed_path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return bed_path + ".data";
  return bed_path.substr(0, dot) + ".data";
}

}  // namespace

std::vector<PathArg> deck_outputs(const std::string& engine, const std::string& bed_path) {
  const auto e = bed::parse_deck_engine(engine, "--export-deck");
  const std::string data = deck_data_path(bed_path);
  return {{"--export-deck", data}, {"--export-deck", bed::deck_files(data, e).input}};
}

void check_run_deck(const dem::Scene& scene, const std::string& engine) {
  if (!scene.has(dem::kDamping) || scene.material.damping == 0) return;
  const bool hertz = scene.law == dem::ContactLaw::hertz;
  if (bed::parse_deck_engine(engine, "--export-deck") == bed::DeckEngine::lammps)
    bed::lammps_tsuji_input(scene.material.damping, hertz, "material.damping (--export-deck lammps)");
  else if (hertz)
    bed::liggghts_hertz_restitution(scene.material.damping, "material.damping (--export-deck liggghts)");
}

bed::DeckLaws run_deck_laws(const dem::Scene& scene, double young_scale, double dt,
                            const std::string& made_by) {
  DeckScene s;
  s.scene = scene;
  s.young_scale = young_scale;
  s.dt = dt;
  for (const char* key : {"material.young", "material.poisson", "material.density", "material.damping",
                          "material.friction", "wall.young", "wall.poisson", "fluid.viscosity",
                          "gravity", "contact.law", "contact.stiffness", "young-scale", "effects.hertz"})
    s.origin.emplace_back(key, made_by);
  return deck_laws(s, {scene.material.density}, "material.density of the run", dt,
                   "the run's time step");
}

void export_run_deck(const bed::Bed& bed, const dem::Scene& scene, double young_scale, double dt,
                     const std::string& engine, const std::string& bed_path) {
  const bed::DeckLaws laws = run_deck_laws(scene, young_scale, dt, "the deposit run that wrote " + bed_path);
  bed::write_deck(bed, laws, bed::parse_deck_engine(engine, "--export-deck"), deck_data_path(bed_path));
}

std::string deck_data_file(const std::string& bed_path) { return deck_data_path(bed_path); }

}  // namespace powderbed::app
