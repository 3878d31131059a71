// security/: the constant-time comparison of the bearer token, the token file, the PEM readers
// (with certificates made by openssl in the test) and who can reach an address.
#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "security/address_reach.h"
#include "security/constant_time_equal.h"
#include "security/pem_files.h"
#include "security/token_file.h"
#include "tests/server/test_certificates.h"

namespace afmesh::security {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

// ----- constant_time_equal --------------------------------------------------------------------

TEST(ConstantTimeEqual, EqualStringsAreEqual) {
  EXPECT_TRUE(constant_time_equal("s3cr3t-token", "s3cr3t-token"));
  EXPECT_TRUE(constant_time_equal("", ""));
  const std::string with_nul("a\0b", 3);
  EXPECT_TRUE(constant_time_equal(with_nul, with_nul));
}

TEST(ConstantTimeEqual, AnyDifferingByteMakesThemDiffer) {
  const std::string secret = "0123456789abcdef";
  for (std::size_t i = 0; i < secret.size(); ++i) {
    std::string presented = secret;
    presented[i] ^= 0x01;
    EXPECT_FALSE(constant_time_equal(presented, secret)) << "byte " << i;
    presented[i] = static_cast<char>(secret[i] ^ 0x80);
    EXPECT_FALSE(constant_time_equal(presented, secret)) << "byte " << i;
  }
}

TEST(ConstantTimeEqual, PrefixesExtensionsAndRepetitionsDiffer) {
  EXPECT_FALSE(constant_time_equal("abc", "abcd"));
  EXPECT_FALSE(constant_time_equal("abcd", "abc"));
  EXPECT_FALSE(constant_time_equal("", "abc"));
  EXPECT_FALSE(constant_time_equal("abc", ""));
  // The secret is cycled over a longer presented string: its repetition must still differ.
  EXPECT_FALSE(constant_time_equal("abcabc", "abc"));
  EXPECT_FALSE(constant_time_equal("aaaa", "a"));
}

// Minimum time of `repetitions` comparisons of `presented` with `secret`, in nanoseconds.
double min_nanoseconds(const std::string& presented, const std::string& secret, int repetitions) {
  double best = 1e300;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const bool equal = constant_time_equal(presented, secret);
    const auto stop = std::chrono::steady_clock::now();
    EXPECT_FALSE(equal);
    best = std::min(best, std::chrono::duration<double, std::nano>(stop - start).count());
  }
  return best;
}

// memcmp-like code returns at the first difference: for 256 KiB strings differing in their
// first byte it would be thousands of times faster than for ones differing in their last. The
// minimum over repetitions removes most scheduling noise; a factor of 3 leaves room for the
// rest on a shared machine while any early exit fails by orders of magnitude.
TEST(ConstantTimeEqual, TimeDoesNotDependOnWhereTheStringsDiffer) {
  const std::string secret(256 * 1024, 'k');
  std::string first = secret;
  first.front() = 'x';
  std::string last = secret;
  last.back() = 'x';
  const double first_ns = min_nanoseconds(first, secret, 15);
  const double last_ns = min_nanoseconds(last, secret, 15);
  EXPECT_LT(last_ns, 3 * first_ns) << first_ns << " ns vs " << last_ns << " ns";
  EXPECT_LT(first_ns, 3 * last_ns) << first_ns << " ns vs " << last_ns << " ns";
}

// ----- files ------------------------------------------------------------------------------------

class SecurityFilesTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    char pattern[] = "/tmp/afmesh-security-files-test-XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    certificates_ = new testing::TestCertificates{pattern};
    const absl::Status made = testing::make_test_certificates(certificates_->dir);
    ASSERT_TRUE(made.ok()) << made;
  }
  static void TearDownTestSuite() {
    fs::remove_all(certificates_->dir);
    delete certificates_;
  }

  static std::string write(const std::string& name, const std::string& text) {
    const fs::path path = certificates_->dir / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }
  static std::string read(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  static testing::TestCertificates* certificates_;
};

testing::TestCertificates* SecurityFilesTest::certificates_ = nullptr;

TEST_F(SecurityFilesTest, TokenIsTheFileWithoutItsTrailingNewline) {
  const absl::StatusOr<std::string> token =
      read_token_file(write("token", "Zm9v-bar_baz.42\n"), "--token-file");
  ASSERT_TRUE(token.ok()) << token.status();
  EXPECT_EQ(*token, "Zm9v-bar_baz.42");
  const absl::StatusOr<std::string> crlf =
      read_token_file(write("token-crlf", "abc\r\n \n"), "--token-file");
  ASSERT_TRUE(crlf.ok()) << crlf.status();
  EXPECT_EQ(*crlf, "abc");
}

TEST_F(SecurityFilesTest, MissingEmptyOrMalformedTokenFilesAreNamedButNotQuoted) {
  const std::string missing = (certificates_->dir / "no-such-token").string();
  EXPECT_THAT(read_token_file(missing, "--token-file").status().message(),
              AllOf(HasSubstr("--token-file"), HasSubstr(missing), HasSubstr("cannot be read")));
  const std::string empty = write("empty-token", "\n\n");
  EXPECT_THAT(read_token_file(empty, "--token-file").status().message(),
              AllOf(HasSubstr(empty), HasSubstr("empty")));
  const std::string spaced = write("spaced-token", "secret part two\n");
  const absl::Status status = read_token_file(spaced, "--token-file").status();
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), AllOf(HasSubstr(spaced), HasSubstr("character 7"),
                                      Not(HasSubstr("secret")), Not(HasSubstr("part"))));
  const std::string long_token = write("long-token", std::string(5000, 'a'));
  EXPECT_THAT(read_token_file(long_token, "--token-file").status().message(),
              HasSubstr("longer than 4096"));
}

TEST_F(SecurityFilesTest, CertificatesAndKeysMadeByOpensslAreRead) {
  const absl::StatusOr<std::string> chain = read_certificates(certificates_->server_cert(), "c");
  ASSERT_TRUE(chain.ok()) << chain.status();
  const absl::StatusOr<std::string> key = read_private_key(certificates_->server_key(), "k");
  ASSERT_TRUE(key.ok()) << key.status();
  EXPECT_TRUE(check_key_matches(*chain, "server.crt", *key, "server.key").ok());
  // A bundle of two CAs.
  const std::string bundle =
      write("bundle.crt", read(certificates_->ca_cert()) + read(certificates_->other_ca_cert()));
  EXPECT_TRUE(read_certificates(bundle, "--tls-client-ca").ok());
}

TEST_F(SecurityFilesTest, UnreadableOrInvalidPemFilesNameTheFlagAndTheFile) {
  const std::string missing = (certificates_->dir / "missing.crt").string();
  EXPECT_THAT(read_certificates(missing, "--tls-cert").status().message(),
              AllOf(HasSubstr("--tls-cert"), HasSubstr(missing), HasSubstr("cannot be read")));
  const std::string text = write("text.crt", "hello\n");
  EXPECT_THAT(read_certificates(text, "--tls-cert").status().message(),
              AllOf(HasSubstr(text), HasSubstr("no PEM certificate")));
  const std::string whole = read(certificates_->server_cert());
  const std::string cut =
      write("cut.crt", whole.substr(0, whole.size() / 2) + "\n-----END CERTIFICATE-----\n");
  EXPECT_THAT(read_certificates(cut, "--tls-cert").status().message(),
              AllOf(HasSubstr(cut), HasSubstr("certificate 1 cannot be parsed")));
  // A good certificate followed by a broken one.
  const std::string second = write("second-broken.crt", whole + whole.substr(0, 100));
  EXPECT_THAT(read_certificates(second, "--tls-cert").status().message(),
              HasSubstr("certificate 2 cannot be parsed"));
  // A certificate given where the key belongs.
  EXPECT_THAT(read_private_key(certificates_->server_cert(), "--tls-key").status().message(),
              AllOf(HasSubstr("--tls-key"), HasSubstr(certificates_->server_cert()),
                    HasSubstr("no PEM private key")));
  const std::string key = read(certificates_->server_key());
  const std::string broken_key =
      write("broken.key", key.substr(0, 40) + "\n-----END PRIVATE KEY-----\n");
  EXPECT_THAT(read_private_key(broken_key, "--tls-key").status().message(),
              AllOf(HasSubstr(broken_key), HasSubstr("cannot be parsed")));
}

TEST_F(SecurityFilesTest, EncryptedKeyIsRefusedWithoutPrompting) {
  const std::string encrypted = (certificates_->dir / "encrypted.key").string();
  const std::string command = "openssl pkey -in '" + certificates_->server_key() +
                              "' -aes256 -passout pass:pw -out '" + encrypted + "' 2>/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_THAT(read_private_key(encrypted, "--tls-key").status().message(),
              AllOf(HasSubstr(encrypted), HasSubstr("encrypted")));
}

TEST_F(SecurityFilesTest, KeyOfAnotherCertificateNamesBothFiles) {
  const absl::StatusOr<std::string> chain = read_certificates(certificates_->server_cert(), "c");
  const absl::StatusOr<std::string> key = read_private_key(certificates_->client_key(), "k");
  ASSERT_TRUE(chain.ok() && key.ok());
  const absl::Status status =
      check_key_matches(*chain, certificates_->server_cert(), *key, certificates_->client_key());
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(),
              AllOf(HasSubstr(certificates_->server_cert()), HasSubstr(certificates_->client_key()),
                    HasSubstr("does not belong")));
}

// ----- reach_of ---------------------------------------------------------------------------------

TEST(AddressReach, LoopbackLocalSocketsAndOtherHostsAreTold) {
  EXPECT_EQ(reach_of("127.0.0.1:50051"), Reach::kLoopback);
  EXPECT_EQ(reach_of("127.1.2.3:1"), Reach::kLoopback);
  EXPECT_EQ(reach_of("localhost:50051"), Reach::kLoopback);
  EXPECT_EQ(reach_of("[::1]:50051"), Reach::kLoopback);
  EXPECT_EQ(reach_of("ipv4:127.0.0.1:7"), Reach::kLoopback);
  EXPECT_EQ(reach_of("unix:/tmp/x.sock"), Reach::kLocalSocket);
  EXPECT_EQ(reach_of("unix-abstract:afmesh"), Reach::kLocalSocket);
  EXPECT_EQ(reach_of("0.0.0.0:50051"), Reach::kOtherHosts);
  EXPECT_EQ(reach_of("[::]:50051"), Reach::kOtherHosts);
  EXPECT_EQ(reach_of("mesher.example.org:443"), Reach::kOtherHosts);
  EXPECT_EQ(reach_of("128.0.0.1:50051"), Reach::kOtherHosts);
  EXPECT_EQ(reach_of("127.0.0.1.example.org:1"), Reach::kOtherHosts);  // a name, not an address
  EXPECT_EQ(reach_of("[::ffff:127.0.0.1]:1"), Reach::kLoopback);
}

TEST(AddressReach, PortIsTheTextAfterTheLastColon) {
  EXPECT_EQ(port_of("127.0.0.1:50051"), "50051");
  EXPECT_EQ(port_of("[::1]:7"), "7");
  EXPECT_EQ(port_of("[::1]"), "");
  EXPECT_EQ(port_of("ipv4:127.0.0.1:7"), "7");
  EXPECT_EQ(port_of("unix:/tmp/a:b"), "");
}

}  // namespace
}  // namespace afmesh::security
