#include "common/material_options.hpp"

#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <variant>

#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/bed/material_file.hpp"
#include "powderbed/bed/material_fills.hpp"

namespace powderbed::app {

namespace {

namespace po = boost::program_options;

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
  for (const auto& m : bed::kMaterialFills) {
    if (std::string(m.program) != app) continue;
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
  const bed::MaterialFile file = bed::read_named_material(path, "--material");
  // Given beside it, an option wins: at the command line always, in the scene file unless
  // --material itself was typed at the command line (then the scene's values give way).
  const bool material_typed = typed.count("material") > 0;
  for (const auto& m : bed::kMaterialFills) {
    if (std::string(m.program) != app) continue;
    const bool in_scene = vm.count(m.option) && !vm[m.option].defaulted();
    if (typed.count(m.option) || (in_scene && !material_typed)) continue;
    const bool conductivity = m.key == std::string("conductivity");  // keff's: it has walls
    const auto value = bed::material_value(file, m, conductivity ? keff_temperature(vm) : 0);
    // The file itself is stored as sinter's table even over a scene's table: it must hold one.
    if (m.required && !value && (!in_scene || m.key == std::string("file")))
      bed::refuse_missing_fill(file, m);
    if (!value) continue;
    if (const auto* number = std::get_if<double>(&*value)) {
      store(vm, m.option, *number);
    } else {
      store(vm, m.option, std::get<std::string>(*value));
    }
    stored.push_back(m.option);
  }
  return stored;
}

}  // namespace powderbed::app
