#pragma once
// A small JSON writer for the apps' --json summaries (one object on one line).
#include <cstdint>
#include <sstream>
#include <string>

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

 private:
  void key(const std::string& k);
  std::ostringstream out_;
  bool need_comma_ = false;
};

// JSON string escaping.
std::string json_escape(const std::string& s);
// Shortest decimal text that reads back to the same double; non-finite become null.
std::string json_number(double v);

}  // namespace powderbed::bed
