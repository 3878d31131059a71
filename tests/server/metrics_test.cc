// afmesh-server's Prometheus metrics (--metrics; server/metrics.h): a server in-process with a
// fake job (no mesher linked), scraped with GET /metrics over a plain TCP socket. The counters
// move by exactly what each call did (its code, the tets and triangles of its Summary, the
// bytes of its messages); the gauges follow running and queued jobs and the budget they hold;
// an address that is not IPV4:PORT, or a port in use, stops the server naming the flag, both
// in-process and through the afmesh-server binary, which also says where it serves them.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "afmesh/v1/mesher.grpc.pb.h"
#include "gmock/gmock.h"
#include "grpc/grpc.h"
#include "grpcpp/grpcpp.h"
#include "gtest/gtest.h"
#include "server/server.h"
#include "tests/server/request_support.h"
#include "tests/server/cli_test_support.h"

namespace afmesh::server {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using ::testing::HasSubstr;
using Request = v1::MeshVolumeRequest;
using Response = v1::MeshVolumeResponse;
using Labels = std::map<std::string, std::string>;

constexpr const char* kToken = "afmesh-metrics-test-token";
constexpr int kFakeTets = 5;  // what the fake job returns: not the input's 4 triangles

// ---------------------------------------------------------------------------------------------
// Scraping: HTTP/1.0 over a TCP socket, and the text format's sample lines.

// The body of GET `path` from 127.0.0.1:`port`; "" (with a test failure) when the request
// fails or the answer is not 200.
std::string http_get(int port, const std::string& path = "/metrics") {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) {
    ADD_FAILURE() << "socket() failed";
    return "";
  }
  const timeval timeout{.tv_sec = 5, .tv_usec = 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string answer;
  if (connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) == 0) {
    // HTTP/1.0 without Accept-Encoding: the server closes after one plain (not gzipped) answer.
    const std::string request = "GET " + path + " HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n";
    if (send(fd, request.data(), request.size(), MSG_NOSIGNAL) ==
        static_cast<ssize_t>(request.size())) {
      char buffer[4096];
      ssize_t got = 0;
      while ((got = recv(fd, buffer, sizeof(buffer), 0)) > 0) answer.append(buffer, got);
    }
  }
  close(fd);
  const std::string::size_type body = answer.find("\r\n\r\n");
  if (answer.rfind("HTTP/1.1 200", 0) != 0 && answer.rfind("HTTP/1.0 200", 0) != 0) {
    ADD_FAILURE() << "GET " << path << " from port " << port << ": "
                  << answer.substr(0, answer.find("\r\n"));
    return "";
  }
  return body == std::string::npos ? "" : answer.substr(body + 4);
}

// The port of "host:port".
int port_of(const std::string& address) {
  return std::stoi(address.substr(address.rfind(':') + 1));
}

// `name{k="v",...}` with the labels in name order, as the samples are keyed below.
std::string series_key(const std::string& name, const Labels& labels) {
  std::string key = name;
  if (labels.empty()) return key;
  key += '{';
  for (const auto& [label, value] : labels) {
    if (key.back() != '{') key += ',';
    key += label + "=\"" + value + "\"";
  }
  return key + '}';
}

// One scrape's samples ("name{labels} value" lines; # lines skipped), by series_key. Label
// values here hold no quotes or commas, so the parse needs no escapes.
class Scrape {
 public:
  explicit Scrape(const std::string& text) {
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
      if (line.empty() || line[0] == '#') continue;
      const std::string::size_type space = line.rfind(' ');
      const std::string series = line.substr(0, space);
      const std::string::size_type brace = series.find('{');
      Labels labels;
      if (brace != std::string::npos) {
        std::istringstream pairs(series.substr(brace + 1, series.size() - brace - 2));
        std::string pair;
        while (std::getline(pairs, pair, ',')) {
          const std::string::size_type equals = pair.find('=');
          labels[pair.substr(0, equals)] = pair.substr(equals + 2, pair.size() - equals - 3);
        }
      }
      samples_[series_key(series.substr(0, brace), labels)] = std::stod(line.substr(space + 1));
    }
  }

  // The sample's value; NaN, with a test failure, when the scrape does not have it.
  double at(const std::string& name, const Labels& labels = {}) const {
    const auto found = samples_.find(series_key(name, labels));
    if (found == samples_.end()) {
      ADD_FAILURE() << "no sample " << series_key(name, labels);
      return std::nan("");
    }
    return found->second;
  }

  // Sum over every series of `name`.
  double total(const std::string& name) const {
    double sum = 0;
    for (const auto& [key, value] : samples_) {
      if (key == name || key.rfind(name + "{", 0) == 0) sum += value;
    }
    return sum;
  }

 private:
  std::map<std::string, double> samples_;
};

// ---------------------------------------------------------------------------------------------
// Requests and fake jobs.

using afmesh::testing::tetrahedron_requests;

std::int64_t bytes_of(const std::vector<Request>& requests) {
  std::int64_t bytes = 0;
  for (const Request& request : requests) {
    bytes += static_cast<std::int64_t>(request.ByteSizeLong());
  }
  return bytes;
}

// The front, with kFakeTets copies of the one tet it bounds.
absl::StatusOr<VolumeJobOutput> fake_tets_job(const Mesh& front, const VolumeParams&, Progress&) {
  VolumeJobOutput output;
  output.volume.mesh = front;
  output.volume.mesh.tets.assign(kFakeTets, {0, 1, 2, 3});
  output.volume.mesh.tet_tags.assign(kFakeTets, 0);
  output.validation.passed = true;
  return output;
}

// Signals `started` on its first run, then polls cancellation every millisecond (for 10 s at
// most, so that a broken cancellation fails the test instead of hanging it).
VolumeJob slow_job(std::shared_ptr<std::promise<void>> started) {
  auto first = std::make_shared<std::atomic<bool>>(true);
  return [started, first](const Mesh&, const VolumeParams&,
                          Progress& progress) -> absl::StatusOr<VolumeJobOutput> {
    if (first->exchange(false)) started->set_value();
    const Clock::time_point give_up = Clock::now() + std::chrono::seconds(10);
    while (Clock::now() < give_up) {
      if (progress.cancelled()) return absl::CancelledError("stopped");
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return absl::InternalError("the job was never cancelled");
  };
}

struct CallOutcome {
  grpc::Status status;
  std::vector<Response> responses;
  std::int64_t response_bytes = 0;
};

// ---------------------------------------------------------------------------------------------
// Fixture: a server with metrics on a port the system picks.

class MetricsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    static const bool initialised = (grpc_init(), true);
    (void)initialised;
  }

  void SetUp() override {
    char pattern[] = "/tmp/afmesh-metrics-test-XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    dir_ = pattern;
  }

  void TearDown() override {
    if (server_ != nullptr) server_->shutdown();
    fs::remove_all(dir_);
  }

  // Starts a server on a unix socket with `options` (metrics on 127.0.0.1:0 unless set).
  void start(VolumeJob job, ServerOptions options = {}) {
    options.listen = "unix:" + (dir_ / "mesher.sock").string();
    if (options.workers == 0) options.workers = 1;
    if (options.metrics.empty()) options.metrics = "127.0.0.1:0";
    options.service.log_calls = false;
    absl::StatusOr<std::unique_ptr<MesherServer>> server =
        MesherServer::start(options, std::move(job));
    ASSERT_TRUE(server.ok()) << server.status();
    server_ = *std::move(server);
    ASSERT_NE(server_->metrics_address(), "127.0.0.1:0");
    stub_ = v1::Mesher::NewStub(
        grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials()));
  }

  Scrape scrape() const { return Scrape(http_get(port_of(server_->metrics_address()))); }

  // Scrapes until `ready` holds (5 s at most); the last scrape.
  Scrape scrape_until(const std::function<bool(const Scrape&)>& ready) const {
    const Clock::time_point give_up = Clock::now() + std::chrono::seconds(5);
    Scrape last = scrape();
    while (!ready(last) && Clock::now() < give_up) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      last = scrape();
    }
    return last;
  }

  // Sends `requests` (with the bearer token when `token` is set), half-closes, reads it all.
  CallOutcome call(const std::vector<Request>& requests, const std::string& token = "") {
    grpc::ClientContext context;
    if (!token.empty()) context.AddMetadata("authorization", "Bearer " + token);
    auto stream = stub_->MeshVolume(&context);
    for (const Request& request : requests) {
      if (!stream->Write(request)) break;
    }
    stream->WritesDone();
    CallOutcome outcome;
    Response response;
    while (stream->Read(&response)) {
      outcome.response_bytes += static_cast<std::int64_t>(response.ByteSizeLong());
      outcome.responses.push_back(response);
    }
    outcome.status = stream->Finish();
    return outcome;
  }

  fs::path dir_;
  std::unique_ptr<MesherServer> server_;
  std::unique_ptr<v1::Mesher::Stub> stub_;
};

const Labels kMeshVolume = {{"rpc", "MeshVolume"}};

Labels mesh_volume_code(const std::string& code) { return {{"rpc", "MeshVolume"}, {"code", code}}; }

Labels mesh_volume_kind(const std::string& kind) { return {{"rpc", "MeshVolume"}, {"kind", kind}}; }

// ---------------------------------------------------------------------------------------------
// Counters.

TEST_F(MetricsTest, ScrapeCountsEachCallByCodeWithItsElementsAndBytes) {
  std::ofstream(dir_ / "token") << kToken << "\n";
  ServerOptions options;
  options.security.token_file = (dir_ / "token").string();
  options.service.limits.max_points = 100;
  start(fake_tets_job, options);

  // Every code the service documents has its series at 0 before any call.
  const Scrape before = scrape();
  for (const char* code :
       {"OK", "INVALID_ARGUMENT", "RESOURCE_EXHAUSTED", "FAILED_PRECONDITION", "CANCELLED",
        "DEADLINE_EXCEEDED", "UNAVAILABLE", "UNAUTHENTICATED", "INTERNAL"}) {
    EXPECT_EQ(before.at("afmesh_calls_total", mesh_volume_code(code)), 0) << code;
  }
  EXPECT_EQ(before.at("afmesh_job_seconds_count", kMeshVolume), 0);

  // A call that succeeds: one OK, its Summary's tets and triangles, every byte both ways.
  const std::vector<Request> requests = tetrahedron_requests();
  const CallOutcome ok = call(requests, kToken);
  ASSERT_TRUE(ok.status.ok()) << ok.status.error_message();
  ASSERT_TRUE(ok.responses.back().has_summary());
  const v1::Summary& summary = ok.responses.back().summary();
  ASSERT_EQ(summary.tet_count(), static_cast<std::uint64_t>(kFakeTets));
  const Scrape after_ok = scrape();
  EXPECT_EQ(after_ok.at("afmesh_calls_total", mesh_volume_code("OK")), 1);
  EXPECT_EQ(after_ok.total("afmesh_calls_total"), 1);
  EXPECT_EQ(after_ok.at("afmesh_elements_produced_total", mesh_volume_kind("tets")),
            summary.tet_count());
  EXPECT_EQ(after_ok.at("afmesh_elements_produced_total", mesh_volume_kind("triangles")),
            summary.triangle_count());
  EXPECT_GT(bytes_of(requests), 0);
  EXPECT_EQ(after_ok.at("afmesh_received_bytes_total", kMeshVolume), bytes_of(requests));
  EXPECT_EQ(after_ok.at("afmesh_sent_bytes_total", kMeshVolume), ok.response_bytes);
  EXPECT_EQ(after_ok.at("afmesh_job_seconds_count", kMeshVolume), 1);
  EXPECT_EQ(after_ok.at("afmesh_job_seconds_bucket", {{"rpc", "MeshVolume"}, {"le", "+Inf"}}), 1);

  // Refused before anything is read (no token): one UNAUTHENTICATED, no byte, no job.
  const CallOutcome refused = call(requests);
  ASSERT_EQ(refused.status.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  const Scrape after_refused = scrape();
  EXPECT_EQ(after_refused.at("afmesh_calls_total", mesh_volume_code("UNAUTHENTICATED")), 1);
  EXPECT_EQ(after_refused.total("afmesh_calls_total"), 2);
  EXPECT_EQ(after_refused.at("afmesh_received_bytes_total", kMeshVolume), bytes_of(requests));
  EXPECT_EQ(after_refused.at("afmesh_sent_bytes_total", kMeshVolume), ok.response_bytes);
  EXPECT_EQ(after_refused.at("afmesh_job_seconds_count", kMeshVolume), 1);

  // Over --max-points by its header: one RESOURCE_EXHAUSTED, the header's bytes, no elements.
  std::vector<Request> too_large = tetrahedron_requests();
  too_large[0].mutable_header()->set_point_count(1000);
  const CallOutcome over = call(too_large, kToken);
  ASSERT_EQ(over.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  ASSERT_THAT(over.status.error_message(), HasSubstr("--max-points"));
  const Scrape after_over = scrape();
  EXPECT_EQ(after_over.at("afmesh_calls_total", mesh_volume_code("RESOURCE_EXHAUSTED")), 1);
  EXPECT_EQ(after_over.total("afmesh_calls_total"), 3);
  EXPECT_EQ(after_over.at("afmesh_received_bytes_total", kMeshVolume),
            bytes_of(requests) + static_cast<std::int64_t>(too_large[0].ByteSizeLong()));
  EXPECT_EQ(after_over.at("afmesh_elements_produced_total", mesh_volume_kind("tets")),
            summary.tet_count());
  EXPECT_EQ(after_over.at("afmesh_job_seconds_count", kMeshVolume), 1);
}

// ---------------------------------------------------------------------------------------------
// Gauges.

TEST_F(MetricsTest, GaugesFollowRunningAndQueuedJobsAndTheBudgetTheyHold) {
  ServerOptions options;
  options.workers = 1;
  options.max_queue = 1;
  auto started = std::make_shared<std::promise<void>>();
  std::future<void> first_started = started->get_future();
  start(slow_job(started), options);
  const Scrape idle = scrape();
  EXPECT_EQ(idle.at("afmesh_workers"), 1);
  EXPECT_EQ(idle.at("afmesh_call_slots"), 2);
  EXPECT_EQ(idle.at("afmesh_calls_in_flight"), 0);
  EXPECT_EQ(idle.at("afmesh_memory_budget_reserved_bytes"), 0);
  EXPECT_GT(idle.at("afmesh_memory_budget_bytes"), 0);
  EXPECT_EQ(idle.at("afmesh_draining"), 0);
  EXPECT_GT(idle.at("process_resident_memory_bytes"), 0);

  // size 0.05: the estimate reserves a few MB of the budget while the job runs.
  const std::vector<Request> requests = tetrahedron_requests(0.05);
  grpc::ClientContext running_context;
  grpc::ClientContext queued_context;
  auto running = stub_->MeshVolume(&running_context);
  for (const Request& request : requests) ASSERT_TRUE(running->Write(request));
  running->WritesDone();
  ASSERT_EQ(first_started.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  const Scrape one = scrape();
  EXPECT_EQ(one.at("afmesh_jobs_running"), 1);
  EXPECT_EQ(one.at("afmesh_jobs_queued"), 0);
  EXPECT_EQ(one.at("afmesh_calls_in_flight"), 1);
  EXPECT_EQ(one.at("afmesh_call_slots_in_use"), 1);
  EXPECT_GT(one.at("afmesh_memory_budget_reserved_bytes"), 0);

  auto queued = stub_->MeshVolume(&queued_context);
  for (const Request& request : requests) ASSERT_TRUE(queued->Write(request));
  queued->WritesDone();
  const Scrape two = scrape_until([](const Scrape& s) { return s.at("afmesh_jobs_queued") == 1; });
  EXPECT_EQ(two.at("afmesh_jobs_queued"), 1);
  EXPECT_EQ(two.at("afmesh_jobs_running"), 1);
  EXPECT_EQ(two.at("afmesh_calls_in_flight"), 2);
  EXPECT_EQ(two.at("afmesh_call_slots_in_use"), 2);

  queued_context.TryCancel();
  running_context.TryCancel();
  EXPECT_EQ(queued->Finish().error_code(), grpc::StatusCode::CANCELLED);
  EXPECT_EQ(running->Finish().error_code(), grpc::StatusCode::CANCELLED);
  // The calls let go of their slots and reservations once gRPC is done with them.
  const Scrape after = scrape_until([](const Scrape& s) {
    return s.at("afmesh_calls_in_flight") == 0 && s.at("afmesh_call_slots_in_use") == 0 &&
           s.at("afmesh_memory_budget_reserved_bytes") == 0;
  });
  EXPECT_EQ(after.at("afmesh_calls_in_flight"), 0);
  EXPECT_EQ(after.at("afmesh_jobs_running"), 0);
  EXPECT_EQ(after.at("afmesh_jobs_queued"), 0);
  EXPECT_EQ(after.at("afmesh_call_slots_in_use"), 0);
  EXPECT_EQ(after.at("afmesh_memory_budget_reserved_bytes"), 0);
  EXPECT_EQ(after.at("afmesh_calls_total", mesh_volume_code("CANCELLED")), 2);
}

// ---------------------------------------------------------------------------------------------
// The flag's errors, in-process.

TEST_F(MetricsTest, AnAddressThatIsNotIpv4AndPortIsRefusedNamingTheFlag) {
  for (const std::string address :
       {"9464", "bogus", "127.0.0.1:", "127.0.0.1:99999", "127.0.0.1:94x4", ":9464", "[::1]:9464",
        "::1", "metrics.example:9464", "127.0.0.256:9464"}) {
    ServerOptions options;
    options.listen = "unix:" + (dir_ / "mesher.sock").string();
    options.workers = 1;
    options.metrics = address;
    const absl::StatusOr<std::unique_ptr<MesherServer>> server =
        MesherServer::start(options, fake_tets_job);
    ASSERT_FALSE(server.ok()) << address;
    EXPECT_EQ(server.status().code(), absl::StatusCode::kInvalidArgument) << server.status();
    EXPECT_THAT(server.status().message(), HasSubstr("--metrics " + address + ": "));
    EXPECT_THAT(server.status().message(), HasSubstr("IPV4:PORT"));
  }
}

TEST_F(MetricsTest, APortInUseIsRefusedNamingTheFlag) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof(address);
  ASSERT_EQ(bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)), 0);
  ASSERT_EQ(listen(fd, 1), 0);
  ASSERT_EQ(getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length), 0);
  const std::string taken = "127.0.0.1:" + std::to_string(ntohs(address.sin_port));

  ServerOptions options;
  options.listen = "unix:" + (dir_ / "mesher.sock").string();
  options.workers = 1;
  options.metrics = taken;
  const absl::StatusOr<std::unique_ptr<MesherServer>> server =
      MesherServer::start(options, fake_tets_job);
  close(fd);
  ASSERT_FALSE(server.ok());
  EXPECT_EQ(server.status().code(), absl::StatusCode::kUnavailable) << server.status();
  EXPECT_THAT(server.status().message(), HasSubstr("--metrics " + taken + ": cannot listen"));
  EXPECT_THAT(server.status().message(), HasSubstr("in use"));
}

// ---------------------------------------------------------------------------------------------
// Through the afmesh-server binary.

// Waits up to 10 s for `log` to hold `text`; the log then.
std::string wait_for_log(const fs::path& log, const std::string& text) {
  const Clock::time_point give_up = Clock::now() + std::chrono::seconds(10);
  std::string content = cli_test::read_file(log);
  while (content.find(text) == std::string::npos && Clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    content = cli_test::read_file(log);
  }
  return content;
}

TEST_F(MetricsTest, ServerBinarySaysWhereItServesMetricsOnAPortItPickedAndServesThem) {
  const fs::path socket = dir_ / "binary.sock";
  const fs::path log = dir_ / "server.log";
  const pid_t pid = cli_test::start_server_process(
      AFMESH_SERVER_BINARY,
      {"--listen", "unix:" + socket.string(), "--workers", "1", "--metrics", "127.0.0.1:0"}, log);
  ASSERT_GT(pid, 0);
  const std::string prefix = "metrics on http://127.0.0.1:";
  const std::string said = wait_for_log(log, "/metrics (loopback only");
  const std::string::size_type at = said.find(prefix);
  ASSERT_NE(at, std::string::npos) << said;
  const int port = std::stoi(said.substr(at + prefix.size()));
  EXPECT_GT(port, 0);
  const std::string text = http_get(port);
  EXPECT_THAT(text, HasSubstr("# TYPE afmesh_calls_total counter"));
  EXPECT_THAT(text, HasSubstr("afmesh_calls_total{code=\"OK\",rpc=\"MeshVolume\"} 0"));
  EXPECT_THAT(text, HasSubstr("# TYPE afmesh_job_seconds histogram"));
  EXPECT_EQ(cli_test::stop_server_process(pid), 0);
}

TEST_F(MetricsTest, ServerBinaryExitsOneNamingTheFlagOnABadMetricsAddress) {
  const fs::path log = dir_ / "server.log";
  const pid_t pid = cli_test::start_server_process(
      AFMESH_SERVER_BINARY,
      {"--listen", "unix:" + (dir_ / "binary.sock").string(), "--metrics", "127.0.0.1:99999"}, log);
  ASSERT_GT(pid, 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_EQ(cli_test::exit_status(status), 1);  // an exit, not a crash (-1)
  EXPECT_THAT(cli_test::read_file(log),
              HasSubstr("afmesh-server: --metrics 127.0.0.1:99999: port '99999' is not a number"));
}

}  // namespace
}  // namespace afmesh::server
