// The bearer token file of `afmesh-server --token-file` and `afmesh ... --token-file`: both
// sides read it with this function, so they agree on what the token is.
#pragma once

#include <string>

#include "absl/status/statusor.h"

namespace afmesh::security {

// The token in `path`: the file's content without trailing whitespace (so `echo TOKEN > FILE`
// works). It must be 1 to 4096 visible ASCII characters (0x21-0x7e, what an HTTP/2 header value
// carries as is) with no whitespace inside. INVALID_ARGUMENT naming `what` and the path when the
// file cannot be read or its content is not such a token; the token itself is never quoted.
absl::StatusOr<std::string> read_token_file(const std::string& path, const std::string& what);

// The metadata key and the value prefix a call carries its token in: "authorization" /
// "Bearer <token>" (RFC 6750, section 2.1).
inline constexpr const char* kAuthorizationKey = "authorization";
inline constexpr const char* kBearerPrefix = "Bearer ";

}  // namespace afmesh::security
