// material_fills.hpp: the values a material file gives each program's options.
#include "powderbed/bed/material_fills.hpp"

#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"

namespace powderbed::bed {

namespace {

// "file" and "conductivity" come from the table.
bool from_table(const std::string& key) { return key == "file" || key == "conductivity"; }

}  // namespace

MaterialFile read_named_material(const std::string& name_or_path, const std::string& option) {
  const std::string path = material_path(name_or_path, option);
  try {
    return read_material_file(path);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", option, e.what()));
  }
}

std::optional<MaterialValue> material_value(const MaterialFile& file, const MaterialFill& fill,
                                            double temperature) {
  const std::string key = fill.key;
  if (from_table(key) && file.solid.empty()) return std::nullopt;
  if (key == "file") return file.path;
  if (key == "conductivity") return file.solid_conductivity(temperature);
  if (const auto v = file.get(key)) return *v;
  return std::nullopt;
}

void refuse_missing_fill(const MaterialFile& file, const MaterialFill& fill) {
  const bool table = from_table(fill.key);
  throw InputError(fmt::format(
      "--material: '{}' gives no {} for {} (accepted: a material file with {}, or --{} given "
      "beside it)",
      file.path, table ? "property table" : fill.key, fill.option,
      table ? "the table temperature_K,...,phase" : std::string("the key ") + fill.key, fill.option));
}

}  // namespace powderbed::bed
