#include "common/material_options.hpp"

#include <filesystem>
#include <iostream>
#include <map>
#include <string>

#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/bed/material_file.hpp"

namespace powderbed::app {

namespace {

namespace po = boost::program_options;

// What a material file fills, program by program: the option and the file's key. Two keys are
// not scalars: "file" is the material file itself (sinter reads its table), "conductivity" the
// table's solid conductivity at the bed's temperature (keff: the mean of the walls, or
// --temperature). A required key is one the program's models always read: a file without it is
// refused unless the option is given beside it, since the option's default is 316L's (wrong for
// any other metal). The keys only some models read (optics, evaporation) are checked by the
// program that knows its models (sinter: require_material_keys).
struct MaterialOption {
  const char* app;
  const char* option;
  const char* key;
  bool required;
};
constexpr MaterialOption kMaterialOptions[] = {
    {"deposit", "material.density", "density", true},
    {"deposit", "material.young", "young_modulus", true},
    {"deposit", "material.poisson", "poisson_ratio", true},
    {"sinter", "material.table", "file", true},
    {"sinter", "material.melting-point", "melting_point", true},
    {"sinter", "material.boiling-point", "boiling_point", false},
    {"sinter", "material.latent-melt", "latent_melt", true},
    {"sinter", "material.latent-vapour", "latent_vapour", false},
    {"sinter", "material.hold-from", "hold_from", true},
    {"sinter", "laser.absorptivity", "absorptivity", false},
    {"sinter", "laser.index-n-solid", "index_n_solid", false},
    {"sinter", "laser.index-k-solid", "index_k_solid", false},
    {"sinter", "laser.index-n-liquid", "index_n_liquid", false},
    {"sinter", "laser.index-k-liquid", "index_k_liquid", false},
    {"sinter", "material.molar-mass", "molar_mass", false},
    {"sinter", "material.surface-tension", "surface_tension", false},
    {"keff", "solid.conductivity", "conductivity", true},
};

// Whether `file` gives what `key` needs: the table for "file" and "conductivity", else the key.
bool file_gives(const bed::MaterialFile& file, const std::string& key) {
  if (key == "file" || key == "conductivity") return !file.solid.empty();
  return file.get(key).has_value();
}

// The bed temperature keff's k_s is read at: --temperature, else the mean of the two walls.
double keff_temperature(const po::variables_map& vm) {
  if (vm.count("temperature")) return vm["temperature"].as<double>();
  return 0.5 * (vm["t-hot"].as<double>() + vm["t-cold"].as<double>());
}

// Stores `value` as option `name`'s value (as if typed: no longer a default).
void store(po::variables_map& vm, const std::string& name, boost::any value) {
  static_cast<std::map<std::string, po::variable_value>&>(vm)[name] =
      po::variable_value(std::move(value), false);
}

}  // namespace

void add_material_options(po::options_description& desc, const char* app) {
  std::string filled;
  for (const auto& m : kMaterialOptions) {
    if (std::string(m.app) != app) continue;
    filled += fmt::format("{}{}", filled.empty() ? "" : ", ", m.option);
  }
  const std::string help = fmt::format(
      "material: a name of --list-materials (data/materials/NAME.csv) or a path to a material "
      "CSV; fills {} (an option given beside it wins: on the command line always, in the scene "
      "file when --material is in the scene file too)",
      filled);
  desc.add_options()("material", po::value<std::string>(), help.c_str())(
      "list-materials", "print the shipped materials (name and description) and exit");
}

bool list_materials(const po::variables_map& vm) {
  if (!vm.count("list-materials")) return false;
  const auto materials = bed::shipped_materials();
  if (vm.count("json")) {
    bed::JsonWriter j;
    j.begin_object().begin_array("materials");
    for (const auto& m : materials) {
      j.begin_object()
          .value("name", m.name)
          .value("description", m.description)
          .value("path", m.path)
          .end_object();
    }
    j.end_array().end_object();
    std::cout << j.str() << '\n';
    return true;
  }
  std::size_t width = 0;
  for (const auto& m : materials) width = std::max(width, m.name.size());
  for (const auto& m : materials)
    std::cout << m.name << std::string(width + 2 - m.name.size(), ' ') << m.description << '\n';
  return true;
}

std::string material_file(const std::string& name_or_path, const po::variables_map& vm,
                          const std::string& option) {
  namespace fs = std::filesystem;
  const std::string path = bed::material_path(name_or_path, option);
  if (fs::path(path).is_absolute() || fs::exists(path) || !vm.count("config")) return path;
  const fs::path beside = fs::path(vm["config"].as<std::string>()).parent_path() / path;
  return fs::exists(beside) ? beside.string() : path;
}

std::vector<std::string> apply_material(const char* app, po::variables_map& vm,
                                        const std::set<std::string>& typed) {
  std::vector<std::string> stored;
  if (!vm.count("material")) return stored;
  const std::string path = material_file(vm["material"].as<std::string>(), vm, "--material");
  bed::MaterialFile file;
  try {
    file = bed::read_material_file(path);
  } catch (const InputError& e) {
    throw InputError(fmt::format("--material: {}", e.what()));
  }
  // Given beside it, an option wins: at the command line always, in the scene file unless
  // --material itself was typed at the command line (then the scene's values give way).
  const bool material_typed = typed.count("material") > 0;
  for (const auto& m : kMaterialOptions) {
    if (std::string(m.app) != app) continue;
    const bool in_scene = vm.count(m.option) && !vm[m.option].defaulted();
    if (typed.count(m.option) || (in_scene && !material_typed)) continue;
    const std::string key = m.key;
    // The file itself is stored as sinter's table even over a scene's table: it must hold one.
    if (m.required && !file_gives(file, key) && (!in_scene || key == "file")) {
      const bool table = key == "file" || key == "conductivity";
      throw InputError(fmt::format(
          "--material: '{}' gives no {} for {} (accepted: a material file with {}, or --{} "
          "given beside it)",
          path, table ? "property table" : key, m.option,
          table ? "the table temperature_K,...,phase" : "the key " + key, m.option));
    }
    if (key == "file") {
      store(vm, m.option, path);
    } else if (key == "conductivity") {
      store(vm, m.option, file.solid_conductivity(keff_temperature(vm)));
    } else if (const auto v = file.get(key)) {
      store(vm, m.option, *v);
    } else {
      continue;
    }
    stored.push_back(m.option);
  }
  return stored;
}

}  // namespace powderbed::app
