// The CLI's side of the server's security flags: --tls-ca (TLS, trusting that CA bundle),
// --tls-cert and --tls-key (a client certificate, for a server that asks for one) and
// --token-file (a bearer token sent with each call). Files are read and checked once, before
// any connection; a bad one is reported by flag and path.
#pragma once

#include <memory>
#include <string>

#include "CLI/CLI.hpp"
#include "absl/status/statusor.h"

namespace grpc {
class ChannelCredentials;
class ClientContext;
}  // namespace grpc

namespace afmesh::cli {

struct ClientSecurityFiles {
  std::string tls_ca;      // PEM CA bundle the server's certificate must chain to; turns TLS on
  std::string tls_cert;    // PEM client certificate chain (needs tls_key and tls_ca)
  std::string tls_key;     // PEM private key of tls_cert
  std::string token_file;  // the bearer token (security/token_file.h)

  // True when any flag was given.
  bool any() const;
};

// Adds --tls-ca, --tls-cert, --tls-key and --token-file to `command`.
void add_client_security_flags(CLI::App& command, ClientSecurityFiles& files);

// What one call needs: the channel's credentials and the token to send.
class ClientSecurity {
 public:
  // Plaintext, no token.
  ClientSecurity();

  // For grpc::CreateChannel.
  std::shared_ptr<grpc::ChannelCredentials> channel_credentials() const;
  // Adds "authorization: Bearer <token>" to `context` when there is a token.
  void add_to(grpc::ClientContext& context) const;

  bool tls() const { return tls_; }
  bool has_token() const { return !token_.empty(); }

 private:
  friend absl::StatusOr<ClientSecurity> load_client_security(const ClientSecurityFiles& files);

  std::shared_ptr<grpc::ChannelCredentials> credentials_;
  bool tls_ = false;
  std::string token_;
};

// Reads and checks the files. INVALID_ARGUMENT naming the flag and the file when one cannot be
// read or is not what its flag needs, or when the flags do not go together (--tls-cert without
// --tls-key, a client certificate without --tls-ca).
absl::StatusOr<ClientSecurity> load_client_security(const ClientSecurityFiles& files);

}  // namespace afmesh::cli
