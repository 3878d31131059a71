// A flat JSON object built field by field and printed on one line: the machine-readable output of
// the benchmark programs, read by bench/run_bench.py.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace afmesh::bench {

class JsonLine {
 public:
  // Each add appends `"key": value`; keys are expected to be plain identifiers.
  JsonLine& add(std::string_view key, std::string_view value);
  JsonLine& add(std::string_view key, const char* value) { return add(key, std::string_view(value)); }
  JsonLine& add(std::string_view key, double value);  // non-finite values print as null
  JsonLine& add(std::string_view key, std::int64_t value);
  JsonLine& add(std::string_view key, int value) { return add(key, std::int64_t{value}); }
  JsonLine& add(std::string_view key, bool value);
  // Appends `"key": <json>` with `json` already formatted (a nested object or array).
  JsonLine& add_raw(std::string_view key, std::string_view json);

  // The object, e.g. {"tool": "afmesh", "tets": 51234}.
  std::string str() const { return "{" + body_ + "}"; }

 private:
  void put_key(std::string_view key);

  std::string body_;
};

// `text` as a JSON string literal, quotes included.
std::string json_string(std::string_view text);

}  // namespace afmesh::bench
