// The Mesher service in-process, on a unix socket (or a TCP port picked by the system), with
// fake meshing jobs: streaming whole meshes in capped slices, admission control, cancellation
// and deadlines reaching the job, input validation, health, and draining on shutdown.
#include <stdlib.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <future>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "absl/status/status.h"
#include "afmesh/v1/mesher.grpc.pb.h"
#include "gmock/gmock.h"
#include "grpc/grpc.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "grpcpp/generic/generic_stub.h"
#include "grpcpp/grpcpp.h"
#include "gtest/gtest.h"
#include "core/environments/detect_environments.h"
#include "core/environments/environments.h"
#include "core/io/mesh_io.h"
#include "core/shapes/shapes.h"
#include "proto/size_spec_convert.h"
#include "proto/slice_codec.h"
#include "server/server.h"
#include "server/volume_output.h"
#include "tests/server/request_support.h"

namespace afmesh::server {
namespace {

using Clock = std::chrono::steady_clock;
using ::testing::HasSubstr;
using Request = v1::MeshVolumeRequest;
using Response = v1::MeshVolumeResponse;

constexpr std::size_t kMessageCap = 1 << 20;  // bytes of payload per message

// ---------------------------------------------------------------------------------------------
// Meshes and requests.

using afmesh::testing::tetrahedron_front;
using afmesh::testing::carries_mesh;
using afmesh::testing::mesh_from;
using afmesh::testing::same_bits;

// A mesh large enough to need several slices of each kind, with coordinates that only survive
// a bit-exact transfer (thirds, -0.0, subnormals, extremes) and negative tags (the longest
// varints).
Mesh large_mesh() {
  constexpr int kPoints = 100'003;
  constexpr int kTriangles = 40'000;
  constexpr int kTets = 70'001;
  Mesh mesh;
  mesh.points.reserve(kPoints);
  for (int i = 0; i < kPoints; ++i) {
    const double third = i / 3.0;
    const double z = i % 7 == 0 ? 4.9e-320 : (i % 11 == 0 ? -1.7e308 : std::sin(i));
    mesh.points.push_back({third, i % 2 == 0 ? -0.0 : 1.0 / (i + 1), z});
  }
  for (int i = 0; i < kTriangles; ++i) {
    mesh.triangles.push_back({i, (i + 1) % kPoints, (i + 2) % kPoints});
    mesh.triangle_tags.push_back(i % 3 == 0 ? -1 : i);
  }
  for (int i = 0; i < kTets; ++i) {
    mesh.tets.push_back({i % kPoints, (i + 5) % kPoints, (i + 9) % kPoints, (i + 13) % kPoints});
    mesh.tet_tags.push_back(i % 4 == 0 ? std::numeric_limits<Index>::min() : i % 5);
  }
  return mesh;
}

Request header_request(double size, std::optional<std::uint64_t> points,
                       std::optional<std::uint64_t> triangles) {
  Request request;
  v1::MeshVolumeHeader& header = *request.mutable_header();
  header.mutable_options()->mutable_size()->set_max_size(size);
  header.mutable_options()->mutable_size()->set_growth(1.2);
  if (points) header.set_point_count(*points);
  if (triangles) header.set_triangle_count(*triangles);
  return request;
}

Request points_request(const std::vector<Point>& points, std::size_t begin, std::size_t end) {
  Request request;
  wire::encode_points(points, begin, end, *request.mutable_points());
  return request;
}

Request triangles_request(const Mesh& front, std::size_t begin, std::size_t end) {
  Request request;
  wire::encode_triangles(front.triangles, front.triangle_tags, begin, end,
                         *request.mutable_triangles());
  return request;
}

// Header, then points and triangles in slices of `slice` items, interleaved.
std::vector<Request> requests_for(const Mesh& front, std::size_t slice = 32768) {
  std::vector<Request> requests = {
      header_request(0.25, front.points.size(), front.triangles.size())};
  const std::size_t longest = std::max(front.points.size(), front.triangles.size());
  for (std::size_t begin = 0; begin < longest; begin += slice) {
    if (begin < front.points.size()) {
      requests.push_back(
          points_request(front.points, begin, std::min(front.points.size(), begin + slice)));
    }
    if (begin < front.triangles.size()) {
      requests.push_back(
          triangles_request(front, begin, std::min(front.triangles.size(), begin + slice)));
    }
  }
  return requests;
}

int count_events(const std::vector<Response>& responses, Response::EventCase kind) {
  int count = 0;
  for (const Response& response : responses) count += response.event_case() == kind ? 1 : 0;
  return count;
}

// ---------------------------------------------------------------------------------------------
// Fake jobs.

VolumeJobOutput output_with(Mesh mesh) {
  VolumeJobOutput output;
  output.volume.mesh = std::move(mesh);
  output.volume.timings = {{"front", 0.5}, {"compact", 0.25}};
  output.quality = {.min_dihedral_deg = 12.5,
                    .max_dihedral_deg = 150.25,
                    .share_below_10_deg = 0.0,
                    .share_below_20_deg = 0.015,
                    .min_radius_ratio = 0.3,
                    .mean_radius_ratio = 0.8,
                    .boundary_min_angle_deg = 4.5,
                    .boundary_slivers = 3,
                    .tets_away_from_slivers = 40,
                    .away_min_dihedral_deg = 19.5,
                    .away_share_below_20_deg = 0.025};
  output.validation = {.passed = true, .messages = {"unused_points: none"}};
  output.warnings = {"fake warning"};
  return output;
}

// Returns `mesh` after reporting some progress.
VolumeJob fixed_job(Mesh mesh) {
  return [mesh = std::move(mesh)](const Mesh&, const VolumeParams&,
                                  Progress& progress) -> absl::StatusOr<VolumeJobOutput> {
    progress.report("front", 0.5);
    progress.report("front", 1.0);
    return output_with(mesh);
  };
}

// Records what a job saw.
struct JobProbe {
  std::atomic<int> runs{0};
  std::promise<void> started;               // set by the first run
  std::promise<Clock::time_point> stopped;  // when the first run saw cancellation
  Mesh front;                               // the first run's input
  VolumeParams params;
};

// Polls cancellation every millisecond, like the core between elements; gives up (INTERNAL)
// after 10 s so that a broken cancellation path fails the test instead of hanging it.
VolumeJob slow_job(std::shared_ptr<JobProbe> probe) {
  return [probe](const Mesh& front, const VolumeParams& params,
                 Progress& progress) -> absl::StatusOr<VolumeJobOutput> {
    const bool first = probe->runs.fetch_add(1) == 0;
    if (first) {
      probe->front = front;
      probe->params = params;
      probe->started.set_value();
    }
    const Clock::time_point give_up = Clock::now() + std::chrono::seconds(10);
    while (Clock::now() < give_up) {
      if (progress.cancelled()) {
        if (first) probe->stopped.set_value(Clock::now());
        return absl::CancelledError("stopped");
      }
      progress.report("front", -1.0);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return absl::InternalError("the job was never cancelled");
  };
}

// Counts runs and returns the tetrahedron meshed as one tet.
VolumeJob counting_job(std::shared_ptr<JobProbe> probe) {
  return [probe](const Mesh& front, const VolumeParams& params,
                 Progress&) -> absl::StatusOr<VolumeJobOutput> {
    if (probe->runs.fetch_add(1) == 0) {
      probe->front = front;
      probe->params = params;
    }
    Mesh mesh = front;
    mesh.tets = {{0, 1, 2, 3}};
    mesh.tet_tags = {0};
    return output_with(std::move(mesh));
  };
}

// ---------------------------------------------------------------------------------------------
// Fixture: an in-process server and a stub.

// The server's retry hint (trailing metadata retry-after-ms), empty when it sent none.
std::string retry_after(const grpc::ClientContext& context) {
  const auto& trailers = context.GetServerTrailingMetadata();
  const auto found = trailers.find("retry-after-ms");
  return found == trailers.end() ? "" : std::string(found->second.data(), found->second.size());
}

struct CallOutcome {
  grpc::Status status;
  std::vector<Response> responses;
};

class MesherServiceTest : public ::testing::Test {
 protected:
  // gRPC shuts its library down when its last object goes away, and in 1.51 that can wait for
  // an executor thread polling with a 10 s timeout; keep it initialised for the whole run.
  static void SetUpTestSuite() {
    static const bool initialised = (grpc_init(), true);
    (void)initialised;
  }

  void SetUp() override {
    char pattern[] = "/tmp/afmesh-server-test-XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    dir_ = pattern;
  }

  void TearDown() override {
    if (server_ != nullptr) server_->shutdown();
    std::filesystem::remove_all(dir_);
  }

  // Starts a server running `job` on a unix socket (unless `options.listen` is a TCP address).
  void start(VolumeJob job, ServerOptions options = {}) {
    if (options.listen == ServerOptions{}.listen) options.listen = "unix:" + dir_ + "/mesher.sock";
    if (options.workers == 0) options.workers = 2;
    options.service.log_calls = false;
    absl::StatusOr<std::unique_ptr<MesherServer>> server =
        MesherServer::start(options, std::move(job));
    ASSERT_TRUE(server.ok()) << server.status();
    server_ = *std::move(server);
    channel_ = grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials());
    stub_ = v1::Mesher::NewStub(channel_);
  }

  // Sends `requests`, half-closes, reads every response.
  CallOutcome call(const std::vector<Request>& requests, grpc::ClientContext& context) {
    std::unique_ptr<grpc::ClientReaderWriter<Request, Response>> stream =
        stub_->MeshVolume(&context);
    for (const Request& request : requests) {
      if (!stream->Write(request)) break;
    }
    stream->WritesDone();
    CallOutcome outcome;
    Response response;
    while (stream->Read(&response)) outcome.responses.push_back(response);
    outcome.status = stream->Finish();
    return outcome;
  }

  CallOutcome call(const std::vector<Request>& requests) {
    grpc::ClientContext context;
    return call(requests, context);
  }

  // Opens a call, sends `requests`, half-closes and waits (5 s at most) until the job of a
  // slow_job server has started. Null, with a test failure, when any of that fails.
  std::unique_ptr<grpc::ClientReaderWriter<Request, Response>> start_running_call(
      grpc::ClientContext& context, const std::vector<Request>& requests) {
    std::unique_ptr<grpc::ClientReaderWriter<Request, Response>> stream =
        stub_->MeshVolume(&context);
    for (const Request& request : requests) {
      if (!stream->Write(request)) {
        ADD_FAILURE() << "the server ended the call while it was being sent";
        return nullptr;
      }
    }
    stream->WritesDone();
    if (probe_->started.get_future().wait_for(std::chrono::seconds(5)) !=
        std::future_status::ready) {
      ADD_FAILURE() << "the job did not start within 5 s";
      return nullptr;
    }
    return stream;
  }

  // Expects the call to fail with `code` and a message holding every one of `parts`, with no
  // mesh sent and no job run.
  void expect_rejected(const std::vector<Request>& requests, grpc::StatusCode code,
                       const std::vector<std::string>& parts) {
    const CallOutcome outcome = call(requests);
    EXPECT_EQ(outcome.status.error_code(), code) << outcome.status.error_message();
    for (const std::string& part : parts) {
      EXPECT_THAT(outcome.status.error_message(), HasSubstr(part));
    }
    for (const Response& response : outcome.responses) EXPECT_FALSE(carries_mesh(response));
    EXPECT_EQ(probe_->runs.load(), 0);
  }

  std::string dir_;
  std::unique_ptr<MesherServer> server_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::Mesher::Stub> stub_;
  std::shared_ptr<JobProbe> probe_ = std::make_shared<JobProbe>();
};

// ---------------------------------------------------------------------------------------------
// Streaming.

TEST_F(MesherServiceTest, JobMeshStreamsBackWholeAndBitExactInCappedSlices) {
  const Mesh mesh = large_mesh();
  start(fixed_job(mesh));
  const CallOutcome outcome = call(requests_for(tetrahedron_front()));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();

  for (const Response& response : outcome.responses) {
    EXPECT_LE(response.ByteSizeLong(), kMessageCap) << response.event_case();
  }
  EXPECT_GT(count_events(outcome.responses, Response::kPoints), 1);
  EXPECT_GT(count_events(outcome.responses, Response::kTriangles), 1);
  EXPECT_GT(count_events(outcome.responses, Response::kTets), 1);

  const Mesh received = mesh_from(outcome.responses);
  EXPECT_TRUE(same_bits(received.points, mesh.points));
  EXPECT_EQ(received.triangles, mesh.triangles);
  EXPECT_EQ(received.triangle_tags, mesh.triangle_tags);
  EXPECT_EQ(received.tets, mesh.tets);
  EXPECT_EQ(received.tet_tags, mesh.tet_tags);
}

TEST_F(MesherServiceTest, SummaryComesLastWithCountsQualityAndTimings) {
  const Mesh mesh = large_mesh();
  start(fixed_job(mesh));
  const CallOutcome outcome = call(requests_for(tetrahedron_front()));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  ASSERT_FALSE(outcome.responses.empty());
  ASSERT_TRUE(outcome.responses.back().has_summary());
  EXPECT_EQ(count_events(outcome.responses, Response::kSummary), 1);

  const v1::Summary& summary = outcome.responses.back().summary();
  EXPECT_EQ(summary.point_count(), mesh.points.size());
  EXPECT_EQ(summary.triangle_count(), mesh.triangles.size());
  EXPECT_EQ(summary.tet_count(), mesh.tets.size());
  EXPECT_EQ(summary.quality().min_dihedral_deg(), 12.5);
  EXPECT_EQ(summary.quality().share_below_20_deg(), 0.015);
  EXPECT_EQ(summary.quality().mean_radius_ratio(), 0.8);
  EXPECT_EQ(summary.quality().boundary_min_angle_deg(), 4.5);
  EXPECT_EQ(summary.quality().boundary_sliver_count(), 3u);
  EXPECT_EQ(summary.quality().tets_away_from_slivers(), 40u);
  EXPECT_EQ(summary.quality().min_dihedral_away_from_slivers_deg(), 19.5);
  EXPECT_EQ(summary.quality().share_away_from_slivers_below_20_deg(), 0.025);
  EXPECT_TRUE(summary.validation().passed());
  ASSERT_EQ(summary.validation().messages_size(), 1);

  std::vector<std::string> stages;
  for (const v1::StageTiming& timing : summary.timings()) {
    stages.push_back(timing.stage());
    EXPECT_GE(timing.seconds(), 0.0);
  }
  EXPECT_THAT(stages,
              ::testing::ElementsAre("receive", "queue", "repair", "front", "compact", "send"));
  EXPECT_EQ(summary.repair().triangles_reoriented(), 0u);
  EXPECT_EQ(summary.repair().components(), 1u);
}

TEST_F(MesherServiceTest, EventsPrecedeMeshSlicesInPointTriangleTetOrder) {
  start(fixed_job(large_mesh()));
  const CallOutcome outcome = call(requests_for(tetrahedron_front()));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  ASSERT_TRUE(outcome.responses.front().has_progress());
  EXPECT_EQ(outcome.responses.front().progress().stage(), "queued");
  // The job's warning, and the server's: the tetrahedron's edges are 4.6 to 5.7 times 0.25.
  EXPECT_EQ(count_events(outcome.responses, Response::kWarning), 2);

  int last_kind = 0;
  bool mesh_started = false;
  for (const Response& response : outcome.responses) {
    if (carries_mesh(response)) mesh_started = true;
    if (mesh_started) {
      EXPECT_FALSE(response.has_progress() || response.has_warning());
      EXPECT_GE(response.event_case(), last_kind);  // points < triangles < tets < summary
      last_kind = response.event_case();
    }
  }
  EXPECT_TRUE(mesh_started);
}

TEST_F(MesherServiceTest, JobReceivesTheFrontAndOptionsAsSent) {
  start(counting_job(probe_));
  const Mesh front = tetrahedron_front();
  const CallOutcome outcome = call(requests_for(front, /*slice=*/1));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  EXPECT_EQ(probe_->runs.load(), 1);
  EXPECT_TRUE(same_bits(probe_->front.points, front.points));
  EXPECT_EQ(probe_->front.triangles, front.triangles);
  EXPECT_EQ(probe_->front.triangle_tags, front.triangle_tags);
  EXPECT_EQ(probe_->params.size, 0.25);
  EXPECT_EQ(probe_->params.growth, 1.2);
  EXPECT_EQ(probe_->params.local_refinements, VolumeParams{}.local_refinements);
}

TEST_F(MesherServiceTest, TrianglesWithoutTagsGetTagZeroAndGrowthZeroMeansOne) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests[0].mutable_header()->mutable_options()->mutable_size()->clear_growth();
  for (Request& request : requests) {
    if (request.has_triangles()) request.mutable_triangles()->clear_tags();
  }
  const CallOutcome outcome = call(requests);
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  EXPECT_EQ(probe_->front.triangle_tags, std::vector<Index>(4, 0));
  EXPECT_EQ(probe_->params.growth, 1.0);
}

// VolumeOptions.max_reruns reaches the job as VolumeParams::local_refinements; unset leaves the
// core's default; out of [0, 32] is INVALID_ARGUMENT naming the field.
TEST_F(MesherServiceTest, MaxRerunsReachesTheJobAndIsChecked) {
  start(counting_job(probe_));  // keeps the first run's params
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests[0].mutable_header()->mutable_options()->set_max_reruns(3);
  CallOutcome outcome = call(requests);
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  EXPECT_EQ(probe_->params.local_refinements, 3);
  for (const int bad : {-1, 33}) {
    requests[0].mutable_header()->mutable_options()->set_max_reruns(bad);
    outcome = call(requests);
    EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << bad;
    EXPECT_THAT(outcome.status.error_message(), HasSubstr("options.max_reruns must be in [0, 32]"));
  }
}

TEST_F(MesherServiceTest, ServesOverTcpOnAPortPickedBySystem) {
  ServerOptions options;
  options.listen = "127.0.0.1:0";
  start(counting_job(probe_), options);
  EXPECT_NE(server_->address(), "127.0.0.1:0");
  const CallOutcome outcome = call(requests_for(tetrahedron_front()));
  EXPECT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  EXPECT_EQ(mesh_from(outcome.responses).tets.size(), 1u);
}

// ---------------------------------------------------------------------------------------------
// Job failures.

TEST_F(MesherServiceTest, JobFailureStatusReachesClientWithoutMeshSlices) {
  start([](const Mesh&, const VolumeParams&, Progress&) -> absl::StatusOr<VolumeJobOutput> {
    return absl::FailedPreconditionError("front stuck at face 12 near (0.5, 0.5, 0.5)");
  });
  const CallOutcome outcome = call(requests_for(tetrahedron_front()));
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_THAT(outcome.status.error_message(), HasSubstr("face 12"));
  for (const Response& response : outcome.responses) {
    EXPECT_FALSE(carries_mesh(response) || response.has_summary());
  }
}

TEST_F(MesherServiceTest, JobExceptionBecomesInternalAndServerKeepsServing) {
  start([](const Mesh&, const VolumeParams&, Progress&) -> absl::StatusOr<VolumeJobOutput> {
    throw std::runtime_error("boom");
  });
  for (int attempt = 0; attempt < 2; ++attempt) {
    const CallOutcome outcome = call(requests_for(tetrahedron_front()));
    EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::INTERNAL);
    EXPECT_THAT(outcome.status.error_message(), HasSubstr("boom"));
  }
}

TEST_F(MesherServiceTest, JobMeshWithIndexOutOfRangeIsNotSent) {
  Mesh broken = tetrahedron_front();
  broken.tets = {{0, 1, 2, 3}, {0, 1, 2, 4}};
  broken.tet_tags = {0, 0};
  start(fixed_job(broken));
  const CallOutcome outcome = call(requests_for(tetrahedron_front()));
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::INTERNAL);
  EXPECT_THAT(outcome.status.error_message(), HasSubstr("tet 1"));
  for (const Response& response : outcome.responses) EXPECT_FALSE(carries_mesh(response));
}

// ---------------------------------------------------------------------------------------------
// Admission, cancellation, deadlines, shutdown.

TEST_F(MesherServiceTest, CallFindingWorkersAndQueueFullGetsResourceExhausted) {
  ServerOptions options;
  options.workers = 1;
  options.max_queue = 1;
  start(slow_job(probe_), options);
  const std::vector<Request> requests = requests_for(tetrahedron_front());

  // Call 1 runs on the only worker.
  grpc::ClientContext running_context;
  auto running = start_running_call(running_context, requests);
  ASSERT_NE(running, nullptr);

  // Call 2 waits in the queue: its first event says so.
  grpc::ClientContext queued_context;
  auto queued = stub_->MeshVolume(&queued_context);
  for (const Request& request : requests) ASSERT_TRUE(queued->Write(request));
  queued->WritesDone();
  Response first;
  ASSERT_TRUE(queued->Read(&first));
  ASSERT_TRUE(first.has_progress());
  EXPECT_EQ(first.progress().stage(), "queued");

  // Call 3 is refused at once, with a hint of when to retry.
  const Clock::time_point asked = Clock::now();
  grpc::ClientContext refused_context;
  const CallOutcome refused = call(requests, refused_context);
  const double seconds = std::chrono::duration<double>(Clock::now() - asked).count();
  EXPECT_EQ(refused.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_THAT(refused.status.error_message(), HasSubstr("busy"));
  EXPECT_EQ(retry_after(refused_context), "1000");
  EXPECT_LT(seconds, 2.0);

  running_context.TryCancel();
  queued_context.TryCancel();
  EXPECT_EQ(running->Finish().error_code(), grpc::StatusCode::CANCELLED);
  EXPECT_EQ(queued->Finish().error_code(), grpc::StatusCode::CANCELLED);
}

TEST_F(MesherServiceTest, CancellationReachesRunningJobWithin100ms) {
  start(slow_job(probe_));
  grpc::ClientContext context;
  auto stream = start_running_call(context, requests_for(tetrahedron_front()));
  ASSERT_NE(stream, nullptr);

  std::future<Clock::time_point> stopped = probe_->stopped.get_future();
  const Clock::time_point cancelled_at = Clock::now();
  context.TryCancel();
  ASSERT_EQ(stopped.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  const double latency_ms =
      std::chrono::duration<double, std::milli>(stopped.get() - cancelled_at).count();
  std::printf("cancellation reached the job after %.2f ms\n", latency_ms);
  EXPECT_LT(latency_ms, 1000.0);  // the target is 100 ms; generous against a loaded machine
  EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::CANCELLED);
}

TEST_F(MesherServiceTest, DeadlineStopsRunningJobAndCallEndsDeadlineExceeded) {
  start(slow_job(probe_));
  grpc::ClientContext context;
  const auto deadline = std::chrono::system_clock::now() + std::chrono::milliseconds(300);
  context.set_deadline(deadline);
  std::future<Clock::time_point> stopped = probe_->stopped.get_future();
  const CallOutcome outcome = call(requests_for(tetrahedron_front()), context);
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  ASSERT_EQ(stopped.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  const double late_ms =
      std::chrono::duration<double, std::milli>(std::chrono::system_clock::now() - deadline)
          .count();
  std::printf("the job had stopped %.2f ms after the deadline (upper bound)\n", late_ms);
  EXPECT_LT(late_ms, 1000.0);
  for (const Response& response : outcome.responses) EXPECT_FALSE(carries_mesh(response));
}

TEST_F(MesherServiceTest, ShutdownLetsCallInFlightFinishWhole) {
  start([](const Mesh& front, const VolumeParams&, Progress&) -> absl::StatusOr<VolumeJobOutput> {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    Mesh mesh = front;
    mesh.tets = {{0, 1, 2, 3}};
    mesh.tet_tags = {7};
    return output_with(std::move(mesh));
  });
  grpc::ClientContext context;
  auto stream = stub_->MeshVolume(&context);
  for (const Request& request : requests_for(tetrahedron_front())) {
    ASSERT_TRUE(stream->Write(request));
  }
  stream->WritesDone();
  Response first;
  ASSERT_TRUE(stream->Read(&first));  // "queued": the job is on its way

  std::thread stopper([this] { server_->shutdown(); });
  std::vector<Response> responses = {first};
  Response response;
  while (stream->Read(&response)) responses.push_back(response);
  const grpc::Status status = stream->Finish();
  stopper.join();
  EXPECT_TRUE(status.ok()) << status.error_message();
  ASSERT_TRUE(responses.back().has_summary());
  EXPECT_EQ(mesh_from(responses).tet_tags, std::vector<Index>{7});
}

// Graceful shutdown (issue 12, part 4): a call still running when --grace-period is over is
// stopped; it ends UNAVAILABLE (retryable elsewhere) and the drain completes soon after.
TEST_F(MesherServiceTest, DrainStopsCallsStillRunningAfterTheGracePeriod) {
  ServerOptions options;
  options.grace_period = std::chrono::milliseconds(300);
  start(slow_job(probe_), options);
  grpc::ClientContext context;
  auto running = start_running_call(context, requests_for(tetrahedron_front()));
  ASSERT_NE(running, nullptr);

  const Clock::time_point asked = Clock::now();
  std::thread stopper([this] { server_->shutdown(); });
  Response response;
  while (running->Read(&response)) {
  }
  const grpc::Status status = running->Finish();
  stopper.join();
  const double seconds = std::chrono::duration<double>(Clock::now() - asked).count();
  std::printf("drain with a 0.3 s grace period took %.2f s\n", seconds);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAVAILABLE) << status.error_message();
  EXPECT_THAT(status.error_message(), HasSubstr("--grace-period ran out"));
  EXPECT_LT(seconds, 5.0);  // the slow job gives up by itself only after 10 s
}

TEST_F(MesherServiceTest, DrainingServerRefusesNewCallsAndReportsNotServing) {
  start(slow_job(probe_));
  grpc::ClientContext running_context;
  auto running = start_running_call(running_context, requests_for(tetrahedron_front()));
  ASSERT_NE(running, nullptr);

  std::thread stopper([this] { server_->shutdown(); });
  auto health = grpc::health::v1::Health::NewStub(channel_);
  grpc::health::v1::HealthCheckResponse::ServingStatus serving =
      grpc::health::v1::HealthCheckResponse::SERVING;
  const Clock::time_point give_up = Clock::now() + std::chrono::seconds(5);
  while (serving == grpc::health::v1::HealthCheckResponse::SERVING && Clock::now() < give_up) {
    grpc::ClientContext context;
    grpc::health::v1::HealthCheckResponse response;
    if (health->Check(&context, {}, &response).ok()) serving = response.status();
  }
  EXPECT_EQ(serving, grpc::health::v1::HealthCheckResponse::NOT_SERVING);

  const CallOutcome refused = call(requests_for(tetrahedron_front()));
  EXPECT_EQ(refused.status.error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_THAT(refused.status.error_message(), HasSubstr("shutting down"));

  running_context.TryCancel();
  EXPECT_EQ(running->Finish().error_code(), grpc::StatusCode::CANCELLED);
  stopper.join();
}

TEST_F(MesherServiceTest, HealthCheckReportsServing) {
  start(counting_job(probe_));
  auto health = grpc::health::v1::Health::NewStub(channel_);
  grpc::ClientContext context;
  grpc::health::v1::HealthCheckRequest request;
  grpc::health::v1::HealthCheckResponse response;
  const grpc::Status status = health->Check(&context, request, &response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(response.status(), grpc::health::v1::HealthCheckResponse::SERVING);
}

// Waits for the next event of `queue` and expects it to be `tag`, completed.
void expect_next(grpc::CompletionQueue& queue, void* tag) {
  void* got = nullptr;
  bool ok = false;
  ASSERT_TRUE(queue.Next(&got, &ok));
  EXPECT_EQ(got, tag);
  EXPECT_TRUE(ok);
}

// Asks grpc.reflection.v1alpha.ServerReflection to list the services, through the generic
// stub with hand-encoded bytes (Debian ships no reflection client stubs).
TEST_F(MesherServiceTest, ReflectionListsTheMesherService) {
  start(counting_job(probe_));
  grpc::GenericStub stub(channel_);
  grpc::CompletionQueue queue;
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  const auto call = stub.PrepareCall(
      &context, "/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo", &queue);
  int tags[5];
  call->StartCall(&tags[0]);
  expect_next(queue, &tags[0]);

  // ServerReflectionRequest{list_services: ""}: field 7, length-delimited, empty.
  const char request_bytes[] = {0x3a, 0x00};
  grpc::Slice slice(request_bytes, sizeof request_bytes);
  call->Write(grpc::ByteBuffer(&slice, 1), &tags[1]);
  expect_next(queue, &tags[1]);
  call->WritesDone(&tags[2]);
  expect_next(queue, &tags[2]);

  grpc::ByteBuffer response;
  call->Read(&response, &tags[3]);
  expect_next(queue, &tags[3]);
  std::vector<grpc::Slice> slices;
  ASSERT_TRUE(response.Dump(&slices).ok());
  std::string bytes;
  for (const grpc::Slice& s : slices)
    bytes.append(reinterpret_cast<const char*>(s.begin()), s.size());
  EXPECT_THAT(bytes, HasSubstr("afmesh.v1.Mesher"));
  EXPECT_THAT(bytes, HasSubstr("grpc.health.v1.Health"));

  grpc::Status status;
  call->Finish(&status, &tags[4]);
  expect_next(queue, &tags[4]);
  EXPECT_TRUE(status.ok()) << status.error_message();
  queue.Shutdown();
  void* ignored_tag = nullptr;
  bool ignored_ok = false;
  while (queue.Next(&ignored_tag, &ignored_ok)) {
  }
}

// ---------------------------------------------------------------------------------------------
// Input validation: each rule, with the element or field named and no job run.

TEST_F(MesherServiceTest, RejectsTriangleIndexOutOfRange) {
  start(counting_job(probe_));
  Mesh front = tetrahedron_front();
  front.triangles[2] = {0, 7, 2};
  expect_rejected(requests_for(front), grpc::StatusCode::INVALID_ARGUMENT,
                  {"triangle 2", "point 7"});
}

TEST_F(MesherServiceTest, RejectsNegativeTriangleIndex) {
  start(counting_job(probe_));
  Mesh front = tetrahedron_front();
  front.triangles[3] = {1, -2, 3};
  expect_rejected(requests_for(front), grpc::StatusCode::INVALID_ARGUMENT, {"triangle 3", "-2"});
}

TEST_F(MesherServiceTest, RejectsNanCoordinate) {
  start(counting_job(probe_));
  Mesh front = tetrahedron_front();
  front.points[2][1] = std::numeric_limits<double>::quiet_NaN();
  expect_rejected(requests_for(front), grpc::StatusCode::INVALID_ARGUMENT, {"point 2", "y = nan"});
}

TEST_F(MesherServiceTest, RejectsInfiniteCoordinate) {
  start(counting_job(probe_));
  Mesh front = tetrahedron_front();
  front.points[3][2] = -std::numeric_limits<double>::infinity();
  expect_rejected(requests_for(front), grpc::StatusCode::INVALID_ARGUMENT, {"point 3", "z"});
}

TEST_F(MesherServiceTest, RejectsTriangleSliceBeforeHeader) {
  start(counting_job(probe_));
  const Mesh front = tetrahedron_front();
  expect_rejected({triangles_request(front, 0, 4), header_request(0.25, 4, 4)},
                  grpc::StatusCode::INVALID_ARGUMENT,
                  {"message 1", "triangles slice before the header"});
}

TEST_F(MesherServiceTest, RejectsSecondHeader) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests.push_back(header_request(0.25, 4, 4));
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT, {"second header"});
}

TEST_F(MesherServiceTest, RejectsEmptyMessage) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests.insert(requests.begin() + 1, Request());
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT, {"message 2", "empty"});
}

TEST_F(MesherServiceTest, RejectsZeroPoints) {
  start(counting_job(probe_));
  const Mesh front = tetrahedron_front();
  expect_rejected(
      {header_request(0.25, std::nullopt, std::nullopt), triangles_request(front, 0, 4)},
      grpc::StatusCode::INVALID_ARGUMENT, {"no points"});
}

TEST_F(MesherServiceTest, RejectsZeroTriangles) {
  start(counting_job(probe_));
  const Mesh front = tetrahedron_front();
  expect_rejected(
      {header_request(0.25, std::nullopt, std::nullopt), points_request(front.points, 0, 4)},
      grpc::StatusCode::INVALID_ARGUMENT, {"no triangles"});
}

TEST_F(MesherServiceTest, RejectsStreamWithoutHeader) {
  start(counting_job(probe_));
  expect_rejected({}, grpc::StatusCode::INVALID_ARGUMENT, {"without a header"});
}

TEST_F(MesherServiceTest, RejectsPointCountDifferingFromHeader) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests[0].mutable_header()->set_point_count(5);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"declared 5 points", "4 were sent"});
}

TEST_F(MesherServiceTest, RejectsMoreTrianglesThanHeaderDeclared) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests[0].mutable_header()->set_triangle_count(3);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"4 triangles sent", "the 3 the header declared"});
}

TEST_F(MesherServiceTest, RejectsPointSliceNotMultipleOfThree) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests[1].mutable_points()->add_xyz(1.0);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"message 2", "not a multiple of 3"});
}

TEST_F(MesherServiceTest, RejectsTagCountDifferingFromTriangleCount) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests[2].mutable_triangles()->add_tags(9);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT, {"5 tags for 4 triangles"});
}

TEST_F(MesherServiceTest, RejectsNonPositiveSize) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests[0].mutable_header()->mutable_options()->mutable_size()->set_max_size(0.0);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT, {"options.size.max_size"});
}

TEST_F(MesherServiceTest, RejectsGrowthBelowOne) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests[0].mutable_header()->mutable_options()->mutable_size()->set_growth(0.5);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT, {"options.size.growth"});
}

TEST_F(MesherServiceTest, InputOverPointLimitGetsResourceExhaustedNamingTheLimit) {
  ServerOptions options;
  options.service.limits.max_points = 3;
  start(counting_job(probe_), options);
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests[0].mutable_header()->clear_point_count();
  expect_rejected(requests, grpc::StatusCode::RESOURCE_EXHAUSTED, {"--max-points", "3"});
}

TEST_F(MesherServiceTest, HeaderDeclaringTooManyTrianglesIsRefusedAtOnce) {
  ServerOptions options;
  options.service.limits.max_triangles = 1000;
  start(counting_job(probe_), options);
  expect_rejected({header_request(0.25, 4, 1001)}, grpc::StatusCode::RESOURCE_EXHAUSTED,
                  {"--max-triangles", "1001"});
}

// ---------------------------------------------------------------------------------------------
// Size specification: sources and background grids reach the job as params.spec; bad ones are
// refused before any work, naming the field as the JSON spells it.

// The tetrahedron's requests with options.size parsed from `json` (protobuf JSON of SizeSpec).
std::vector<Request> requests_with_spec(const std::string& json) {
  std::vector<Request> requests = requests_for(tetrahedron_front());
  absl::StatusOr<v1::SizeSpec> spec = size_spec_proto_from_json(json);
  EXPECT_TRUE(spec.ok()) << spec.status();
  if (spec.ok()) *requests[0].mutable_header()->mutable_options()->mutable_size() = *spec;
  return requests;
}

// A point source at the origin with the given fields spliced in (JSON members).
std::string point_source_spec(const std::string& source_fields) {
  return R"({"maxSize": 0.5, "growth": 1.2, "sources": [{)" + source_fields + "}]}";
}

constexpr const char* kOrigin = R"("points": [{"x": 0, "y": 0, "z": 0}])";

TEST_F(MesherServiceTest, SpecWithSourcesReachesJobAsParamsSpec) {
  start(counting_job(probe_));
  const CallOutcome outcome = call(requests_with_spec(point_source_spec(
      std::string(kOrigin) +
      R"(, "delta0": 0.1, "r0": 0.2, "r1": 0.5, "polynomial": {"coefficients": [1.0, 0.5]})")));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  ASSERT_TRUE(probe_->params.spec.has_value());
  const SizeSpec& spec = *probe_->params.spec;
  EXPECT_EQ(spec.max_size, 0.5);
  EXPECT_EQ(spec.growth, 1.2);
  ASSERT_EQ(spec.sources.size(), 1u);
  EXPECT_EQ(spec.sources[0].r0, 0.2);
  ASSERT_TRUE(std::holds_alternative<PolynomialLaw>(spec.sources[0].law));
  EXPECT_EQ(std::get<PolynomialLaw>(spec.sources[0].law).coefficients,
            (std::vector<double>{1.0, 0.5}));
  EXPECT_FALSE(spec.background.has_value());
}

TEST_F(MesherServiceTest, UniformSizeLeavesParamsSpecUnset) {
  start(counting_job(probe_));
  const CallOutcome outcome = call(requests_for(tetrahedron_front()));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  EXPECT_FALSE(probe_->params.spec.has_value());
}

TEST_F(MesherServiceTest, RejectsSourceWithNonPositiveR1) {
  start(counting_job(probe_));
  expect_rejected(requests_with_spec(point_source_spec(
                      std::string(kOrigin) + R"(, "delta0": 0.1, "r1": 0, "power": {"gamma": 1})")),
                  grpc::StatusCode::INVALID_ARGUMENT, {"options.size.sources[0].r1", "> 0"});
}

TEST_F(MesherServiceTest, RejectsSourceWithoutPoints) {
  start(counting_job(probe_));
  expect_rejected(
      requests_with_spec(point_source_spec(R"("delta0": 0.1, "r1": 1, "power": {"gamma": 1})")),
      grpc::StatusCode::INVALID_ARGUMENT, {"options.size.sources[0].points", "got 0"});
}

TEST_F(MesherServiceTest, RejectsSourceWithFourPoints) {
  start(counting_job(probe_));
  expect_rejected(requests_with_spec(point_source_spec(
                      R"("points": [{}, {"x": 1}, {"y": 1}, {"z": 1}], "delta0": 0.1, "r1": 1,)"
                      R"( "power": {"gamma": 1})")),
                  grpc::StatusCode::INVALID_ARGUMENT, {"options.size.sources[0].points", "got 4"});
}

TEST_F(MesherServiceTest, RejectsNanDelta0SentAsJsonNan) {
  start(counting_job(probe_));
  expect_rejected(requests_with_spec(point_source_spec(
                      std::string(kOrigin) +
                      R"(, "delta0": "NaN", "r1": 1, "exponential": {"gamma": 1})")),
                  grpc::StatusCode::INVALID_ARGUMENT, {"options.size.sources[0].delta0", "nan"});
}

TEST_F(MesherServiceTest, RejectsSourceWithoutLaw) {
  start(counting_job(probe_));
  expect_rejected(
      requests_with_spec(point_source_spec(std::string(kOrigin) + R"(, "delta0": 0.1, "r1": 1)")),
      grpc::StatusCode::INVALID_ARGUMENT, {"options.size.sources[0]", "no decay law"});
}

// A law this server does not know (a field number from a newer schema) arrives as an unknown
// field, so the source has no law it can use.
TEST_F(MesherServiceTest, RejectsSourceWhoseLawIsUnknownToTheServer) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_with_spec(
      point_source_spec(std::string(kOrigin) + R"(, "delta0": 0.1, "r1": 1)"));
  v1::SizeSource& source = *requests[0].mutable_header()->mutable_options()->mutable_size()
                                ->mutable_sources(0);
  source.GetReflection()->MutableUnknownFields(&source)->AddLengthDelimited(99, "");
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"options.size.sources[0]", "no decay law"});
}

// The server is stateless and never opens client paths: the client inlines grid files.
TEST_F(MesherServiceTest, RejectsBackgroundFileSayingTheClientMustSendTheGrid) {
  start(counting_job(probe_));
  expect_rejected(requests_with_spec(R"({"maxSize": 0.5, "background": {"file": "bg.msh"}})"),
                  grpc::StatusCode::INVALID_ARGUMENT,
                  {"options.size.background.file", "servers never open client paths",
                   "the client must read the grid file and send the grid itself"});
}

TEST_F(MesherServiceTest, RejectsInvertedBackgroundTet) {
  start(counting_job(probe_));
  expect_rejected(
      requests_with_spec(R"({"maxSize": 0.5, "background": {
          "points": [{}, {"x": 1}, {"y": 1}, {"z": 1}], "tets": [0, 2, 1, 3],
          "sizes": [1, 1, 1, 1]}})"),
      grpc::StatusCode::INVALID_ARGUMENT, {"options.size.background.tets[0]"});
}

// An inline grid in the header (small grids, e.g. from grpcurl) still reaches the job.
TEST_F(MesherServiceTest, InlineBackgroundGridInTheHeaderReachesTheJob) {
  start(counting_job(probe_));
  const CallOutcome outcome = call(requests_with_spec(R"({"maxSize": 0.5, "background": {
          "points": [{}, {"x": 1}, {"y": 1}, {"z": 1}], "tets": [0, 1, 2, 3],
          "sizes": [0.1, 0.2, 0.3, 0.4]}})"));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  ASSERT_TRUE(probe_->params.spec.has_value());
  ASSERT_TRUE(probe_->params.spec->background.has_value());
  EXPECT_EQ(probe_->params.spec->background->sizes, (std::vector<double>{0.1, 0.2, 0.3, 0.4}));
}

// A streamed background grid: the header declares its counts, BackgroundGridSlice messages carry
// points, sizes and tets (each list continuing across slices independently).

// A structured grid of (n+1)^3 points over [-1, 2]^3 with size 0.1 + 0.01 * (point index).
BackgroundGridSpec structured_grid(int n) {
  Mesh mesh = box_tets({-1, -1, -1}, {2, 2, 2}, n);
  BackgroundGridSpec grid{.points = std::move(mesh.points), .tets = std::move(mesh.tets), .sizes = {}};
  for (std::size_t i = 0; i < grid.points.size(); ++i) grid.sizes.push_back(0.1 + 0.01 * i);
  return grid;
}

// The tetrahedron's requests with `grid` streamed in slices of `slice` items, points and tets
// of one slice together and sizes in slices of their own, after the front's slices.
std::vector<Request> requests_with_grid(const BackgroundGridSpec& grid, std::size_t slice) {
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests[0].mutable_header()->set_grid_point_count(grid.points.size());
  requests[0].mutable_header()->set_grid_tet_count(grid.tets.size());
  const std::size_t longest = std::max(grid.points.size(), grid.tets.size());
  for (std::size_t begin = 0; begin < longest; begin += slice) {
    v1::BackgroundGridSlice& part = *requests.emplace_back().mutable_background_grid();
    if (begin < grid.points.size()) {
      wire::encode_grid_points(grid.points, begin, wire::slice_end(begin, grid.points.size(), slice),
                               part);
    }
    if (begin < grid.tets.size()) {
      wire::encode_grid_tets(grid.tets, begin, wire::slice_end(begin, grid.tets.size(), slice),
                             part);
    }
  }
  for (std::size_t begin = 0; begin < grid.sizes.size(); begin += slice) {
    wire::encode_grid_sizes(grid.sizes, begin, wire::slice_end(begin, grid.sizes.size(), slice),
                            *requests.emplace_back().mutable_background_grid());
  }
  return requests;
}

TEST_F(MesherServiceTest, StreamedBackgroundGridReachesTheJobWholeAndBitExact) {
  start(counting_job(probe_));
  const BackgroundGridSpec grid = structured_grid(4);  // 125 points, 384 tets
  const std::vector<Request> requests = requests_with_grid(grid, 50);
  for (const Request& request : requests) EXPECT_LE(request.ByteSizeLong(), kMessageCap);
  const CallOutcome outcome = call(requests);
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  ASSERT_TRUE(probe_->params.spec.has_value());
  EXPECT_EQ(probe_->params.spec->max_size, 0.25);
  ASSERT_TRUE(probe_->params.spec->background.has_value());
  const BackgroundGridSpec& received = *probe_->params.spec->background;
  EXPECT_TRUE(same_bits(received.points, grid.points));
  EXPECT_EQ(received.tets, grid.tets);
  EXPECT_EQ(received.sizes, grid.sizes);
}

TEST_F(MesherServiceTest, RejectsFewerGridPointsThanDeclared) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_with_grid(structured_grid(2), 1000);
  requests[0].mutable_header()->set_grid_point_count(28);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"declared 28 background grid points (grid_point_count) but 27 were sent"});
}

TEST_F(MesherServiceTest, RejectsMoreGridTetsThanDeclared) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_with_grid(structured_grid(2), 1000);
  requests[0].mutable_header()->set_grid_tet_count(47);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"48 background grid tets sent, more than the 47", "grid_tet_count"});
}

TEST_F(MesherServiceTest, RejectsMissingGridSizes) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_with_grid(structured_grid(2), 1000);
  requests.pop_back();  // the sizes slice
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"declared 27 background grid points (grid_point_count), so as many sizes, "
                   "but 0 sizes were sent"});
}

TEST_F(MesherServiceTest, RejectsGridTetIndexOutOfRangeNamingTheTet) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_with_grid(structured_grid(2), 10);
  // Tet 12 (the slice of points and tets 10 to 19), corner 2.
  requests[4].mutable_background_grid()->set_tets(4 * 2 + 2, 27);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"background_grid.tets[12][2] = 27 is out of range [0, 27)"});
}

TEST_F(MesherServiceTest, RejectsNegativeGridTetIndexNamingTheTet) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_with_grid(structured_grid(2), 10);
  requests[4].mutable_background_grid()->set_tets(1, -3);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"background_grid.tets[10][1] = -3"});
}

TEST_F(MesherServiceTest, RejectsInvertedGridTetNamingIt) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_with_grid(structured_grid(2), 1000);
  auto& tets = *requests[3].mutable_background_grid()->mutable_tets();
  std::swap(tets[4 * 7 + 2], tets[4 * 7 + 3]);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"background_grid.tets[7]", "inverted"});
}

TEST_F(MesherServiceTest, RejectsNonPositiveAndNanGridSizesNamingThePoint) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_with_grid(structured_grid(2), 1000);
  requests.back().mutable_background_grid()->set_sizes(5, 0.0);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"background_grid.sizes[5] must be finite and > 0, got 0"});
  requests.back().mutable_background_grid()->set_sizes(5, std::nan(""));
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT, {"background_grid.sizes[5]"});
}

TEST_F(MesherServiceTest, RejectsNonFiniteGridPointNamingIt) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_with_grid(structured_grid(2), 1000);
  requests[3].mutable_background_grid()->set_xyz(3 * 4 + 1,
                                                 std::numeric_limits<double>::infinity());
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"background_grid.points[4].y must be finite, got inf"});
}

TEST_F(MesherServiceTest, RejectsGridSliceWithoutDeclaredCounts) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_with_grid(structured_grid(2), 1000);
  requests[0].mutable_header()->clear_grid_point_count();
  requests[0].mutable_header()->clear_grid_tet_count();
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"message 4 is a background_grid slice", "grid_point_count and grid_tet_count"});
}

TEST_F(MesherServiceTest, RejectsHeaderDeclaringOnlyOneGridCount) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_with_grid(structured_grid(2), 1000);
  requests[0].mutable_header()->clear_grid_tet_count();
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"sets grid_point_count but not grid_tet_count"});
}

TEST_F(MesherServiceTest, RejectsGridBothInlineAndStreamed) {
  start(counting_job(probe_));
  std::vector<Request> requests = requests_with_grid(structured_grid(2), 1000);
  *requests[0].mutable_header()->mutable_options()->mutable_size()->mutable_background() =
      size_spec_to_proto(SizeSpec{.max_size = 1.0,
                                  .growth = 1.0,
                                  .sources = {},
                                  .background = structured_grid(1)})
          .background();
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"options.size.background", "one way only"});
}

TEST_F(MesherServiceTest, GridCountsOverTheLimitsAreRefusedAtOnceNamingTheFlag) {
  ServerOptions options;
  options.service.limits.max_grid_points = 26;
  options.service.limits.max_grid_tets = 47;
  start(counting_job(probe_), options);
  std::vector<Request> requests = requests_with_grid(structured_grid(2), 1000);
  expect_rejected({requests[0]}, grpc::StatusCode::RESOURCE_EXHAUSTED,
                  {"27 background grid points", "--max-grid-points"});
  requests[0].mutable_header()->set_grid_point_count(26);
  expect_rejected({requests[0]}, grpc::StatusCode::RESOURCE_EXHAUSTED,
                  {"48 background grid tets", "--max-grid-tets"});
}

TEST_F(MesherServiceTest, InlineGridOverTheLimitIsRefusedNamingTheFlag) {
  ServerOptions options;
  options.service.limits.max_grid_points = 3;
  start(counting_job(probe_), options);
  expect_rejected(requests_with_spec(R"({"maxSize": 0.5, "background": {
          "points": [{}, {"x": 1}, {"y": 1}, {"z": 1}], "tets": [0, 1, 2, 3],
          "sizes": [1, 1, 1, 1]}})"),
                  grpc::StatusCode::RESOURCE_EXHAUSTED,
                  {"4 background grid points", "--max-grid-points"});
}

// ---------------------------------------------------------------------------------------------
// Crossing environments (VolumeOptions.environments, paper §2): computed on the worker before
// the job, which receives them as params.face_environments.

Mesh dome_front() {
  absl::StatusOr<Mesh> dome = read_mesh(std::string(AFMESH_SOURCE_DIR) + "/examples/dome/dome.mesh");
  EXPECT_TRUE(dome.ok()) << dome.status();
  return dome.ok() ? *std::move(dome) : Mesh{};
}

std::vector<Request> requests_with_environments(const Mesh& front, v1::EnvironmentMode mode) {
  std::vector<Request> requests = requests_for(front);
  requests[0].mutable_header()->mutable_options()->set_environments(mode);
  return requests;
}

std::vector<std::string> warnings_of(const CallOutcome& outcome) {
  std::vector<std::string> warnings;
  for (const Response& response : outcome.responses) {
    if (response.has_warning()) warnings.push_back(response.warning().message());
  }
  return warnings;
}

std::vector<std::string> stages_of(const CallOutcome& outcome) {
  std::vector<std::string> stages;
  for (const Response& response : outcome.responses) {
    if (!response.has_summary()) continue;
    for (const v1::StageTiming& timing : response.summary().timings()) {
      stages.push_back(timing.stage());
    }
  }
  return stages;
}

TEST_F(MesherServiceTest, WithoutEnvironmentsTheJobGetsNone) {
  start(counting_job(probe_));
  const CallOutcome outcome = call(requests_for(dome_front()));  // crossing, but not checked here
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  EXPECT_TRUE(probe_->params.face_environments.empty());
  EXPECT_THAT(stages_of(outcome), ::testing::Not(::testing::Contains("environments")));
}

TEST_F(MesherServiceTest, TagEnvironmentsReachTheJob) {
  start(counting_job(probe_));
  const Mesh dome = dome_front();
  const CallOutcome outcome = call(requests_with_environments(dome, v1::ENVIRONMENT_MODE_TAGS));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  EXPECT_EQ(probe_->params.face_environments, dome.triangle_tags);
  EXPECT_THAT(warnings_of(outcome),
              ::testing::Contains(HasSubstr("from tags: 2 environments on 1048 of 1264")));
  EXPECT_THAT(stages_of(outcome), ::testing::Contains("environments"));
}

TEST_F(MesherServiceTest, AutoEnvironmentsReachTheJob) {
  start(counting_job(probe_));
  const Mesh dome = dome_front();
  const CallOutcome outcome = call(requests_with_environments(dome, v1::ENVIRONMENT_MODE_AUTO));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  absl::StatusOr<DetectedEnvironments> expected = detect_environments(dome, {}, no_progress());
  ASSERT_TRUE(expected.ok()) << expected.status();
  EXPECT_EQ(probe_->params.face_environments, expected->environments.face);
  EXPECT_EQ(count_environments(probe_->params.face_environments), 2);
  EXPECT_THAT(warnings_of(outcome), ::testing::Contains(HasSubstr("found: 2 environments")));
}

TEST_F(MesherServiceTest, RejectsTagEnvironmentsWithoutTags) {
  start(counting_job(probe_));
  Mesh front = tetrahedron_front();
  front.triangle_tags.assign(4, 0);
  expect_rejected(requests_with_environments(front, v1::ENVIRONMENT_MODE_TAGS),
                  grpc::StatusCode::INVALID_ARGUMENT,
                  {"ENVIRONMENT_MODE_TAGS", "none of the 4 triangles carries a positive tag"});
}

TEST_F(MesherServiceTest, RejectsNegativeTagAsEnvironment) {
  start(counting_job(probe_));
  Mesh front = tetrahedron_front();
  front.triangle_tags[2] = -5;
  expect_rejected(requests_with_environments(front, v1::ENVIRONMENT_MODE_TAGS),
                  grpc::StatusCode::INVALID_ARGUMENT, {"triangle 2 has tag -5"});
}

TEST_F(MesherServiceTest, RejectsCrossingWithinOneEnvironment) {
  start(counting_job(probe_));
  Mesh dome = dome_front();
  for (Index& tag : dome.triangle_tags) tag = tag > 0 ? 1 : 0;  // both sides in environment 1
  expect_rejected(requests_with_environments(dome, v1::ENVIRONMENT_MODE_TAGS),
                  grpc::StatusCode::INVALID_ARGUMENT,
                  {"invalid front: no_self_intersections", "within environment 1"});
}

TEST_F(MesherServiceTest, RejectsUnknownEnvironmentMode) {
  start(counting_job(probe_));
  expect_rejected(requests_with_environments(tetrahedron_front(),
                                             static_cast<v1::EnvironmentMode>(7)),
                  grpc::StatusCode::INVALID_ARGUMENT, {"options.environments", "unknown value 7"});
}

// ---------------------------------------------------------------------------------------------
// Limits up front (issue 12, part 1): what a request asks for is estimated before meshing
// (core/volume/estimate_elements.h) and checked against --max-elements and the memory budget.

std::vector<Request> tetrahedron_requests_at(double size) {
  std::vector<Request> requests = requests_for(tetrahedron_front());
  requests[0].mutable_header()->mutable_options()->mutable_size()->set_max_size(size);
  return requests;
}

TEST_F(MesherServiceTest, ASizeAskingForTrillionsOfTetsIsRefusedWithItsEstimateBeforeMeshing) {
  start(counting_job(probe_));
  // Volume 1/6 at edges of 1e-4: about 1.5e12 tets.
  expect_rejected(tetrahedron_requests_at(1e-4), grpc::StatusCode::RESOURCE_EXHAUSTED,
                  {"about 1.51e+12 tetrahedra", "limit of 100000000 (--max-elements)"});
  // Asking again cannot help: no retry hint.
  grpc::ClientContext context;
  EXPECT_EQ(call(tetrahedron_requests_at(1e-4), context).status.error_code(),
            grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(retry_after(context), "");
}

TEST_F(MesherServiceTest, AJobNeedingMoreThanTheWholeMemoryBudgetIsRefused) {
  ServerOptions options;
  options.service.memory_budget_bytes = std::int64_t{1} << 20;
  start(counting_job(probe_), options);
  expect_rejected(tetrahedron_requests_at(0.01), grpc::StatusCode::RESOURCE_EXHAUSTED,
                  {"memory budget of 0.000977 GiB (--memory-budget-mb)"});
}

TEST_F(MesherServiceTest, ABudgetHeldByARunningJobRefusesTheNextUntilItEnds) {
  ServerOptions options;
  options.service.memory_budget_bytes = std::int64_t{5} << 20;  // one job of ~3 MB fits
  start(slow_job(probe_), options);
  const std::vector<Request> requests = tetrahedron_requests_at(0.05);
  grpc::ClientContext running_context;
  auto running = start_running_call(running_context, requests);
  ASSERT_NE(running, nullptr);

  grpc::ClientContext refused_context;
  const CallOutcome refused = call(requests, refused_context);
  EXPECT_EQ(refused.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_THAT(refused.status.error_message(), HasSubstr("held by the jobs running now"));
  EXPECT_EQ(retry_after(refused_context), "2000");
  EXPECT_THAT(refused.status.error_message(), HasSubstr("retry later"));
  EXPECT_EQ(probe_->runs.load(), 1);

  running_context.TryCancel();
  EXPECT_EQ(running->Finish().error_code(), grpc::StatusCode::CANCELLED);
  // The cancelled call's reservation is given back once the call is gone; a new job runs then.
  bool admitted = false;
  for (int attempt = 0; attempt < 100 && !admitted; ++attempt) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(200));
    const CallOutcome outcome = call(requests, context);
    admitted = outcome.status.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED;
  }
  EXPECT_TRUE(admitted);
  EXPECT_GE(probe_->runs.load(), 2);
}

// A client that stops reading its result would hold the finished mesh and its share of the
// budget for as long as it liked: after --stall-timeout with a write pending the call ends.
TEST_F(MesherServiceTest, AClientThatStopsReadingIsCancelledAfterTheStallTimeoutFreeingItsBudget) {
  ServerOptions options;
  options.service.memory_budget_bytes = std::int64_t{5} << 20;  // one job of ~3 MB fits
  options.service.stall_timeout = std::chrono::milliseconds(300);
  start(fixed_job(large_mesh()), options);
  const std::vector<Request> requests = tetrahedron_requests_at(0.05);
  // A receive window of 64 KiB that does not grow: the ~4 MB result cannot all be in flight.
  grpc::ChannelArguments small_window;
  small_window.SetInt(GRPC_ARG_HTTP2_BDP_PROBE, 0);
  small_window.SetInt(GRPC_ARG_HTTP2_STREAM_LOOKAHEAD_BYTES, 64 * 1024);
  std::unique_ptr<v1::Mesher::Stub> stalled_stub = v1::Mesher::NewStub(grpc::CreateCustomChannel(
      server_->address(), grpc::InsecureChannelCredentials(), small_window));
  grpc::ClientContext stalled_context;
  auto stalled = stalled_stub->MeshVolume(&stalled_context);
  for (const Request& request : requests) ASSERT_TRUE(stalled->Write(request));
  stalled->WritesDone();
  Response response;
  int read = 0;
  while (stalled->Read(&response) && !carries_mesh(response)) ++read;  // then stops reading
  ASSERT_TRUE(carries_mesh(response)) << "no mesh slice after " << read << " messages";

  // While the stalled call holds the budget, a second job is refused; once the stall timeout
  // has ended the stalled call, the next one is admitted and streams whole to a client that
  // reads (the same 300 ms timeout does not touch it).
  bool admitted = false;
  for (int attempt = 0; attempt < 100 && !admitted; ++attempt) {
    const CallOutcome outcome = call(requests);
    admitted = outcome.status.ok();
    if (!admitted) {
      ASSERT_EQ(outcome.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED)
          << outcome.status.error_message();
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  EXPECT_TRUE(admitted);
  while (stalled->Read(&response)) ++read;
  EXPECT_EQ(stalled->Finish().error_code(), grpc::StatusCode::CANCELLED) << read << " read";
}

TEST_F(MesherServiceTest, ARequestOverTheByteLimitIsRefusedNamingTheFlag) {
  ServerOptions options;
  options.service.limits.max_request_bytes = 100;
  start(counting_job(probe_), options);
  expect_rejected(requests_for(large_mesh()), grpc::StatusCode::RESOURCE_EXHAUSTED,
                  {"limit of 100 bytes (--max-request-mb)"});
}

TEST_F(MesherServiceTest, SummaryCarriesTheEstimateTheLimitsWereCheckedAgainst) {
  start(counting_job(probe_));
  const CallOutcome outcome = call(tetrahedron_requests_at(0.05));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  ASSERT_TRUE(outcome.responses.back().has_summary());
  // (1/6) / (0.05^3 / (6 sqrt 2)) regular tets, times 1.07 for an advancing-front mesh.
  EXPECT_NEAR(outcome.responses.back().summary().estimated_tet_count(), 12'107, 10);
}

// Nothing silently: a front far coarser than the size asked is said to be, before meshing.
TEST_F(MesherServiceTest, AFrontFarCoarserThanTheSizeAskedIsWarnedAbout) {
  start(counting_job(probe_));
  const CallOutcome outcome = call(tetrahedron_requests_at(0.05));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  std::string warnings;
  for (const Response& response : outcome.responses) {
    if (response.has_warning()) warnings += response.warning().message() + "\n";
  }
  EXPECT_THAT(warnings, HasSubstr("4 of the 4 input triangles have edges over 3 times the size "
                                  "asked on them (up to 28.3 times)"));
  EXPECT_THAT(warnings, HasSubstr("re-triangulate the surface at the size first"));
}

}  // namespace
}  // namespace afmesh::server
