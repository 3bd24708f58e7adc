#include "powderbed/bed/json_units.hpp"

#include <string>
#include <vector>

namespace powderbed::bed {

void write_units(bed::JsonWriter& json, std::span<const UnitEntry> table) {
  const std::vector<std::string> keys = json.numeric_keys();  // a copy: the units add none
  json.begin_object("units");
  for (const std::string& key : keys) {
    for (const UnitEntry& entry : table) {
      if (key == entry.key) {
        json.value(key, entry.unit);
        break;
      }
    }
  }
  json.end_object();
}

}  // namespace powderbed::bed
