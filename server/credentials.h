// What afmesh-server asks of its clients, from its security flags: TLS (--tls-cert, --tls-key),
// mutual TLS (--tls-client-ca) and a bearer token (--token-file). Every file is read and checked
// once, at start-up; a bad one stops the server with a message naming it.
#pragma once

#include <memory>
#include <string>

#include "absl/status/statusor.h"

namespace grpc {
class ServerCredentials;
}

namespace afmesh::server {

// The files; all empty means plaintext and no token (fit for loopback and unix sockets only).
struct SecurityFiles {
  // PEM certificate chain the server presents (leaf first); with tls_key turns TLS on.
  std::string tls_cert;
  // PEM private key of tls_cert's first certificate, unencrypted.
  std::string tls_key;
  // PEM CA bundle: when set, a client must present a certificate signed by one of these CAs or
  // its handshake fails (mutual TLS). Needs tls_cert.
  std::string tls_client_ca;
  // A file holding the token (security/token_file.h): when set, every Mesher call must carry
  // "authorization: Bearer <token>" or ends UNAUTHENTICATED before its input is read.
  std::string token_file;
};

struct ServerSecurity {
  // For ServerBuilder::AddListeningPort: SSL credentials, or insecure ones without TLS.
  std::shared_ptr<grpc::ServerCredentials> credentials;
  bool tls = false;
  bool mutual_tls = false;
  // The token calls must present; empty when none is asked for.
  std::string bearer_token;

  // "TLS, client certificates required, bearer token required", "plaintext, no token", ...
  std::string describe() const;
};

// Reads and checks the files. INVALID_ARGUMENT naming the flag and the file when one cannot be
// read or is not what its flag needs (no certificate, a key that does not match the
// certificate, ...), or when the flags do not go together (a key without a certificate, a
// client CA without TLS).
absl::StatusOr<ServerSecurity> load_server_security(const SecurityFiles& files);

}  // namespace afmesh::server
