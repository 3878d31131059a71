#include "security/token_file.h"

#include <cstddef>
#include <fstream>
#include <sstream>

#include "absl/strings/str_format.h"

namespace afmesh::security {
namespace {

constexpr std::size_t kMaxTokenBytes = 4096;

bool is_trailing_space(char c) { return c == '\n' || c == '\r' || c == ' ' || c == '\t'; }
bool is_visible_ascii(char c) { return c >= 0x21 && c <= 0x7e; }

}  // namespace

absl::StatusOr<std::string> read_token_file(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::InvalidArgumentError(absl::StrFormat("%s %s: cannot be read", what, path));
  std::string token(kMaxTokenBytes + 2, '\0');
  in.read(token.data(), static_cast<std::streamsize>(token.size()));
  if (in.bad()) {
    return absl::InvalidArgumentError(absl::StrFormat("%s %s: cannot be read", what, path));
  }
  token.resize(static_cast<std::size_t>(in.gcount()));
  while (!token.empty() && is_trailing_space(token.back())) token.pop_back();
  if (token.empty()) {
    return absl::InvalidArgumentError(absl::StrFormat("%s %s: the file is empty", what, path));
  }
  if (token.size() > kMaxTokenBytes) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s %s: the token is longer than %d characters", what, path, kMaxTokenBytes));
  }
  for (std::size_t i = 0; i < token.size(); ++i) {
    if (!is_visible_ascii(token[i])) {
      return absl::InvalidArgumentError(absl::StrFormat(
          "%s %s: character %d of the token is whitespace, a control character or not ASCII; "
          "a token is one line of visible ASCII characters",
          what, path, i + 1));
    }
  }
  return token;
}

}  // namespace afmesh::security
