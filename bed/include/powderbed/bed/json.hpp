#pragma once
// A small JSON writer for the apps' --json summaries (one object on one line).
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace powderbed::bed {

class JsonWriter {
 public:
  JsonWriter& begin_object(const std::string& key = "");
  JsonWriter& end_object();
  JsonWriter& begin_array(const std::string& key = "");
  JsonWriter& end_array();
  JsonWriter& value(const std::string& key, double v);
  JsonWriter& value(const std::string& key, std::int64_t v);
  JsonWriter& value(const std::string& key, std::uint64_t v);
  JsonWriter& value(const std::string& key, int v) { return value(key, std::int64_t{v}); }
  JsonWriter& value(const std::string& key, const std::string& v);
  JsonWriter& value(const std::string& key, const char* v) { return value(key, std::string(v)); }
  JsonWriter& value(const std::string& key, bool v);
  JsonWriter& element(double v);  // array element
  std::string str() const { return out_.str(); }
  // The keys of the numbers written so far (an array of numbers: its key), each once, in the
  // order of first appearance: what a summary's "units" object must name (apps/common/json_units).
  const std::vector<std::string>& numeric_keys() const { return numeric_keys_; }

 private:
  void key(const std::string& k);
  void numeric(const std::string& k);
  std::ostringstream out_;
  bool need_comma_ = false;
  std::vector<std::string> open_;  // the keys of the open objects and arrays
  std::vector<std::string> numeric_keys_;
};

// JSON string escaping.
std::string json_escape(const std::string& s);
// Shortest decimal text that reads back to the same double; non-finite become null.
std::string json_number(double v);

}  // namespace powderbed::bed
