// `afmesh volume` against an `afmesh-server` with mutual TLS and a bearer token, both binaries
// as a user runs them, with certificates made by openssl in the test: served with every
// credential, refused (with the exit code and message a user acts on) without each one; bad
// files refused at start-up by name.
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <thread>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/server/cli_test_support.h"
#include "tests/server/test_certificates.h"

namespace afmesh {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;

using cli_test::exit_status;
using cli_test::kTetrahedronFront;
using cli_test::read_file;
using cli_test::shell_quoted;

// One afmesh-server with mutual TLS and a token on a free loopback port, for the whole suite.
class CliSecurityTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    char pattern[] = "/tmp/afmesh-cli-security-test-XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    pki_ = new testing::TestCertificates{pattern};
    const absl::Status made = testing::make_test_certificates(pki_->dir);
    ASSERT_TRUE(made.ok()) << made;
    std::ofstream(pki_->dir / "token") << "cli-test-token\n";
    std::ofstream(pki_->dir / "wrong-token") << "not-the-token\n";
    std::ofstream(pki_->dir / "front.mesh") << kTetrahedronFront;
    start_server();
  }

  static void start_server() {
    const std::string log = (pki_->dir / "server.log").string();
    server_ = cli_test::start_server_process(
        AFMESH_SERVER_BINARY,
        {"--listen", "127.0.0.1:0", "--workers", "1", "--tls-cert", pki_->server_cert(),
         "--tls-key", pki_->server_key(), "--tls-client-ca", pki_->ca_cert(), "--token-file",
         (pki_->dir / "token").string()},
        log);
    ASSERT_GE(server_, 0);
    // The chosen port is in the start-up line.
    const std::regex listening("listening on 127\\.0\\.0\\.1:([0-9]+) ");
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    std::smatch match;
    while (std::chrono::steady_clock::now() < give_up) {
      start_line_ = read_file(log);
      if (std::regex_search(start_line_, match, listening)) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_FALSE(match.empty()) << start_line_;
    port_ = match[1];
  }

  static void TearDownTestSuite() {
    if (server_ > 0) {
      kill(server_, SIGTERM);
      int status = 0;
      waitpid(server_, &status, 0);
    }
    fs::remove_all(pki_->dir);
    delete pki_;
  }

  static std::string file(const std::string& name) { return (pki_->dir / name).string(); }

  // Runs `command` with stdout and stderr in files; returns the exit status.
  int run(const std::string& command) {
    const std::string line = command + " >" + shell_quoted(file("stdout.txt")) + " 2>" +
                             shell_quoted(file("stderr.txt"));
    return exit_status(std::system(line.c_str()));
  }

  // `afmesh volume front.mesh -o out.vtu --server 127.0.0.1:PORT ARGS`.
  int volume(const std::string& args) {
    fs::remove(file("out.vtu"));
    return run(std::string(AFMESH_CLI_BINARY) + " volume " + shell_quoted(file("front.mesh")) +
               " -o " + shell_quoted(file("out.vtu")) + " --quiet --server 127.0.0.1:" + port_ +
               " " + args);
  }

  std::string tls_flags() const {
    return "--tls-ca " + shell_quoted(pki_->ca_cert()) + " --tls-cert " +
           shell_quoted(pki_->client_cert()) + " --tls-key " + shell_quoted(pki_->client_key());
  }
  std::string stderr_text() const { return read_file(file("stderr.txt")); }

  static testing::TestCertificates* pki_;
  static pid_t server_;
  static std::string port_;
  static std::string start_line_;
};

testing::TestCertificates* CliSecurityTest::pki_ = nullptr;
pid_t CliSecurityTest::server_ = -1;
std::string CliSecurityTest::port_;
std::string CliSecurityTest::start_line_;

TEST_F(CliSecurityTest, ServerSaysItIsLoopbackOnlyAndWhatItAsks) {
  EXPECT_THAT(start_line_,
              HasSubstr("afmesh-server: listening on 127.0.0.1:" + port_ +
                        " (loopback only; use --listen 0.0.0.0:" + port_ +
                        " to serve other hosts); TLS, client certificates required, bearer "
                        "token required"));
}

TEST_F(CliSecurityTest, EveryCredentialGivenIsServed) {
  EXPECT_EQ(volume(tls_flags() + " --token-file " + shell_quoted(file("token"))), 0)
      << stderr_text();
  EXPECT_TRUE(fs::exists(file("out.vtu")));
}

TEST_F(CliSecurityTest, MissingOrWrongTokenExitsUnauthenticated) {
  EXPECT_EQ(volume(tls_flags()), 8);
  EXPECT_THAT(stderr_text(), HasSubstr("needs a bearer token"));
  EXPECT_EQ(volume(tls_flags() + " --token-file " + shell_quoted(file("wrong-token"))), 8);
  EXPECT_THAT(stderr_text(), HasSubstr("the bearer token is not valid"));
  EXPECT_FALSE(fs::exists(file("out.vtu")));
}

// --retries 0: a refused handshake looks like an unreachable server, which the CLI retries.
TEST_F(CliSecurityTest, MissingClientCertificateOrTlsCannotReachTheServer) {
  const std::string token = " --retries 0 --token-file " + shell_quoted(file("token"));
  EXPECT_EQ(volume("--tls-ca " + shell_quoted(pki_->ca_cert()) + token), 5);
  EXPECT_THAT(stderr_text(), HasSubstr("cannot reach the server"));
  EXPECT_EQ(volume(token.substr(1)), 5);  // plaintext against TLS
  EXPECT_THAT(stderr_text(), HasSubstr("cannot reach the server"));
}

TEST_F(CliSecurityTest, BadClientFlagsAreUsageErrorsNamingTheFile) {
  const std::string missing = file("missing-ca.crt");
  EXPECT_EQ(volume("--tls-ca " + shell_quoted(missing)), 2);
  EXPECT_THAT(stderr_text(), AllOf(HasSubstr("--tls-ca"), HasSubstr(missing)));
  EXPECT_EQ(volume("--tls-ca " + shell_quoted(pki_->ca_cert()) + " --tls-cert " +
                   shell_quoted(pki_->client_cert())),
            2);
  EXPECT_THAT(stderr_text(), HasSubstr("--tls-cert and --tls-key go together"));
  // Without --server the private server needs no credentials.
  EXPECT_EQ(
      run(std::string(AFMESH_CLI_BINARY) + " volume " + shell_quoted(file("front.mesh")) + " -o " +
          shell_quoted(file("out.vtu")) + " --token-file " + shell_quoted(file("token"))),
      2);
  EXPECT_THAT(stderr_text(), HasSubstr("give --server"));
}

TEST_F(CliSecurityTest, ServerWithAnUnreadableCertificateExitsOneNamingIt) {
  const std::string missing = file("missing-server.crt");
  EXPECT_EQ(run(std::string(AFMESH_SERVER_BINARY) + " --listen 127.0.0.1:0 --tls-cert " +
                shell_quoted(missing) + " --tls-key " + shell_quoted(pki_->server_key())),
            1);
  EXPECT_THAT(stderr_text(),
              HasSubstr("afmesh-server: --tls-cert " + missing + ": cannot be read"));
  EXPECT_EQ(
      run(std::string(AFMESH_SERVER_BINARY) + " --listen 127.0.0.1:0 --tls-cert " +
          shell_quoted(pki_->server_cert()) + " --tls-key " + shell_quoted(pki_->client_key())),
      1);
  EXPECT_THAT(stderr_text(), HasSubstr("does not belong to the certificate"));
}

}  // namespace
}  // namespace afmesh
