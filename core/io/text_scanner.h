// TextScanner: a cursor over the bytes of a mesh file held in memory, reading
// whitespace-separated tokens and numbers (std::from_chars: exact, locale-free) and producing
// errors that name the file and the line (or, for binary data, the byte offset).
//
// Tokens are views into the file text: scanning allocates nothing. Newlines count as whitespace
// for token reads; the line-oriented helpers (`at_line_end`, `rest_of_line`) serve formats
// whose statements end at the end of a line (OBJ, STL solid names).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "absl/status/status.h"

namespace afmesh {

class TextScanner {
 public:
  // `text` must outlive the scanner. `source_name` (usually the path) starts every error
  // message. `comment` starts a comment running to the end of the line; '\0' means none.
  TextScanner(std::string_view text, std::string_view source_name, char comment = '\0');

  // The next whitespace-delimited token; empty at the end of the input.
  std::string_view next_token();
  // True when no token remains.
  bool at_end();

  // True when only blanks and a comment remain on the current line.
  bool at_line_end();
  // The rest of the current line without its comment, trimmed; the cursor moves to the end of
  // the line (before the newline).
  std::string_view rest_of_line();
  // Moves the cursor past the next newline (or to the end of the input).
  void skip_line();

  // Reads the next token as a finite double; `what` names the expected value in the error
  // ("a vertex coordinate").
  absl::Status read_double(double& value, std::string_view what);
  // Reads the next token as a double that may be NaN or infinite (STL facet normals).
  absl::Status read_any_double(double& value, std::string_view what);
  // Reads the next token as a signed 64-bit integer.
  absl::Status read_int(std::int64_t& value, std::string_view what);
  // Reads the next token and checks that it equals `keyword`, ignoring ASCII case.
  absl::Status expect_keyword(std::string_view keyword);

  // Binary data embedded in the text (binary MSH): points `bytes` at the next `count` bytes and
  // moves past them, or fails naming `what` when fewer remain.
  absl::Status take_bytes(std::size_t count, std::string_view what, const char*& bytes);
  // Offset of the cursor from the start of the text.
  std::size_t offset() const { return pos_; }
  // Moves the cursor forward to `offset` (clamped to the text size), counting the newlines
  // passed over.
  void seek(std::size_t offset);
  // From now on errors name the byte offset of the last token instead of its line (for files
  // that mix text and binary data, where lines mean little).
  void report_offsets() { report_offsets_ = true; }

  std::string_view source_name() const { return source_name_; }
  std::string_view text() const { return text_; }

  // INVALID_ARGUMENT "<source>:<line>: <message>" (or "<source>: byte <offset>: <message>").
  absl::Status error(std::string_view message) const;
  // The error for a token that is not what the format requires at this point:
  // "expected <what>, found '<found>'" ("found end of file" when `found` is empty).
  absl::Status unexpected(std::string_view what, std::string_view found) const;

 private:
  // Moves past whitespace and comments, counting newlines.
  void skip_blanks();

  std::string_view text_;
  std::string source_name_;
  char comment_;
  std::size_t pos_ = 0;
  int line_ = 1;        // line of the cursor
  int token_line_ = 1;  // line where the last token started
  std::size_t token_offset_ = 0;
  bool report_offsets_ = false;
};

// INVALID_ARGUMENT "<source>: byte <offset>: <message>", for errors in binary files.
absl::Status binary_error(std::string_view source_name, std::size_t offset,
                          std::string_view message);

// Parses all of `token` as a double (an optional leading '+' is accepted). False when the token
// is not a number, has trailing characters or is out of the double range.
bool parse_double(std::string_view token, double& value);
// Parses all of `token` as a signed 64-bit integer (an optional leading '+' is accepted).
bool parse_int(std::string_view token, std::int64_t& value);

}  // namespace afmesh
