#include "server/credentials.h"

#include <utility>

#include "absl/strings/str_cat.h"
#include "grpcpp/security/server_credentials.h"
#include "security/pem_files.h"
#include "security/token_file.h"

namespace afmesh::server {
namespace {

absl::Status check_flags_go_together(const SecurityFiles& files) {
  if (files.tls_cert.empty() != files.tls_key.empty()) {
    return absl::InvalidArgumentError(
        "--tls-cert and --tls-key go together: TLS needs both the certificate and its key");
  }
  if (!files.tls_client_ca.empty() && files.tls_cert.empty()) {
    return absl::InvalidArgumentError(
        "--tls-client-ca needs --tls-cert and --tls-key: client certificates are checked "
        "during a TLS handshake");
  }
  return absl::OkStatus();
}

absl::StatusOr<std::shared_ptr<grpc::ServerCredentials>> tls_credentials(
    const SecurityFiles& files) {
  absl::StatusOr<std::string> certificate =
      security::read_certificates(files.tls_cert, "--tls-cert");
  if (!certificate.ok()) return certificate.status();
  absl::StatusOr<std::string> key = security::read_private_key(files.tls_key, "--tls-key");
  if (!key.ok()) return key.status();
  if (absl::Status status =
          security::check_key_matches(*certificate, files.tls_cert, *key, files.tls_key);
      !status.ok()) {
    return status;
  }
  grpc::SslServerCredentialsOptions options(
      files.tls_client_ca.empty() ? GRPC_SSL_DONT_REQUEST_CLIENT_CERTIFICATE
                                  : GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY);
  if (!files.tls_client_ca.empty()) {
    absl::StatusOr<std::string> client_ca =
        security::read_certificates(files.tls_client_ca, "--tls-client-ca");
    if (!client_ca.ok()) return client_ca.status();
    options.pem_root_certs = *std::move(client_ca);
  }
  options.pem_key_cert_pairs.push_back({*std::move(key), *std::move(certificate)});
  return grpc::SslServerCredentials(options);
}

}  // namespace

std::string ServerSecurity::describe() const {
  const char* transport = mutual_tls ? "TLS, client certificates required"
                          : tls      ? "TLS"
                                     : "plaintext";
  return absl::StrCat(transport, bearer_token.empty() ? ", no token" : ", bearer token required");
}

absl::StatusOr<ServerSecurity> load_server_security(const SecurityFiles& files) {
  if (absl::Status status = check_flags_go_together(files); !status.ok()) return status;
  ServerSecurity security;
  if (files.tls_cert.empty()) {
    security.credentials = grpc::InsecureServerCredentials();
  } else {
    absl::StatusOr<std::shared_ptr<grpc::ServerCredentials>> credentials = tls_credentials(files);
    if (!credentials.ok()) return credentials.status();
    security.credentials = *std::move(credentials);
    security.tls = true;
    security.mutual_tls = !files.tls_client_ca.empty();
  }
  if (!files.token_file.empty()) {
    absl::StatusOr<std::string> token = security::read_token_file(files.token_file, "--token-file");
    if (!token.ok()) return token.status();
    security.bearer_token = *std::move(token);
  }
  return security;
}

}  // namespace afmesh::server
