// A throwaway PKI for the TLS tests, made with the openssl command line in a folder of the
// test's own: a CA, a server certificate for localhost / 127.0.0.1 / ::1, a client certificate,
// and a second CA with a client certificate of its own (one the server must not accept).
// EC P-256 keys, valid for one day.
#pragma once

#include <filesystem>
#include <string>

#include "absl/status/status.h"

namespace afmesh::testing {

struct TestCertificates {
  std::filesystem::path dir;

  std::string ca_cert() const { return (dir / "ca.crt").string(); }
  std::string server_cert() const { return (dir / "server.crt").string(); }
  std::string server_key() const { return (dir / "server.key").string(); }
  std::string client_cert() const { return (dir / "client.crt").string(); }
  std::string client_key() const { return (dir / "client.key").string(); }
  // Signed by another CA than ca.crt.
  std::string other_ca_cert() const { return (dir / "other-ca.crt").string(); }
  std::string other_client_cert() const { return (dir / "other-client.crt").string(); }
  std::string other_client_key() const { return (dir / "other-client.key").string(); }
};

// Makes the files in `dir` (which must exist). INTERNAL with openssl's output when a command
// fails.
absl::Status make_test_certificates(const std::filesystem::path& dir);

}  // namespace afmesh::testing
