#include "core/io/text_scanner.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <system_error>

#include "core/io/string_util.h"

namespace afmesh {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// Drops one leading '+' that precedes a digit or a '.': std::from_chars rejects it, C's
// strtod and every mesh tool accept it.
std::string_view strip_plus(std::string_view token) {
  if (token.size() >= 2 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
    token.remove_prefix(1);
  }
  return token;
}

// A short, printable quote of `token` for error messages.
std::string quote(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  std::string shown(token.substr(0, kMaxShown));
  for (char& c : shown) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  if (token.size() > kMaxShown) shown += "...";
  return str_cat("'", shown, "'");
}

}  // namespace

bool parse_double(std::string_view token, double& value) {
  token = strip_plus(token);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end;
}

bool parse_int(std::string_view token, std::int64_t& value) {
  token = strip_plus(token);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end;
}

absl::Status binary_error(std::string_view source_name, std::size_t offset,
                          std::string_view message) {
  return absl::InvalidArgumentError(str_cat(source_name, ": byte ", offset, ": ", message));
}

TextScanner::TextScanner(std::string_view text, std::string_view source_name, char comment)
    : text_(text), source_name_(source_name), comment_(comment) {}

void TextScanner::skip_blanks() {
  const std::size_t size = text_.size();
  while (pos_ < size) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (is_blank(c)) {
      ++pos_;
    } else if (c == comment_ && c != '\0') {
      while (pos_ < size && text_[pos_] != '\n') ++pos_;
    } else {
      return;
    }
  }
}

std::string_view TextScanner::next_token() {
  skip_blanks();
  token_line_ = line_;
  token_offset_ = pos_;
  const std::size_t start = pos_;
  const std::size_t size = text_.size();
  while (pos_ < size) {
    const char c = text_[pos_];
    if (c == '\n' || is_blank(c) || (c == comment_ && c != '\0')) break;
    ++pos_;
  }
  return text_.substr(start, pos_ - start);
}

bool TextScanner::at_end() {
  skip_blanks();
  return pos_ >= text_.size();
}

bool TextScanner::at_line_end() {
  std::size_t pos = pos_;
  while (pos < text_.size() && is_blank(text_[pos])) ++pos;
  return pos >= text_.size() || text_[pos] == '\n' || (text_[pos] == comment_ && comment_ != '\0');
}

std::string_view TextScanner::rest_of_line() {
  const std::size_t start = pos_;
  while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  std::string_view rest = text_.substr(start, pos_ - start);
  if (comment_ != '\0') rest = rest.substr(0, rest.find(comment_));
  while (!rest.empty() && is_blank(rest.front())) rest.remove_prefix(1);
  while (!rest.empty() && is_blank(rest.back())) rest.remove_suffix(1);
  return rest;
}

void TextScanner::skip_line() {
  while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  if (pos_ < text_.size()) {
    ++pos_;
    ++line_;
  }
}

absl::Status TextScanner::read_double(double& value, std::string_view what) {
  const std::string_view token = next_token();
  if (!parse_double(token, value) || !std::isfinite(value)) {
    return unexpected(str_cat("a finite number (", what, ")"), token);
  }
  return absl::OkStatus();
}

absl::Status TextScanner::read_any_double(double& value, std::string_view what) {
  const std::string_view token = next_token();
  if (!parse_double(token, value)) {
    return unexpected(str_cat("a number (", what, ")"), token);
  }
  return absl::OkStatus();
}

absl::Status TextScanner::read_int(std::int64_t& value, std::string_view what) {
  const std::string_view token = next_token();
  if (!parse_int(token, value)) {
    return unexpected(str_cat("an integer (", what, ")"), token);
  }
  return absl::OkStatus();
}

absl::Status TextScanner::expect_keyword(std::string_view keyword) {
  const std::string_view token = next_token();
  if (!equals_ignore_case(token, keyword)) {
    return unexpected(str_cat("'", keyword, "'"), token);
  }
  return absl::OkStatus();
}

absl::Status TextScanner::take_bytes(std::size_t count, std::string_view what, const char*& bytes) {
  token_offset_ = pos_;
  token_line_ = line_;
  if (text_.size() - pos_ < count) {
    return error(str_cat("expected ", count, " bytes of ", what, ", but the file ends after ",
                         text_.size() - pos_, " more"));
  }
  bytes = text_.data() + pos_;
  pos_ += count;
  return absl::OkStatus();
}

void TextScanner::seek(std::size_t offset) {
  offset = std::min(offset, text_.size());
  if (offset <= pos_) return;
  line_ += static_cast<int>(std::count(text_.begin() + pos_, text_.begin() + offset, '\n'));
  pos_ = offset;
}

absl::Status TextScanner::error(std::string_view message) const {
  if (report_offsets_) return binary_error(source_name_, token_offset_, message);
  return absl::InvalidArgumentError(str_cat(source_name_, ":", token_line_, ": ", message));
}

absl::Status TextScanner::unexpected(std::string_view what, std::string_view found) const {
  if (found.empty()) return error(str_cat("expected ", what, ", found end of file"));
  return error(str_cat("expected ", what, ", found ", quote(found)));
}

}  // namespace afmesh
