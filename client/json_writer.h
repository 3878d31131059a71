// A minimal streaming JSON writer for the CLI's --json output: objects, arrays, strings
// (escaped), integers, booleans and doubles (shortest round-trip form; NaN and infinities, which
// JSON lacks, are written as null).
#pragma once

#include <cstdint>
#include <ostream>
#include <string_view>
#include <vector>

namespace afmesh::cli {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out) : out_(out) {}

  void begin_object(std::string_view key = {});
  void end_object();
  void begin_array(std::string_view key = {});
  void end_array();

  void field(std::string_view key, std::string_view value);
  void field(std::string_view key, const char* value) { field(key, std::string_view(value)); }
  void field(std::string_view key, std::int64_t value);
  void field(std::string_view key, int value) { field(key, static_cast<std::int64_t>(value)); }
  void field(std::string_view key, double value);
  void field(std::string_view key, bool value);

  void value(std::string_view v);
  void value(std::int64_t v);
  void value(double v);

 private:
  void separator();
  void key(std::string_view k);
  void string(std::string_view s);
  void number(double v);

  std::ostream& out_;
  std::vector<bool> first_;  // per open container: nothing written in it yet
};

}  // namespace afmesh::cli
