#include "bench/json_line.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace afmesh::bench {

std::string json_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20)
          out += absl::StrFormat("\\u%04x", static_cast<unsigned char>(c));
        else
          out += c;
    }
  }
  return out + "\"";
}

void JsonLine::put_key(std::string_view key) {
  if (!body_.empty()) body_ += ", ";
  absl::StrAppend(&body_, json_string(key), ": ");
}

JsonLine& JsonLine::add(std::string_view key, std::string_view value) {
  put_key(key);
  body_ += json_string(value);
  return *this;
}

JsonLine& JsonLine::add(std::string_view key, double value) {
  put_key(key);
  body_ += std::isfinite(value) ? absl::StrFormat("%.17g", value) : "null";
  return *this;
}

JsonLine& JsonLine::add(std::string_view key, std::int64_t value) {
  put_key(key);
  absl::StrAppend(&body_, value);
  return *this;
}

JsonLine& JsonLine::add(std::string_view key, bool value) {
  put_key(key);
  body_ += value ? "true" : "false";
  return *this;
}

JsonLine& JsonLine::add_raw(std::string_view key, std::string_view json) {
  put_key(key);
  body_ += json;
  return *this;
}

}  // namespace afmesh::bench
