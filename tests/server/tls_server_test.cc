// afmesh-server's security in-process, with certificates made by openssl in the test: TLS,
// mutual TLS and the bearer token, each accepted with the right credentials and refused
// without them; the token checked before the server reads any input; bad files refused at
// start-up by name. Fake meshing job (no mesher linked).
#include <stdlib.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_split.h"
#include "afmesh/v1/mesher.grpc.pb.h"
#include "gmock/gmock.h"
#include "grpc/grpc.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "grpcpp/grpcpp.h"
#include "gtest/gtest.h"
#include "server/credentials.h"
#include "server/listen_note.h"
#include "server/server.h"
#include "tests/server/request_support.h"
#include "tests/server/test_certificates.h"

namespace afmesh::server {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using Request = v1::MeshVolumeRequest;
using Response = v1::MeshVolumeResponse;

constexpr const char* kToken = "afmesh-test-token-7f3a9c";

using afmesh::testing::tetrahedron_requests;

// Counts its runs and meshes the tetrahedron as one tet.
VolumeJob counting_job(std::shared_ptr<std::atomic<int>> runs) {
  return
      [runs](const Mesh& front, const VolumeParams&, Progress&) -> absl::StatusOr<VolumeJobOutput> {
        runs->fetch_add(1);
        VolumeJobOutput output;
        output.volume.mesh = front;
        output.volume.mesh.tets = {{0, 1, 2, 3}};
        output.volume.mesh.tet_tags = {0};
        output.validation.passed = true;
        return output;
      };
}

// Security flags as afmesh-server takes them ("" = not given).
SecurityFiles security_files(const std::string& cert, const std::string& key,
                             const std::string& client_ca, const std::string& token) {
  SecurityFiles files;
  files.tls_cert = cert;
  files.tls_key = key;
  files.tls_client_ca = client_ca;
  files.token_file = token;
  return files;
}

struct Outcome {
  grpc::Status status;
  int tets = 0;  // tet indices received / 4
};

class TlsServerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    static const bool initialised = (grpc_init(), true);
    (void)initialised;
    char pattern[] = "/tmp/afmesh-tls-test-XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    pki_ = new testing::TestCertificates{pattern};
    const absl::Status made = testing::make_test_certificates(pki_->dir);
    ASSERT_TRUE(made.ok()) << made;
    std::ofstream(pki_->dir / "token") << kToken << "\n";
  }
  static void TearDownTestSuite() {
    fs::remove_all(pki_->dir);
    delete pki_;
  }

  void TearDown() override {
    if (server_ != nullptr) server_->shutdown();
  }

  static SecurityFiles tls_files() {
    return security_files(pki_->server_cert(), pki_->server_key(), "", "");
  }
  static SecurityFiles mutual_tls_files() {
    SecurityFiles files = tls_files();
    files.tls_client_ca = pki_->ca_cert();
    return files;
  }
  static SecurityFiles token_files() {
    return security_files("", "", "", (pki_->dir / "token").string());
  }

  // Starts a server on a free loopback port with `files`.
  void start(const SecurityFiles& files) {
    ServerOptions options;
    options.listen = "127.0.0.1:0";
    options.workers = 1;
    options.service.log_calls = false;
    options.security = files;
    absl::StatusOr<std::unique_ptr<MesherServer>> server =
        MesherServer::start(options, counting_job(runs_));
    ASSERT_TRUE(server.ok()) << server.status();
    server_ = *std::move(server);
  }

  // What a client trusting the test CA uses, optionally with a client certificate.
  static std::shared_ptr<grpc::ChannelCredentials> tls_client(const std::string& ca,
                                                              const std::string& cert = "",
                                                              const std::string& key = "") {
    grpc::SslCredentialsOptions options;
    options.pem_root_certs = read(ca);
    if (!cert.empty()) {
      options.pem_cert_chain = read(cert);
      options.pem_private_key = read(key);
    }
    return grpc::SslCredentials(options);
  }

  static std::string read(const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  std::unique_ptr<v1::Mesher::Stub> stub(std::shared_ptr<grpc::ChannelCredentials> credentials) {
    return v1::Mesher::NewStub(grpc::CreateChannel(server_->address(), credentials));
  }

  // A deadline for calls expected to fail fast: long enough never to be what ends them.
  static void set_deadline(grpc::ClientContext& context) {
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  }

  // Meshes the tetrahedron; `authorization` (when not empty) goes as that metadata entry.
  Outcome mesh(std::shared_ptr<grpc::ChannelCredentials> credentials,
               const std::string& authorization = "") {
    const std::unique_ptr<v1::Mesher::Stub> mesher = stub(std::move(credentials));
    grpc::ClientContext context;
    set_deadline(context);
    if (!authorization.empty()) context.AddMetadata("authorization", authorization);
    const auto stream = mesher->MeshVolume(&context);
    for (const Request& request : tetrahedron_requests()) {
      if (!stream->Write(request)) break;
    }
    stream->WritesDone();
    Outcome outcome;
    Response response;
    while (stream->Read(&response)) {
      if (response.has_tets()) outcome.tets += response.tets().indices_size() / 4;
    }
    outcome.status = stream->Finish();
    return outcome;
  }

  static testing::TestCertificates* pki_;
  std::shared_ptr<std::atomic<int>> runs_ = std::make_shared<std::atomic<int>>(0);
  std::unique_ptr<MesherServer> server_;
};

testing::TestCertificates* TlsServerTest::pki_ = nullptr;

// ----- TLS and mutual TLS -----------------------------------------------------------------------

TEST_F(TlsServerTest, CallOverTlsSucceeds) {
  start(tls_files());
  const Outcome outcome = mesh(tls_client(pki_->ca_cert()));
  EXPECT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  EXPECT_EQ(outcome.tets, 1);
  EXPECT_EQ(runs_->load(), 1);
  EXPECT_TRUE(server_->security().tls);
  EXPECT_FALSE(server_->security().mutual_tls);
}

TEST_F(TlsServerTest, PlaintextClientAgainstTlsServerFails) {
  start(tls_files());
  const Outcome outcome = mesh(grpc::InsecureChannelCredentials());
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::UNAVAILABLE)
      << outcome.status.error_message();
  EXPECT_EQ(runs_->load(), 0);
}

TEST_F(TlsServerTest, ClientTrustingAnotherCaRefusesTheServer) {
  start(tls_files());
  const Outcome outcome = mesh(tls_client(pki_->other_ca_cert()));
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::UNAVAILABLE)
      << outcome.status.error_message();
  EXPECT_EQ(runs_->load(), 0);
}

TEST_F(TlsServerTest, MutualTlsServesAClientWithACertificateOfTheClientCa) {
  start(mutual_tls_files());
  EXPECT_TRUE(server_->security().mutual_tls);
  const Outcome outcome =
      mesh(tls_client(pki_->ca_cert(), pki_->client_cert(), pki_->client_key()));
  EXPECT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  EXPECT_EQ(outcome.tets, 1);
}

TEST_F(TlsServerTest, MutualTlsRefusesAClientWithoutCertificate) {
  start(mutual_tls_files());
  const Outcome outcome = mesh(tls_client(pki_->ca_cert()));
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::UNAVAILABLE)
      << outcome.status.error_message();
  EXPECT_EQ(runs_->load(), 0);
}

TEST_F(TlsServerTest, MutualTlsRefusesACertificateOfAnotherCa) {
  start(mutual_tls_files());
  const Outcome outcome =
      mesh(tls_client(pki_->ca_cert(), pki_->other_client_cert(), pki_->other_client_key()));
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::UNAVAILABLE)
      << outcome.status.error_message();
  EXPECT_EQ(runs_->load(), 0);
}

// ----- the bearer token -------------------------------------------------------------------------

TEST_F(TlsServerTest, RightTokenIsServed) {
  start(token_files());
  const Outcome outcome = mesh(grpc::InsecureChannelCredentials(), std::string("Bearer ") + kToken);
  EXPECT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  EXPECT_EQ(outcome.tets, 1);
  // The scheme's case does not matter (RFC 7235); the token's does.
  EXPECT_TRUE(
      mesh(grpc::InsecureChannelCredentials(), std::string("bearer ") + kToken).status.ok());
}

TEST_F(TlsServerTest, MissingOrWrongTokenIsUnauthenticated) {
  start(token_files());
  const std::string token = kToken;
  const std::vector<std::string> wrong = {
      "",  // no metadata at all
      "Bearer " + token.substr(0, token.size() - 1),
      "Bearer " + token + "x",
      "Bearer " + std::string(token.size(), 'a'),
      "Bearer AFMESH-TEST-TOKEN-7F3A9C",
      "Basic " + token,
      token,
      "Bearer",
  };
  for (const std::string& authorization : wrong) {
    const Outcome outcome = mesh(grpc::InsecureChannelCredentials(), authorization);
    EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::UNAUTHENTICATED)
        << "'" << authorization << "': " << outcome.status.error_message();
    EXPECT_THAT(outcome.status.error_message(), Not(HasSubstr(kToken)));
    EXPECT_EQ(outcome.tets, 0);
  }
  EXPECT_THAT(mesh(grpc::InsecureChannelCredentials()).status.error_message(),
              HasSubstr("authorization: Bearer <token>"));
  EXPECT_EQ(runs_->load(), 0);
}

TEST_F(TlsServerTest, TwoAuthorizationEntriesAreUnauthenticated) {
  start(token_files());
  const std::unique_ptr<v1::Mesher::Stub> mesher = stub(grpc::InsecureChannelCredentials());
  grpc::ClientContext context;
  set_deadline(context);
  context.AddMetadata("authorization", "Bearer wrong");
  context.AddMetadata("authorization", std::string("Bearer ") + kToken);
  const auto stream = mesher->MeshVolume(&context);
  stream->WritesDone();
  EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::UNAUTHENTICATED);
}

// The call is refused as soon as it arrives: a client that sends nothing and never half-closes
// still gets UNAUTHENTICATED at once.
TEST_F(TlsServerTest, TokenIsCheckedBeforeTheClientSendsAnything) {
  start(token_files());
  const std::unique_ptr<v1::Mesher::Stub> mesher = stub(grpc::InsecureChannelCredentials());
  grpc::ClientContext context;
  set_deadline(context);
  const Clock::time_point start = Clock::now();
  const auto stream = mesher->MeshVolume(&context);
  Response response;
  EXPECT_FALSE(stream->Read(&response));
  EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(2));
}

// An input the server would refuse on reading its header (over the point limit) is refused for
// its missing token instead: the header was never read.
TEST_F(TlsServerTest, TokenIsCheckedBeforeTheInputIsRead) {
  start(token_files());
  std::vector<Request> requests = tetrahedron_requests();
  requests.front().mutable_header()->set_point_count(1'000'000'000'000);
  const std::unique_ptr<v1::Mesher::Stub> mesher = stub(grpc::InsecureChannelCredentials());
  grpc::ClientContext context;
  set_deadline(context);
  const auto stream = mesher->MeshVolume(&context);
  for (const Request& request : requests) {
    if (!stream->Write(request)) break;
  }
  stream->WritesDone();
  const grpc::Status status = stream->Finish();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAUTHENTICATED) << status.error_message();

  // With the token, the same input reaches the limit check.
  grpc::ClientContext with_token;
  set_deadline(with_token);
  with_token.AddMetadata("authorization", std::string("Bearer ") + kToken);
  const auto served = mesher->MeshVolume(&with_token);
  for (const Request& request : requests) {
    if (!served->Write(request)) break;
  }
  served->WritesDone();
  EXPECT_NE(served->Finish().error_code(), grpc::StatusCode::UNAUTHENTICATED);
}

// A client streaming 256 MiB without the token is stopped after a small part of it: its writes
// fail once the server has refused the call, which it does without reading.
TEST_F(TlsServerTest, LargeUploadWithoutTokenIsRefusedFast) {
  start(token_files());
  Request slice;
  for (int i = 0; i < 3 * 43'690; ++i) slice.mutable_points()->add_xyz(i);  // ~1 MiB
  const std::unique_ptr<v1::Mesher::Stub> mesher = stub(grpc::InsecureChannelCredentials());
  grpc::ClientContext context;
  set_deadline(context);
  const Clock::time_point start = Clock::now();
  const auto stream = mesher->MeshVolume(&context);
  Request header = tetrahedron_requests().front();
  header.mutable_header()->set_point_count(256 * 43'690);
  int written = 0;
  if (stream->Write(header)) {
    while (written < 256 && stream->Write(slice)) ++written;
  }
  const grpc::Status status = stream->Finish();
  const auto elapsed = Clock::now() - start;
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAUTHENTICATED) << status.error_message();
  EXPECT_LT(written, 16) << "MiB accepted before the refusal";
  EXPECT_LT(elapsed, std::chrono::seconds(2));
}

// Health carries no meshes and orchestrators probe it without credentials: it needs no token.
TEST_F(TlsServerTest, HealthNeedsNoToken) {
  start(token_files());
  auto health = grpc::health::v1::Health::NewStub(
      grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  set_deadline(context);
  grpc::health::v1::HealthCheckResponse response;
  ASSERT_TRUE(health->Check(&context, {}, &response).ok());
  EXPECT_EQ(response.status(), grpc::health::v1::HealthCheckResponse::SERVING);
}

TEST_F(TlsServerTest, MutualTlsAndTokenTogether) {
  SecurityFiles files = mutual_tls_files();
  files.token_file = token_files().token_file;
  start(files);
  const auto credentials = tls_client(pki_->ca_cert(), pki_->client_cert(), pki_->client_key());
  EXPECT_EQ(mesh(credentials).status.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_TRUE(mesh(credentials, std::string("Bearer ") + kToken).status.ok());
  EXPECT_EQ(server_->security().describe(),
            "TLS, client certificates required, bearer token required");
}

// ----- the log line per call --------------------------------------------------------------------

// A served call and a refused one each leave one structured line (server/call_log.h); the
// refused one read nothing.
TEST_F(TlsServerTest, EachCallLogsOneStructuredLine) {
  ServerOptions options;
  options.listen = "127.0.0.1:0";
  options.workers = 1;
  options.security = token_files();
  absl::StatusOr<std::unique_ptr<MesherServer>> server =
      MesherServer::start(options, counting_job(runs_));
  ASSERT_TRUE(server.ok()) << server.status();
  server_ = *std::move(server);
  ::testing::internal::CaptureStderr();
  const Outcome served = mesh(grpc::InsecureChannelCredentials(), std::string("Bearer ") + kToken);
  const Outcome refused = mesh(grpc::InsecureChannelCredentials());
  const std::string log = ::testing::internal::GetCapturedStderr();
  ASSERT_TRUE(served.status.ok()) << served.status.error_message();
  ASSERT_EQ(refused.status.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  const std::vector<std::string> lines = absl::StrSplit(log, '\n', absl::SkipEmpty());
  ASSERT_EQ(lines.size(), 2u) << log;
  EXPECT_THAT(lines[0], AllOf(HasSubstr("rpc=MeshVolume peer=ipv4:127.0.0.1:"),
                              HasSubstr("messages_in=3"), HasSubstr("points_in=4 triangles_in=4"),
                              HasSubstr("outcome=ok code=OK points_out=4 tets_out=1")));
  EXPECT_THAT(lines[1], AllOf(HasSubstr("messages_in=0 bytes_in=0 points_in=0"),
                              HasSubstr("outcome=refused code=UNAUTHENTICATED"),
                              HasSubstr("message=\"this server needs a bearer token")));
}

// ----- start-up ---------------------------------------------------------------------------------

// Start-up with `files` fails INVALID_ARGUMENT with a message holding `part`.
void expect_start_refused(const SecurityFiles& files, const std::string& part) {
  ServerOptions options;
  options.listen = "127.0.0.1:0";
  options.security = files;
  const absl::StatusOr<std::unique_ptr<MesherServer>> server =
      MesherServer::start(options, counting_job(std::make_shared<std::atomic<int>>(0)));
  ASSERT_FALSE(server.ok());
  EXPECT_EQ(server.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(server.status().message(), HasSubstr(part));
}

TEST_F(TlsServerTest, BadSecurityFilesStopTheStartNamingTheFile) {
  const std::string missing = (pki_->dir / "missing.crt").string();
  expect_start_refused(security_files(missing, pki_->server_key(), "", ""), missing);
  expect_start_refused(security_files(pki_->server_key(), pki_->server_key(), "", ""),
                       "--tls-cert " + pki_->server_key() + ": no PEM certificate");
  expect_start_refused(security_files(pki_->server_cert(), pki_->client_key(), "", ""),
                       "does not belong");
  SecurityFiles bad_ca = tls_files();
  bad_ca.tls_client_ca = pki_->server_key();
  expect_start_refused(bad_ca, "--tls-client-ca " + pki_->server_key());
  const std::string no_token = (pki_->dir / "no-token").string();
  expect_start_refused(security_files("", "", "", no_token),
                       "--token-file " + no_token + ": cannot be read");
}

TEST_F(TlsServerTest, FlagsThatDoNotGoTogetherStopTheStart) {
  expect_start_refused(security_files(pki_->server_cert(), "", "", ""),
                       "--tls-cert and --tls-key go together");
  expect_start_refused(security_files("", pki_->server_key(), "", ""),
                       "--tls-cert and --tls-key go together");
  expect_start_refused(security_files("", "", pki_->ca_cert(), ""),
                       "--tls-client-ca needs --tls-cert");
}

// ----- what the server says when it starts ------------------------------------------------------

TEST(ListenNote, SaysWhoCanConnectAndWhatIsAsked) {
  ServerSecurity plaintext;
  EXPECT_THAT(listen_note("127.0.0.1:50051", plaintext),
              ::testing::ElementsAre(
                  "listening on 127.0.0.1:50051 (loopback only; use --listen 0.0.0.0:50051 to "
                  "serve other hosts); plaintext, no token"));
  EXPECT_THAT(listen_note("unix:/tmp/m.sock", plaintext),
              ::testing::ElementsAre("listening on unix:/tmp/m.sock (local socket only); "
                                     "plaintext, no token"));
  const std::vector<std::string> open = listen_note("0.0.0.0:50051", plaintext);
  ASSERT_EQ(open.size(), 2u);
  EXPECT_THAT(open[0], HasSubstr("(other hosts can connect)"));
  EXPECT_THAT(open[1], AllOf(HasSubstr("warning: plaintext"), HasSubstr("--tls-cert")));
  ServerSecurity tls;
  tls.tls = true;
  tls.bearer_token = "t";
  EXPECT_THAT(listen_note("0.0.0.0:443", tls),
              ::testing::ElementsAre("listening on 0.0.0.0:443 (other hosts can connect); TLS, "
                                     "bearer token required"));
}

}  // namespace
}  // namespace afmesh::server
