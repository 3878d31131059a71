#include "server/listen_note.h"

#include "absl/strings/str_cat.h"
#include "security/address_reach.h"

namespace afmesh::server {

std::vector<std::string> listen_note(const std::string& address, const ServerSecurity& security) {
  using security::Reach;
  const Reach reach = security::reach_of(address);
  const std::string who =
      reach == Reach::kLocalSocket ? "local socket only"
      : reach == Reach::kLoopback
          ? absl::StrCat("loopback only; use --listen 0.0.0.0:", security::port_of(address),
                         " to serve other hosts")
          : "other hosts can connect";
  std::vector<std::string> lines = {
      absl::StrCat("listening on ", address, " (", who, "); ", security.describe())};
  if (reach == Reach::kOtherHosts && !security.tls) {
    lines.push_back(
        "warning: plaintext on an address other hosts can reach: anyone on the path can read the "
        "meshes (and the bearer token, if any); use --tls-cert and --tls-key");
  }
  return lines;
}

std::string metrics_note(const std::string& address) {
  const bool loopback = security::reach_of(address) == security::Reach::kLoopback;
  return absl::StrCat("metrics on http://", address, "/metrics (",
                      loopback ? "loopback only" : "other hosts can connect",
                      "; plain HTTP, no token: call counts and sizes, never meshes)");
}

}  // namespace afmesh::server
