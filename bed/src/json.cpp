#include "powderbed/bed/json.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace powderbed::bed {

std::string json_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size() + 2);
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

void JsonWriter::key(const std::string& k) {
  if (need_comma_) out_ << ',';
  if (!k.empty()) out_ << '"' << json_escape(k) << "\":";
  need_comma_ = true;
}

void JsonWriter::numeric(const std::string& k) {
  if (!k.empty() && std::find(numeric_keys_.begin(), numeric_keys_.end(), k) == numeric_keys_.end())
    numeric_keys_.push_back(k);
}

JsonWriter& JsonWriter::begin_object(const std::string& k) {
  open_.push_back(k);
  key(k);
  out_ << '{';
  need_comma_ = false;
  return *this;
}
JsonWriter& JsonWriter::end_object() {
  if (!open_.empty()) open_.pop_back();
  out_ << '}';
  need_comma_ = true;
  return *this;
}
JsonWriter& JsonWriter::begin_array(const std::string& k) {
  open_.push_back(k);
  key(k);
  out_ << '[';
  need_comma_ = false;
  return *this;
}
JsonWriter& JsonWriter::end_array() {
  if (!open_.empty()) open_.pop_back();
  out_ << ']';
  need_comma_ = true;
  return *this;
}
JsonWriter& JsonWriter::value(const std::string& k, double v) {
  numeric(k);
  key(k);
  out_ << json_number(v);
  return *this;
}
JsonWriter& JsonWriter::value(const std::string& k, std::int64_t v) {
  numeric(k);
  key(k);
  out_ << v;
  return *this;
}
JsonWriter& JsonWriter::value(const std::string& k, std::uint64_t v) {
  numeric(k);
  key(k);
  out_ << v;
  return *this;
}
JsonWriter& JsonWriter::value(const std::string& k, const std::string& v) {
  key(k);
  out_ << '"' << json_escape(v) << '"';
  return *this;
}
JsonWriter& JsonWriter::value(const std::string& k, bool v) {
  key(k);
  out_ << (v ? "true" : "false");
  return *this;
}
JsonWriter& JsonWriter::element(double v) {
  if (!open_.empty()) numeric(open_.back());
  key("");
  out_ << json_number(v);
  return *this;
}

}  // namespace powderbed::bed
