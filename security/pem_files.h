// PEM files named on the command line (TLS certificate chains, private keys, CA bundles), read
// once at start-up and checked with OpenSSL, so that a wrong file is reported by name before
// any connection is attempted rather than as a failed handshake later.
#pragma once

#include <string>

#include "absl/status/statusor.h"

namespace afmesh::security {

// The text of `path`, which must hold at least one PEM certificate ("-----BEGIN CERTIFICATE"),
// every one of them parseable. `what` names the file's role in messages ("--tls-cert").
// INVALID_ARGUMENT naming the flag and the path when the file cannot be read or holds no valid
// certificate.
absl::StatusOr<std::string> read_certificates(const std::string& path, const std::string& what);

// The text of `path`, which must hold one unencrypted PEM private key (PKCS#8, RSA or EC).
// INVALID_ARGUMENT naming the flag and the path otherwise.
absl::StatusOr<std::string> read_private_key(const std::string& path, const std::string& what);

// OK when the first certificate of `certificate_pem` carries the public half of `key_pem`;
// INVALID_ARGUMENT naming both files otherwise. Both must have passed the readers above.
absl::Status check_key_matches(const std::string& certificate_pem,
                               const std::string& certificate_path, const std::string& key_pem,
                               const std::string& key_path);

}  // namespace afmesh::security
