#include "client/json_writer.h"

#include <charconv>
#include <cmath>

#include "absl/strings/str_format.h"

namespace afmesh::cli {

void JsonWriter::separator() {
  if (first_.empty()) return;
  if (!first_.back()) out_ << ',';
  first_.back() = false;
}

void JsonWriter::key(std::string_view k) {
  separator();
  if (!k.empty()) {
    string(k);
    out_ << ':';
  }
}

void JsonWriter::string(std::string_view s) {
  out_ << '"';
  for (char c : s) {
    switch (c) {
      case '"': out_ << "\\\""; break;
      case '\\': out_ << "\\\\"; break;
      case '\n': out_ << "\\n"; break;
      case '\t': out_ << "\\t"; break;
      case '\r': out_ << "\\r"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20)
          out_ << absl::StrFormat("\\u%04x", static_cast<unsigned char>(c));
        else
          out_ << c;
    }
  }
  out_ << '"';
}

void JsonWriter::number(double v) {
  if (!std::isfinite(v)) {
    out_ << "null";
    return;
  }
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out_.write(buf, r.ptr - buf);
}

void JsonWriter::begin_object(std::string_view k) {
  key(k);
  out_ << '{';
  first_.push_back(true);
}

void JsonWriter::end_object() {
  first_.pop_back();
  out_ << '}';
}

void JsonWriter::begin_array(std::string_view k) {
  key(k);
  out_ << '[';
  first_.push_back(true);
}

void JsonWriter::end_array() {
  first_.pop_back();
  out_ << ']';
}

void JsonWriter::field(std::string_view k, std::string_view v) {
  key(k);
  string(v);
}

void JsonWriter::field(std::string_view k, std::int64_t v) {
  key(k);
  out_ << v;
}

void JsonWriter::field(std::string_view k, double v) {
  key(k);
  number(v);
}

void JsonWriter::field(std::string_view k, bool v) {
  key(k);
  out_ << (v ? "true" : "false");
}

void JsonWriter::value(std::string_view v) {
  separator();
  string(v);
}

void JsonWriter::value(std::int64_t v) {
  separator();
  out_ << v;
}

void JsonWriter::value(double v) {
  separator();
  number(v);
}

}  // namespace afmesh::cli
