#include "client/channel_credentials.h"

#include <utility>

#include "absl/strings/str_cat.h"
#include "grpcpp/grpcpp.h"
#include "security/pem_files.h"
#include "security/token_file.h"

namespace afmesh::cli {
namespace {

absl::Status check_flags_go_together(const ClientSecurityFiles& files) {
  if (files.tls_cert.empty() != files.tls_key.empty()) {
    return absl::InvalidArgumentError(
        "--tls-cert and --tls-key go together: a client certificate needs its key");
  }
  if (!files.tls_cert.empty() && files.tls_ca.empty()) {
    return absl::InvalidArgumentError(
        "--tls-cert needs --tls-ca: the CA bundle the server's certificate is checked against");
  }
  return absl::OkStatus();
}

absl::StatusOr<std::shared_ptr<grpc::ChannelCredentials>> tls_credentials(
    const ClientSecurityFiles& files) {
  grpc::SslCredentialsOptions options;
  absl::StatusOr<std::string> ca = security::read_certificates(files.tls_ca, "--tls-ca");
  if (!ca.ok()) return ca.status();
  options.pem_root_certs = *std::move(ca);
  if (!files.tls_cert.empty()) {
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
    options.pem_cert_chain = *std::move(certificate);
    options.pem_private_key = *std::move(key);
  }
  return grpc::SslCredentials(options);
}

}  // namespace

bool ClientSecurityFiles::any() const {
  return !tls_ca.empty() || !tls_cert.empty() || !tls_key.empty() || !token_file.empty();
}

void add_client_security_flags(CLI::App& command, ClientSecurityFiles& files) {
  command.add_option("--tls-ca", files.tls_ca,
                     "connect with TLS, trusting the PEM CA bundle in FILE (needs --server)");
  command.add_option("--tls-cert", files.tls_cert,
                     "PEM client certificate, for a server that requires one (needs --tls-key)");
  command.add_option("--tls-key", files.tls_key, "PEM private key of --tls-cert (unencrypted)");
  command.add_option("--token-file", files.token_file,
                     "send the bearer token in FILE with the call (authorization: Bearer)");
}

ClientSecurity::ClientSecurity() : credentials_(grpc::InsecureChannelCredentials()) {}

std::shared_ptr<grpc::ChannelCredentials> ClientSecurity::channel_credentials() const {
  return credentials_;
}

void ClientSecurity::add_to(grpc::ClientContext& context) const {
  if (!token_.empty()) {
    context.AddMetadata(security::kAuthorizationKey, absl::StrCat(security::kBearerPrefix, token_));
  }
}

absl::StatusOr<ClientSecurity> load_client_security(const ClientSecurityFiles& files) {
  if (absl::Status status = check_flags_go_together(files); !status.ok()) return status;
  ClientSecurity security;
  if (!files.tls_ca.empty()) {
    absl::StatusOr<std::shared_ptr<grpc::ChannelCredentials>> credentials = tls_credentials(files);
    if (!credentials.ok()) return credentials.status();
    security.credentials_ = *std::move(credentials);
    security.tls_ = true;
  }
  if (!files.token_file.empty()) {
    absl::StatusOr<std::string> token = security::read_token_file(files.token_file, "--token-file");
    if (!token.ok()) return token.status();
    security.token_ = *std::move(token);
  }
  return security;
}

}  // namespace afmesh::cli
