// The material file of material_file.hpp: one reader for every program, messages naming the
// file and the line.
#include "powderbed/bed/material_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/input_file.hpp"

namespace powderbed::bed {

namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

// The first `count` comma-separated fields, trimmed; the rest of the line (commas and all) is one
// more field when there is any.
std::vector<std::string> split_fields(const std::string& line, std::size_t count) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (fields.size() < count) {
    const auto comma = line.find(',', start);
    if (comma == std::string::npos) break;
    fields.push_back(trim(line.substr(start, comma - start)));
    start = comma + 1;
  }
  fields.push_back(trim(line.substr(start)));
  return fields;
}

double parse_positive(const std::string& text, const std::string& where, const char* what) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || !std::isfinite(value) || value <= 0) {
    throw InputError(where + ": " + what + " " + quoted_excerpt(text) +
                     " is not a finite positive number (accepted: value > 0)");
  }
  return value;
}

const MaterialKey* find_key(const std::string& key) {
  for (const auto& k : kMaterialKeys)
    if (key == k.key) return &k;
  return nullptr;
}

std::string key_list() {
  std::string list = "name, description";
  for (const auto& k : kMaterialKeys) list += std::string(", ") + k.key;
  return list;
}

constexpr const char* kTableHeader =
    "temperature_K,specific_heat_J_per_kgK,conductivity_W_per_mK,density_kg_per_m3,phase";

// One scalar line "key,value,unit,source" (or name/description) into `file`.
void read_scalar(const std::vector<std::string>& all, const std::string& line,
                 const std::string& where, MaterialFile& file) {
  const std::string& key = all[0];
  if (key == "name" || key == "description") {
    const auto rest = trim(line.substr(line.find(',') + 1));
    if (rest.empty())
      throw InputError(where + ": " + key + " is empty (accepted: one line of text)");
    (key == "name" ? file.name : file.description) = rest;
    return;
  }
  const MaterialKey* known = find_key(key);
  if (!known) {
    throw InputError(where + ": unknown property " + quoted_excerpt(key) + " (accepted: " + key_list() +
                     ", then the table header " + kTableHeader + ")");
  }
  const auto fields = split_fields(line, 3);
  if (fields.size() < 3) {
    throw InputError(where + ": " + quoted_excerpt(line) + " (accepted: " + key + ",value," + known->unit +
                     ",source)");
  }
  if (fields[2] != known->unit) {
    throw InputError(where + ": " + key + " in " + quoted_excerpt(fields[2]) + " (accepted: " + known->unit +
                     ", SI)");
  }
  const double value = parse_positive(fields[1], where, known->key);
  if (!(value > known->min && value <= known->max)) {
    throw InputError(fmt::format("{}: {} {} is out of range (accepted: {:g} < value <= {:g} {})",
                                 where, key, fields[1], known->min, known->max, known->unit));
  }
  for (const auto& p : file.properties)
    if (p.key == key) throw InputError(where + ": " + key + " given twice (accepted: once)");
  file.properties.push_back({key, value, fields.size() > 3 ? fields[3] : ""});
}

void read_row(const std::string& line, const std::string& where, MaterialFile& file) {
  const auto fields = split_fields(line, 5);
  if (fields.size() < 5) {
    throw InputError(where + ": " + std::to_string(fields.size()) +
                     " fields (accepted: 5 or 6: T, c, k, rho, phase[, source])");
  }
  MaterialRow row;
  row.temperature = parse_positive(fields[0], where, "temperature");
  row.specific_heat = parse_positive(fields[1], where, "specific heat");
  row.conductivity = parse_positive(fields[2], where, "conductivity");
  row.density = parse_positive(fields[3], where, "density");
  row.source = fields.size() > 5 ? fields[5] : "";
  if (fields[4] == "solid") {
    if (file.liquid)
      throw InputError(where +
                       ": solid row after the liquid row (accepted: solid "
                       "rows first, then one liquid row)");
    if (!file.solid.empty() && row.temperature <= file.solid.back().temperature) {
      throw InputError(where + ": temperature " + fields[0] +
                       " K does not increase (accepted: strictly increasing solid rows)");
    }
    file.solid.push_back(row);
  } else if (fields[4] == "liquid") {
    if (file.liquid) throw InputError(where + ": a second liquid row (accepted: one)");
    row.liquid = true;
    file.liquid = row;
  } else {
    throw InputError(where + ": phase " + quoted_excerpt(fields[4]) + " (accepted: solid or liquid)");
  }
}

// solidus <= melting_point <= liquidus < boiling_point, where the file gives them.
void check_consistency(const MaterialFile& file) {
  const auto refuse = [&](const std::string& what) { throw InputError(file.path + ": " + what); };
  const auto solidus = file.get("solidus"), liquidus = file.get("liquidus");
  const auto melting = file.get("melting_point"), boiling = file.get("boiling_point");
  if (solidus && liquidus && *solidus > *liquidus)
    refuse("solidus above liquidus (accepted: solidus <= liquidus)");
  if (melting && solidus && *melting < *solidus)
    refuse("melting_point below solidus (accepted: solidus <= melting_point <= liquidus)");
  if (melting && liquidus && *melting > *liquidus)
    refuse("melting_point above liquidus (accepted: solidus <= melting_point <= liquidus)");
  if (melting && boiling && *boiling <= *melting)
    refuse("boiling_point not above melting_point (accepted: T_v > T_m)");
}

}  // namespace

std::optional<double> MaterialFile::get(const std::string& key) const {
  for (const auto& p : properties)
    if (p.key == key) return p.value;
  return std::nullopt;
}

double MaterialFile::solid_conductivity(double temperature) const {
  if (solid.empty())
    throw InputError(path + ": no property table (accepted: a table with solid rows)");
  if (temperature <= solid.front().temperature) return solid.front().conductivity;
  if (temperature >= solid.back().temperature) return solid.back().conductivity;
  const auto upper =
      std::upper_bound(solid.begin(), solid.end(), temperature,
                       [](double t, const MaterialRow& r) { return t < r.temperature; });
  const auto& a = *(upper - 1);
  const auto& b = *upper;
  return a.conductivity + (b.conductivity - a.conductivity) * (temperature - a.temperature) /
                              (b.temperature - a.temperature);
}

MaterialFile read_material_file(const std::string& path) {
  require_regular_file(path, "material file");  // a FIFO would block, /dev/zero never end
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the material file");
  MaterialFile file;
  file.path = path;
  bool table = false;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    line = trim(line);
    const std::string where = path + ":" + std::to_string(number);
    const auto first = split_fields(line, 1);
    if (!table && first[0] == "property") continue;  // the scalar block's header
    if (!table && first[0].rfind("temperature", 0) == 0) {
      const auto header = split_fields(line, 5);
      if (header.size() < 5 || header[4] != "phase" ||
          (header.size() == 6 && header[5] != "source")) {
        throw InputError(where + ": header " + quoted_excerpt(line) + " (accepted: " + kTableHeader +
                         "[,source])");
      }
      table = true;
      continue;
    }
    if (table) {
      read_row(line, where, file);
    } else {
      read_scalar(first, line, where, file);
    }
  }
  if (table && (file.solid.size() < 2 || !file.liquid)) {
    throw InputError(fmt::format(
        "{}: {} solid rows and {} liquid row (accepted: at least 2 solid rows and one liquid "
        "row)",
        path, file.solid.size(), file.liquid ? "one" : "no"));
  }
  if (file.name.empty()) file.name = std::filesystem::path(path).stem().string();
  check_consistency(file);
  return file;
}

std::string materials_folder() { return POWDERBED_MATERIALS_DIR; }

std::vector<MaterialFile> shipped_materials() {
  std::vector<std::string> paths;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(materials_folder(), ec))
    if (entry.path().extension() == ".csv") paths.push_back(entry.path().string());
  std::sort(paths.begin(), paths.end());
  std::vector<MaterialFile> files;
  for (const auto& p : paths) files.push_back(read_material_file(p));
  return files;
}

std::string material_path(const std::string& name_or_path, const std::string& option) {
  const bool is_path =
      name_or_path.find('/') != std::string::npos ||
      (name_or_path.size() > 4 && name_or_path.compare(name_or_path.size() - 4, 4, ".csv") == 0);
  if (is_path) return name_or_path;
  const std::string path = materials_folder() + "/" + name_or_path + ".csv";
  if (std::filesystem::exists(path)) return path;
  std::string names;
  std::error_code ec;
  std::vector<std::string> stems;
  for (const auto& entry : std::filesystem::directory_iterator(materials_folder(), ec))
    if (entry.path().extension() == ".csv") stems.push_back(entry.path().stem().string());
  std::sort(stems.begin(), stems.end());
  for (const auto& s : stems) names += (names.empty() ? "" : ", ") + s;
  throw InputError(option + ": '" + name_or_path + "' is not a material (accepted: " + names +
                   ", or a path to a material CSV; --list-materials)");
}

}  // namespace powderbed::bed
