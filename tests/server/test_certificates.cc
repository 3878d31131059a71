#include "tests/server/test_certificates.h"

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <vector>

#include "absl/strings/str_cat.h"

namespace afmesh::testing {
namespace {

namespace fs = std::filesystem;

std::string quoted(const fs::path& path) { return absl::StrCat("'", path.string(), "'"); }

void write_file(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

std::string read_file(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The openssl commands, run in `dir`.
std::vector<std::string> commands() {
  const std::string new_key =
      "openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:P-256 -out ";
  const std::string new_ca =
      "openssl req -x509 -new -days 1 -sha256 -config ext.cnf -extensions ca_ext ";
  return {
      new_key + "ca.key",
      new_ca + "-key ca.key -out ca.crt -subj /CN=afmesh-test-ca",
      new_key + "other-ca.key",
      new_ca + "-key other-ca.key -out other-ca.crt -subj /CN=afmesh-other-test-ca",
      new_key + "server.key",
      "openssl req -new -key server.key -out server.csr -subj /CN=localhost",
      "openssl x509 -req -days 1 -sha256 -set_serial 1 -extfile ext.cnf -extensions server_ext "
      "-in server.csr -CA ca.crt -CAkey ca.key -out server.crt",
      new_key + "client.key",
      "openssl req -new -key client.key -out client.csr -subj /CN=afmesh-test-client",
      "openssl x509 -req -days 1 -sha256 -set_serial 2 -extfile ext.cnf -extensions client_ext "
      "-in client.csr -CA ca.crt -CAkey ca.key -out client.crt",
      new_key + "other-client.key",
      "openssl req -new -key other-client.key -out other-client.csr -subj /CN=afmesh-other-client",
      "openssl x509 -req -days 1 -sha256 -set_serial 3 -extfile ext.cnf -extensions client_ext "
      "-in other-client.csr -CA other-ca.crt -CAkey other-ca.key -out other-client.crt",
  };
}

// The extensions of each kind of certificate; also a minimal config for `req`.
constexpr const char* kExtensions = R"([req]
distinguished_name = dn
[dn]
[ca_ext]
basicConstraints = critical, CA:TRUE
keyUsage = critical, keyCertSign, cRLSign
subjectKeyIdentifier = hash
[server_ext]
basicConstraints = critical, CA:FALSE
keyUsage = critical, digitalSignature
extendedKeyUsage = serverAuth
subjectAltName = DNS:localhost, IP:127.0.0.1, IP:::1
[client_ext]
basicConstraints = critical, CA:FALSE
keyUsage = critical, digitalSignature
extendedKeyUsage = clientAuth
)";

}  // namespace

absl::Status make_test_certificates(const fs::path& dir) {
  write_file(dir / "ext.cnf", kExtensions);
  const fs::path log = dir / "openssl.log";
  for (const std::string& command : commands()) {
    const std::string line =
        absl::StrCat("cd ", quoted(dir), " && ", command, " >>", quoted(log), " 2>&1");
    if (std::system(line.c_str()) != 0) {
      return absl::InternalError(
          absl::StrCat("`", command, "` failed in ", dir.string(), ":\n", read_file(log)));
    }
  }
  return absl::OkStatus();
}

}  // namespace afmesh::testing
