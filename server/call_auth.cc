#include "server/call_auth.h"

#include <iterator>

#include "absl/strings/match.h"
#include "security/constant_time_equal.h"
#include "security/token_file.h"

namespace afmesh::server {

grpc::Status check_bearer_token(const grpc::ServerContextBase& context, std::string_view token) {
  if (token.empty()) return grpc::Status::OK;
  const auto& metadata = context.client_metadata();
  const auto [first, last] = metadata.equal_range(security::kAuthorizationKey);
  if (first == last) {
    return grpc::Status(grpc::StatusCode::UNAUTHENTICATED,
                        "this server needs a bearer token: send 'authorization: Bearer <token>' "
                        "metadata (afmesh --token-file FILE)");
  }
  if (std::next(first) != last) {
    return grpc::Status(grpc::StatusCode::UNAUTHENTICATED,
                        "more than one 'authorization' metadata entry; send exactly one");
  }
  const std::string_view value(first->second.data(), first->second.size());
  const std::string_view prefix = security::kBearerPrefix;
  if (value.size() < prefix.size() ||
      !absl::EqualsIgnoreCase(absl::string_view(value.data(), prefix.size()),
                              absl::string_view(prefix.data(), prefix.size()))) {
    return grpc::Status(grpc::StatusCode::UNAUTHENTICATED,
                        "the 'authorization' metadata is not 'Bearer <token>'");
  }
  if (!security::constant_time_equal(value.substr(prefix.size()), token)) {
    return grpc::Status(grpc::StatusCode::UNAUTHENTICATED, "the bearer token is not valid");
  }
  return grpc::Status::OK;
}

}  // namespace afmesh::server
