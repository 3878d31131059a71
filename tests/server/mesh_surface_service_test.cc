// MeshSurface in-process, on a unix socket, with fake surface jobs (the core's surface front is
// not linked): the header first, slices in and out bit-exact with tags, the SurfaceSummary,
// validation errors naming the field or element, the estimate against --max-elements and the
// memory budget, cancellation, and MeshVolume's remesh_surface running both jobs in one call.
#include <stdlib.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <future>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "afmesh/v1/mesher.grpc.pb.h"
#include "gmock/gmock.h"
#include "google/protobuf/util/json_util.h"
#include "grpc/grpc.h"
#include "grpcpp/grpcpp.h"
#include "gtest/gtest.h"
#include "proto/slice_codec.h"
#include "server/server.h"
#include "server/surface_step.h"
#include "tests/server/request_support.h"

namespace afmesh::server {
namespace {

using Clock = std::chrono::steady_clock;
using ::testing::HasSubstr;
using Request = v1::MeshSurfaceRequest;
using Response = v1::MeshSurfaceResponse;
using afmesh::testing::carries_mesh;
using afmesh::testing::mesh_from;
using afmesh::testing::same_bits;
using afmesh::testing::tetrahedron_front;

// A surface needing several slices of each kind, with coordinates that only survive a bit-exact
// transfer and negative tags (the longest varints).
Mesh large_surface() {
  constexpr int kPoints = 70'001;
  constexpr int kTriangles = 40'000;
  Mesh mesh;
  for (int i = 0; i < kPoints; ++i) {
    mesh.points.push_back({i / 3.0, i % 2 == 0 ? -0.0 : 1.0 / (i + 1), std::sin(i)});
  }
  for (int i = 0; i < kTriangles; ++i) {
    mesh.triangles.push_back({i, (i + 1) % kPoints, (i + 2) % kPoints});
    mesh.triangle_tags.push_back(i % 3 == 0 ? -7 : i);
  }
  return mesh;
}

SurfaceResult result_with(Mesh mesh) {
  SurfaceResult result;
  result.mesh = std::move(mesh);
  result.report = {.input_points = 4,
                   .input_triangles = 4,
                   .duplicate_triangles_dropped = 1,
                   .degenerate_triangles_dropped = 2,
                   .unused_points_dropped = 3,
                   .triangles_reoriented = 4,
                   .folded_slivers_collapsed = 2,
                   .longest_folded_edge_collapsed = 0.25,
                   .sliver_steps_removed = 6,
                   .highest_sliver_step = 0.125,
                   .components = 1,
                   .closed_components = 1,
                   .patches = 4,
                   .lines = 6,
                   .corners = 4,
                   .short_ridges_dropped = 5,
                   .hausdorff = 0.125,
                   .max_vertex_distance = 0.0625,
                   .model_size = 1.75,
                   .patches_from_input = 1,
                   .front_stops = {"the surface front of patch 2 (input tag 0) got stuck"},
                   .wall_sizes_after_crossing = 1.0,
                   .thin_triangles_at_thinner_input = 7};
  result.timings = {{"features", 0.5}, {"front", 0.25}};
  return result;
}

// What the jobs saw, and the cancellation they noticed.
struct Probe {
  std::atomic<int> surface_runs{0};
  std::atomic<int> volume_runs{0};
  Mesh input;           // the surface job's input
  SurfaceParams params;  // its params
  Mesh volume_front;     // the volume job's front
  std::promise<void> started;
  std::promise<Clock::time_point> stopped;
};

// Returns `mesh` (whatever the input) after some progress.
SurfaceJob fixed_job(std::shared_ptr<Probe> probe, Mesh mesh) {
  return [probe, mesh](const Mesh& input, const SurfaceParams& params,
                       Progress& progress) -> absl::StatusOr<SurfaceResult> {
    if (probe->surface_runs.fetch_add(1) == 0) {
      probe->input = input;
      probe->params = params;
    }
    progress.report("front", 0.5);
    return result_with(mesh);
  };
}

// Polls cancellation every millisecond; INTERNAL after 10 s so that a broken path fails.
SurfaceJob slow_job(std::shared_ptr<Probe> probe) {
  return [probe](const Mesh&, const SurfaceParams&,
                 Progress& progress) -> absl::StatusOr<SurfaceResult> {
    probe->surface_runs.fetch_add(1);
    probe->started.set_value();
    const Clock::time_point give_up = Clock::now() + std::chrono::seconds(10);
    while (Clock::now() < give_up) {
      if (progress.cancelled()) {
        probe->stopped.set_value(Clock::now());
        return absl::CancelledError("stopped");
      }
      progress.report("front", -1.0);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return absl::InternalError("the job was never cancelled");
  };
}

// The volume job of remesh_surface calls: one tet on whatever front it gets.
VolumeJob one_tet_job(std::shared_ptr<Probe> probe) {
  return [probe](const Mesh& front, const VolumeParams&,
                 Progress&) -> absl::StatusOr<VolumeJobOutput> {
    probe->volume_runs.fetch_add(1);
    probe->volume_front = front;
    VolumeJobOutput output;
    output.volume.mesh = front;
    output.volume.mesh.tets = {{0, 1, 2, 3}};
    output.volume.mesh.tet_tags = {0};
    output.validation.passed = true;
    return output;
  };
}

Request header(double size, double ridge = 0.0, double corner = 0.0) {
  Request request;
  v1::MeshSurfaceHeader& h = *request.mutable_header();
  h.mutable_options()->mutable_size()->set_max_size(size);
  h.mutable_options()->mutable_size()->set_growth(1.2);
  h.mutable_options()->set_ridge_angle_deg(ridge);
  h.mutable_options()->set_corner_angle_deg(corner);
  return request;
}

// `head`, then the points and triangles of `input` in slices of at most 32768.
std::vector<Request> requests_for(const Mesh& input, Request head) {
  head.mutable_header()->set_point_count(input.points.size());
  head.mutable_header()->set_triangle_count(input.triangles.size());
  std::vector<Request> requests = {head};
  for (std::size_t begin = 0; begin < input.points.size(); begin += wire::kMaxSliceItems) {
    wire::encode_points(input.points, begin, wire::slice_end(begin, input.points.size()),
                        *requests.emplace_back().mutable_points());
  }
  for (std::size_t begin = 0; begin < input.triangles.size(); begin += wire::kMaxSliceItems) {
    wire::encode_triangles(input.triangles, input.triangle_tags, begin,
                           wire::slice_end(begin, input.triangles.size()),
                           *requests.emplace_back().mutable_triangles());
  }
  return requests;
}

std::vector<Request> tetrahedron_requests(double size = 0.5) {
  return requests_for(tetrahedron_front(), header(size));
}

struct Outcome {
  grpc::Status status;
  std::vector<Response> responses;
};

class MeshSurfaceServiceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    static const bool initialised = (grpc_init(), true);
    (void)initialised;
  }

  void SetUp() override {
    char pattern[] = "/tmp/afmesh-surface-test-XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    dir_ = pattern;
  }

  void TearDown() override {
    if (server_ != nullptr) server_->shutdown();
    std::filesystem::remove_all(dir_);
  }

  void start(SurfaceJob job, ServerOptions options = {}) {
    options.listen = "unix:" + dir_ + "/mesher.sock";
    options.workers = 2;
    options.service.log_calls = false;
    absl::StatusOr<std::unique_ptr<MesherServer>> server =
        MesherServer::start(options, one_tet_job(probe_), std::move(job));
    ASSERT_TRUE(server.ok()) << server.status();
    server_ = *std::move(server);
    stub_ = v1::Mesher::NewStub(
        grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials()));
  }

  template <class Req, class Resp>
  static Outcome finish(grpc::ClientReaderWriter<Req, Resp>& stream,
                        const std::vector<Req>& requests, std::vector<Resp>& responses) {
    for (const Req& request : requests) {
      if (!stream.Write(request)) break;
    }
    stream.WritesDone();
    Resp response;
    while (stream.Read(&response)) responses.push_back(response);
    return {stream.Finish(), {}};
  }

  // A MeshVolume call; its responses in `responses`.
  Outcome call_volume(const std::vector<v1::MeshVolumeRequest>& requests,
                      std::vector<v1::MeshVolumeResponse>& responses) {
    grpc::ClientContext context;
    auto stream = stub_->MeshVolume(&context);
    return finish(*stream, requests, responses);
  }

  Outcome call(const std::vector<Request>& requests) {
    grpc::ClientContext context;
    auto stream = stub_->MeshSurface(&context);
    std::vector<Response> responses;
    Outcome outcome = finish(*stream, requests, responses);
    outcome.responses = std::move(responses);
    return outcome;
  }

  // Fails with `code`, a message holding each of `parts`, no mesh sent, no job run.
  void expect_rejected(const std::vector<Request>& requests, grpc::StatusCode code,
                       const std::vector<std::string>& parts) {
    const Outcome outcome = call(requests);
    EXPECT_EQ(outcome.status.error_code(), code) << outcome.status.error_message();
    for (const std::string& part : parts) {
      EXPECT_THAT(outcome.status.error_message(), HasSubstr(part));
    }
    for (const Response& response : outcome.responses) EXPECT_FALSE(carries_mesh(response));
    EXPECT_EQ(probe_->surface_runs.load(), 0);
  }

  std::string dir_;
  std::unique_ptr<MesherServer> server_;
  std::unique_ptr<v1::Mesher::Stub> stub_;
  std::shared_ptr<Probe> probe_ = std::make_shared<Probe>();
};

// ---------------------------------------------------------------------------------------------
// Streaming and the summary.

TEST_F(MeshSurfaceServiceTest, FakeSurfaceStreamsBackBitExactWithTagsInCappedSlices) {
  const Mesh surface = large_surface();
  start(fixed_job(probe_, surface));
  const Outcome outcome = call(tetrahedron_requests());
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  const Mesh received = mesh_from(outcome.responses);
  EXPECT_TRUE(same_bits(received.points, surface.points));
  EXPECT_EQ(received.triangles, surface.triangles);
  EXPECT_EQ(received.triangle_tags, surface.triangle_tags);
  for (const Response& response : outcome.responses) {
    EXPECT_LT(response.ByteSizeLong(), std::size_t{1} << 20);
    EXPECT_LE(response.points().xyz_size(), 3 * 32768);
    EXPECT_LE(response.triangles().indices_size(), 3 * 32768);
  }
}

TEST_F(MeshSurfaceServiceTest, WarningsComeBeforeTheSlicesAndTheSummaryLast) {
  start(fixed_job(probe_, tetrahedron_front()));
  const Outcome outcome = call(tetrahedron_requests());
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  ASSERT_FALSE(outcome.responses.empty());
  EXPECT_TRUE(outcome.responses.back().has_summary());
  EXPECT_TRUE(outcome.responses.front().has_progress());
  EXPECT_EQ(outcome.responses.front().progress().stage(), "queued");
  bool mesh_seen = false;
  std::vector<std::string> warnings;
  for (const Response& response : outcome.responses) {
    mesh_seen = mesh_seen || carries_mesh(response);
    if (response.has_warning()) {
      EXPECT_FALSE(mesh_seen) << "a warning after the mesh";
      warnings.push_back(response.warning().message());
    }
  }
  // The four repair counts of result_with, the short ridges, the front that stopped, the walls.
  ASSERT_EQ(warnings.size(), 9u);
  EXPECT_THAT(warnings[0], HasSubstr("1 duplicate triangles"));
  EXPECT_THAT(warnings[3], HasSubstr("4 triangles of the input were turned"));
  EXPECT_THAT(warnings[4], HasSubstr("2 sliver triangles of the input folded back"));
  EXPECT_THAT(warnings[4], HasSubstr("moved by at most 0.25"));
  EXPECT_THAT(warnings[5], HasSubstr("6 sliver triangles of the input standing as a step"));
  EXPECT_THAT(warnings[5], HasSubstr("moved by at most 0.125"));
  EXPECT_THAT(warnings[6], HasSubstr("5 ridges of the input that end freely"));
  EXPECT_THAT(warnings[7], HasSubstr("the surface front of patch 2 (input tag 0) got stuck; the "
                                     "patch was re-triangulated from its own input triangles"));
  EXPECT_THAT(warnings[8], HasSubstr("crossed itself across walls thinner than the size; it was "
                                     "made again with its triangles no longer than 1 times a "
                                     "wall's thickness"));
}

TEST_F(MeshSurfaceServiceTest, SummaryCarriesCountsQualityRepairFeaturesDistanceAndTimings) {
  start(fixed_job(probe_, tetrahedron_front()));
  const Outcome outcome = call(tetrahedron_requests(0.5));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  const v1::SurfaceSummary& summary = outcome.responses.back().summary();
  EXPECT_EQ(summary.point_count(), 4u);
  EXPECT_EQ(summary.triangle_count(), 4u);
  // The corner tetrahedron: three right isosceles faces (45, 45, 90) and one equilateral.
  EXPECT_NEAR(summary.quality().min_angle_deg(), 45.0, 1e-9);
  EXPECT_NEAR(summary.quality().max_angle_deg(), 90.0, 1e-9);
  EXPECT_EQ(summary.quality().share_below_30_deg(), 0.0);
  EXPECT_EQ(summary.quality().count_below_15_deg(), 0u);
  // The core's count, passed on as it is (the fake job's report).
  EXPECT_EQ(summary.quality().count_below_15_deg_at_thinner_input(), 7u);
  EXPECT_EQ(summary.repair().duplicate_triangles_dropped(), 1u);
  EXPECT_EQ(summary.repair().degenerate_triangles_dropped(), 2u);
  EXPECT_EQ(summary.repair().unused_points_dropped(), 3u);
  EXPECT_EQ(summary.repair().triangles_reoriented(), 4u);
  EXPECT_EQ(summary.repair().components(), 1u);
  EXPECT_EQ(summary.repair().closed_components(), 1u);
  EXPECT_EQ(summary.repair().folded_slivers_collapsed(), 2u);
  EXPECT_EQ(summary.repair().longest_folded_edge_collapsed(), 0.25);
  EXPECT_EQ(summary.repair().sliver_steps_removed(), 6u);
  EXPECT_EQ(summary.repair().highest_sliver_step(), 0.125);
  EXPECT_EQ(summary.features().patches(), 4u);
  EXPECT_EQ(summary.features().lines(), 6u);
  EXPECT_EQ(summary.features().corners(), 4u);
  EXPECT_EQ(summary.features().short_ridges_dropped(), 5u);
  EXPECT_EQ(summary.features().patches_from_input(), 1u);
  EXPECT_EQ(summary.distance().hausdorff(), 0.125);
  EXPECT_EQ(summary.distance().max_vertex_distance(), 0.0625);
  EXPECT_EQ(summary.distance().model_size(), 1.75);
  // Area 1.5 + sqrt(3)/2 over sqrt(3)/4 * 0.25: about 22.9 triangles.
  EXPECT_NEAR(summary.estimated_triangle_count(),
              (1.5 + std::sqrt(3.0) / 2.0) / (std::sqrt(3.0) / 4.0 * 0.25), 1e-9);
  std::vector<std::string> stages;
  for (const v1::StageTiming& timing : summary.timings()) stages.push_back(timing.stage());
  EXPECT_THAT(stages, ::testing::ElementsAre("receive", "queue", "estimate", "features", "front",
                                             "send"));
}

TEST_F(MeshSurfaceServiceTest, JobReceivesTheInputTagsAndOptionsAsSent) {
  start(fixed_job(probe_, tetrahedron_front()));
  ASSERT_TRUE(call(requests_for(tetrahedron_front(), header(0.25, 40.0, 75.0))).status.ok());
  EXPECT_TRUE(same_bits(probe_->input.points, tetrahedron_front().points));
  EXPECT_EQ(probe_->input.triangle_tags, tetrahedron_front().triangle_tags);
  EXPECT_EQ(probe_->params.size, 0.25);
  EXPECT_EQ(probe_->params.growth, 1.2);
  EXPECT_EQ(probe_->params.ridge_angle_deg, 40.0);
  EXPECT_EQ(probe_->params.corner_angle_deg, 75.0);
  EXPECT_FALSE(probe_->params.spec.has_value());
  EXPECT_EQ(probe_->params.max_triangles, InputLimits{}.max_elements);
}

TEST_F(MeshSurfaceServiceTest, UnsetAnglesMeanTheCoreDefaults) {
  start(fixed_job(probe_, tetrahedron_front()));
  ASSERT_TRUE(call(tetrahedron_requests()).status.ok());
  EXPECT_EQ(probe_->params.ridge_angle_deg, SurfaceParams{}.ridge_angle_deg);
  EXPECT_EQ(probe_->params.corner_angle_deg, SurfaceParams{}.corner_angle_deg);
  EXPECT_EQ(probe_->params.curvature_angle_deg, SurfaceParams{}.curvature_angle_deg);
  EXPECT_EQ(probe_->params.curvature_deviation, SurfaceParams{}.curvature_deviation);
  EXPECT_EQ(probe_->params.wall_sizes, SurfaceParams{}.wall_sizes);
}

// wall_sizes likewise: unset is the default (above, none), any value in [0, 100) reaches the
// job; outside it, or not finite, it is refused naming the field.
TEST_F(MeshSurfaceServiceTest, WallSizesReachTheJob) {
  start(fixed_job(probe_, tetrahedron_front()));
  Request head = header(0.25);
  head.mutable_header()->mutable_options()->set_wall_sizes(1.5);
  ASSERT_TRUE(call(requests_for(tetrahedron_front(), head)).status.ok());
  EXPECT_EQ(probe_->params.wall_sizes, 1.5);
}

TEST_F(MeshSurfaceServiceTest, RejectsWallSizesOutsideZeroTo100) {
  start(fixed_job(probe_, tetrahedron_front()));
  for (const double walls : {100.0, -1.0, std::nan(""), HUGE_VAL}) {
    Request bad = header(0.25);
    bad.mutable_header()->mutable_options()->set_wall_sizes(walls);
    expect_rejected(requests_for(tetrahedron_front(), bad), grpc::StatusCode::INVALID_ARGUMENT,
                    {"options.wall_sizes must be in [0, 100)"});
  }
}

// curvature_deviation likewise: unset is the default (above), 0 turns the chord bound off, any
// other value in (0, 1) is the bound; outside [0, 1) it is refused, naming the field.
TEST_F(MeshSurfaceServiceTest, CurvatureDeviationReachesTheJob) {
  start(fixed_job(probe_, tetrahedron_front()));
  Request head = header(0.25);
  head.mutable_header()->mutable_options()->set_curvature_deviation(0.002);
  ASSERT_TRUE(call(requests_for(tetrahedron_front(), head)).status.ok());
  EXPECT_EQ(probe_->params.curvature_deviation, 0.002);
}

TEST_F(MeshSurfaceServiceTest, CurvatureDeviationOfZeroReachesTheJob) {
  start(fixed_job(probe_, tetrahedron_front()));
  Request head = header(0.25);
  head.mutable_header()->mutable_options()->set_curvature_deviation(0.0);
  ASSERT_TRUE(call(requests_for(tetrahedron_front(), head)).status.ok());
  EXPECT_EQ(probe_->params.curvature_deviation, 0.0);
}

TEST_F(MeshSurfaceServiceTest, RejectsCurvatureDeviationsOutsideZeroToOne) {
  start(fixed_job(probe_, tetrahedron_front()));
  for (const double deviation : {1.0, -1e-4, std::nan(""), HUGE_VAL}) {
    Request head = header(0.25);
    head.mutable_header()->mutable_options()->set_curvature_deviation(deviation);
    expect_rejected(requests_for(tetrahedron_front(), head), grpc::StatusCode::INVALID_ARGUMENT,
                    {"options.curvature_deviation must be in [0, 1)"});
  }
}

// curvature_angle_deg is optional on the wire: unset is the default (above), 0 turns the
// curvature bound off (here), any other value in (0, 180) is the bound (the JSON test below).
TEST_F(MeshSurfaceServiceTest, CurvatureAngleOfZeroReachesTheJob) {
  start(fixed_job(probe_, tetrahedron_front()));
  Request head = header(0.25);
  head.mutable_header()->mutable_options()->set_curvature_angle_deg(0.0);
  ASSERT_TRUE(call(requests_for(tetrahedron_front(), head)).status.ok());
  EXPECT_EQ(probe_->params.curvature_angle_deg, 0.0);
}

TEST_F(MeshSurfaceServiceTest, RejectsCurvatureAnglesOutsideZeroTo180) {
  start(fixed_job(probe_, tetrahedron_front()));
  for (const double angle : {180.0, -1.0, std::nan("")}) {
    Request head = header(0.25);
    head.mutable_header()->mutable_options()->set_curvature_angle_deg(angle);
    expect_rejected(requests_for(tetrahedron_front(), head), grpc::StatusCode::INVALID_ARGUMENT,
                    {"options.curvature_angle_deg must be in [0, 180)"});
  }
}

// The header as a JSON user would write it (protobuf's JSON mapping), with a source.
TEST_F(MeshSurfaceServiceTest, HeaderFromProtoJsonCarriesItsSpecToTheJob) {
  start(fixed_job(probe_, tetrahedron_front()));
  Request head;
  const auto parsed = google::protobuf::util::JsonStringToMessage(
      R"({"options": {"size": {"maxSize": 0.5, "growth": 1.3,
           "sources": [{"points": [{"x": 0, "y": 0, "z": 0}], "delta0": 0.05, "r0": 0.1,
                        "r1": 0.2, "power": {"gamma": 1.5}}]},
          "ridgeAngleDeg": 45, "cornerAngleDeg": 90, "curvatureAngleDeg": 12.5}})",
      head.mutable_header());
  ASSERT_TRUE(parsed.ok()) << parsed.ToString();
  ASSERT_TRUE(call(requests_for(tetrahedron_front(), head)).status.ok());
  ASSERT_TRUE(probe_->params.spec.has_value());
  EXPECT_EQ(probe_->params.spec->max_size, 0.5);
  EXPECT_EQ(probe_->params.spec->growth, 1.3);
  ASSERT_EQ(probe_->params.spec->sources.size(), 1u);
  EXPECT_EQ(probe_->params.ridge_angle_deg, 45.0);
  EXPECT_EQ(probe_->params.corner_angle_deg, 90.0);
  EXPECT_EQ(probe_->params.curvature_angle_deg, 12.5);
}

TEST_F(MeshSurfaceServiceTest, JobFailureReachesTheClientWithoutSlices) {
  start([](const Mesh&, const SurfaceParams&, Progress&) -> absl::StatusOr<SurfaceResult> {
    return absl::FailedPreconditionError("patch 3 could not be closed near (1, 2, 3)");
  });
  const Outcome outcome = call(tetrahedron_requests());
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_THAT(outcome.status.error_message(), HasSubstr("patch 3"));
  for (const Response& response : outcome.responses) EXPECT_FALSE(carries_mesh(response));
}

TEST_F(MeshSurfaceServiceTest, JobExceptionBecomesInternalAndTheServerKeepsServing) {
  auto calls = std::make_shared<std::atomic<int>>(0);
  start([calls](const Mesh& input, const SurfaceParams&,
                Progress&) -> absl::StatusOr<SurfaceResult> {
    if (calls->fetch_add(1) == 0) throw std::runtime_error("boom");
    return result_with(input);
  });
  const Outcome first = call(tetrahedron_requests());
  EXPECT_EQ(first.status.error_code(), grpc::StatusCode::INTERNAL);
  EXPECT_THAT(first.status.error_message(), HasSubstr("boom"));
  EXPECT_TRUE(call(tetrahedron_requests()).status.ok());
}

TEST_F(MeshSurfaceServiceTest, JobSurfaceWithIndexOutOfRangeIsNotSent) {
  Mesh broken = tetrahedron_front();
  broken.triangles[2][1] = 9;
  start(fixed_job(probe_, broken));
  const Outcome outcome = call(tetrahedron_requests());
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::INTERNAL);
  EXPECT_THAT(outcome.status.error_message(), HasSubstr("triangle 2"));
  for (const Response& response : outcome.responses) EXPECT_FALSE(carries_mesh(response));
}

TEST_F(MeshSurfaceServiceTest, AServerWithoutASurfaceJobAnswersUnimplemented) {
  start(SurfaceJob{});
  const Outcome outcome = call(tetrahedron_requests());
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::UNIMPLEMENTED);
  EXPECT_THAT(outcome.status.error_message(), HasSubstr("no surface mesher"));
}

// ---------------------------------------------------------------------------------------------
// Validation: INVALID_ARGUMENT naming the field or element, before any job runs.

TEST_F(MeshSurfaceServiceTest, RejectsRidgeAngleOf180) {
  start(fixed_job(probe_, tetrahedron_front()));
  expect_rejected(requests_for(tetrahedron_front(), header(0.5, 180.0)),
                  grpc::StatusCode::INVALID_ARGUMENT,
                  {"options.ridge_angle_deg must be in (0, 180)", "got 180"});
}

TEST_F(MeshSurfaceServiceTest, RejectsNegativeAndNanCornerAngles) {
  start(fixed_job(probe_, tetrahedron_front()));
  expect_rejected(requests_for(tetrahedron_front(), header(0.5, 0.0, -5.0)),
                  grpc::StatusCode::INVALID_ARGUMENT,
                  {"options.corner_angle_deg must be in (0, 180]", "got -5"});
  expect_rejected(requests_for(tetrahedron_front(), header(0.5, 0.0, std::nan(""))),
                  grpc::StatusCode::INVALID_ARGUMENT, {"options.corner_angle_deg"});
}

TEST_F(MeshSurfaceServiceTest, RejectsNonPositiveSizeNamingTheField) {
  start(fixed_job(probe_, tetrahedron_front()));
  expect_rejected(tetrahedron_requests(0.0), grpc::StatusCode::INVALID_ARGUMENT,
                  {"options.size.max_size must be finite and > 0"});
}

TEST_F(MeshSurfaceServiceTest, RejectsSliceBeforeHeaderNamingTheMessage) {
  start(fixed_job(probe_, tetrahedron_front()));
  std::vector<Request> requests = tetrahedron_requests();
  std::swap(requests[0], requests[1]);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"message 1 is a points slice before the header"});
}

TEST_F(MeshSurfaceServiceTest, RejectsTriangleIndexOutOfRangeNamingTheTriangle) {
  start(fixed_job(probe_, tetrahedron_front()));
  Mesh input = tetrahedron_front();
  input.triangles[3][2] = 4;
  expect_rejected(requests_for(input, header(0.5)), grpc::StatusCode::INVALID_ARGUMENT,
                  {"triangle 3 refers to point 4 (corner 2)"});
}

TEST_F(MeshSurfaceServiceTest, RejectsNanCoordinateNamingThePoint) {
  start(fixed_job(probe_, tetrahedron_front()));
  Mesh input = tetrahedron_front();
  input.points[2][1] = std::nan("");
  expect_rejected(requests_for(input, header(0.5)), grpc::StatusCode::INVALID_ARGUMENT,
                  {"point 2"});
}

TEST_F(MeshSurfaceServiceTest, RejectsEmptyMessageAndSecondHeader) {
  start(fixed_job(probe_, tetrahedron_front()));
  std::vector<Request> requests = tetrahedron_requests();
  requests.insert(requests.begin() + 1, Request());
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT, {"message 2 is empty"});
  requests = tetrahedron_requests();
  requests.push_back(header(0.5));
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT, {"message 4 is a second header"});
}

TEST_F(MeshSurfaceServiceTest, RejectsPointCountDifferingFromTheHeader) {
  start(fixed_job(probe_, tetrahedron_front()));
  std::vector<Request> requests = tetrahedron_requests();
  requests[0].mutable_header()->set_point_count(5);
  expect_rejected(requests, grpc::StatusCode::INVALID_ARGUMENT,
                  {"the header declared 5 points but 4 were sent"});
}

// ---------------------------------------------------------------------------------------------
// Limits.

TEST_F(MeshSurfaceServiceTest, InputOverThePointLimitIsRefusedNamingTheFlag) {
  ServerOptions options;
  options.service.limits.max_points = 3;
  start(fixed_job(probe_, tetrahedron_front()), options);
  expect_rejected(tetrahedron_requests(), grpc::StatusCode::RESOURCE_EXHAUSTED,
                  {"--max-points"});
}

TEST_F(MeshSurfaceServiceTest, ASizeAskingForTooManyTrianglesIsRefusedWithItsEstimate) {
  ServerOptions options;
  options.service.limits.max_elements = 1000;
  start(fixed_job(probe_, tetrahedron_front()), options);
  // Area 2.366 over sqrt(3)/4 * 0.001^2: about 5.46e6 triangles at size 0.001.
  expect_rejected(tetrahedron_requests(0.001), grpc::StatusCode::RESOURCE_EXHAUSTED,
                  {"about 5.46e+06 surface triangles", "limit of 1000 (--max-elements)"});
}

TEST_F(MeshSurfaceServiceTest, AJobNeedingMoreThanTheWholeMemoryBudgetIsRefused) {
  ServerOptions options;
  options.service.memory_budget_bytes = 1 << 20;
  start(fixed_job(probe_, tetrahedron_front()), options);
  expect_rejected(tetrahedron_requests(0.01), grpc::StatusCode::RESOURCE_EXHAUSTED,
                  {"surface triangles", "--memory-budget-mb"});
}

// The estimate before meshing sees the size field only; the sizes attached to the surface
// (curvature, gaps) can ask for several times more (of_bullet: 40k estimated, 148k made). The core
// hands its own count to params.admit_expected, and the server admits the job again by it.
SurfaceJob job_whose_attached_sizes_ask_for(double triangles) {
  return [triangles](const Mesh&, const SurfaceParams& params,
                     Progress&) -> absl::StatusOr<SurfaceResult> {
    if (!params.admit_expected) return absl::InternalError("no admit_expected");
    if (absl::Status admitted = params.admit_expected(triangles); !admitted.ok()) return admitted;
    return result_with(tetrahedron_front());
  };
}

TEST_F(MeshSurfaceServiceTest, AJobWhoseAttachedSizesNeedMoreThanTheBudgetIsRefusedBeforeItsFront) {
  ServerOptions options;
  options.service.memory_budget_bytes = 1 << 20;
  start(job_whose_attached_sizes_ask_for(1e5), options);
  expect_rejected(tetrahedron_requests(0.5), grpc::StatusCode::RESOURCE_EXHAUSTED,
                  {"1e+05 surface triangles", "--memory-budget-mb"});
}

TEST_F(MeshSurfaceServiceTest, AJobWhoseAttachedSizesFitTheBudgetRuns) {
  ServerOptions options;
  options.service.memory_budget_bytes = 1 << 20;
  start(job_whose_attached_sizes_ask_for(100), options);
  const Outcome outcome = call(tetrahedron_requests(0.5));
  EXPECT_TRUE(outcome.status.ok()) << outcome.status.error_message();
}

TEST_F(MeshSurfaceServiceTest, EstimateFollowsTheSizeFieldOfASpec) {
  SurfaceParams uniform;
  uniform.size = 0.5;
  SurfaceParams graded = uniform;
  graded.spec = SizeSpec{};
  graded.spec->max_size = 0.5;
  graded.spec->sources.push_back(
      SizeSource{.points = {{0, 0, 0}}, .delta0 = 0.05, .r0 = 0.5, .r1 = 1.0,
                 .law = PowerLaw{.gamma = 1.0}});
  const Mesh input = tetrahedron_front();
  const absl::StatusOr<SurfaceEstimate> coarse = estimate_surface_mesh(input, uniform);
  const absl::StatusOr<SurfaceEstimate> fine = estimate_surface_mesh(input, graded);
  ASSERT_TRUE(coarse.ok() && fine.ok());
  EXPECT_GT(fine->triangles, 10 * coarse->triangles);
  EXPECT_GT(fine->bytes, coarse->bytes);
}

// ---------------------------------------------------------------------------------------------
// Cancellation.

TEST_F(MeshSurfaceServiceTest, CancellationReachesTheRunningJobWithin100ms) {
  start(slow_job(probe_));
  grpc::ClientContext context;
  auto stream = stub_->MeshSurface(&context);
  for (const Request& request : tetrahedron_requests()) ASSERT_TRUE(stream->Write(request));
  stream->WritesDone();
  ASSERT_EQ(probe_->started.get_future().wait_for(std::chrono::seconds(5)),
            std::future_status::ready);
  const Clock::time_point cancelled_at = Clock::now();
  context.TryCancel();
  std::future<Clock::time_point> stopped = probe_->stopped.get_future();
  ASSERT_EQ(stopped.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  EXPECT_LT(stopped.get() - cancelled_at, std::chrono::milliseconds(100));
  Response response;
  while (stream->Read(&response)) EXPECT_FALSE(carries_mesh(response));
  EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::CANCELLED);
}

// ---------------------------------------------------------------------------------------------
// MeshVolume with remesh_surface: both jobs in one call.

std::vector<v1::MeshVolumeRequest> remesh_requests(double ridge, double corner, bool remesh) {
  std::vector<v1::MeshVolumeRequest> requests = afmesh::testing::tetrahedron_requests(0.5);
  v1::VolumeOptions& options = *requests[0].mutable_header()->mutable_options();
  options.set_remesh_surface(remesh);
  options.set_ridge_angle_deg(ridge);
  options.set_corner_angle_deg(corner);
  return requests;
}

TEST_F(MeshSurfaceServiceTest, RemeshSurfaceMeshesTheNewSurfaceInTheSameCall) {
  Mesh surface = tetrahedron_front();
  surface.points[3] = {0, 0, 2};  // tells the new surface from the input
  start(fixed_job(probe_, surface));
  std::vector<v1::MeshVolumeResponse> responses;
  const Outcome outcome = call_volume(remesh_requests(35.0, 0.0, true), responses);
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  EXPECT_EQ(probe_->surface_runs.load(), 1);
  EXPECT_EQ(probe_->volume_runs.load(), 1);
  EXPECT_EQ(probe_->params.ridge_angle_deg, 35.0);
  EXPECT_EQ(probe_->params.corner_angle_deg, SurfaceParams{}.corner_angle_deg);
  EXPECT_EQ(probe_->params.size, 0.5);
  EXPECT_TRUE(same_bits(probe_->volume_front.points, surface.points));
  const v1::Summary& summary = responses.back().summary();
  EXPECT_TRUE(summary.surface_remeshed());
  EXPECT_EQ(summary.surface().triangle_count(), 4u);
  EXPECT_EQ(summary.surface().features().corners(), 4u);
  EXPECT_EQ(summary.surface().distance().hausdorff(), 0.125);
  EXPECT_GT(summary.surface().estimated_triangle_count(), 0.0);
  bool noted = false;
  for (const v1::MeshVolumeResponse& response : responses) {
    noted = noted || (response.has_warning() &&
                      response.warning().message().find("re-triangulated first") !=
                          std::string::npos);
  }
  EXPECT_TRUE(noted);
}

TEST_F(MeshSurfaceServiceTest, WithoutRemeshSurfaceTheSummarySaysTheBoundaryIsTheInput) {
  start(fixed_job(probe_, tetrahedron_front()));
  std::vector<v1::MeshVolumeResponse> responses;
  ASSERT_TRUE(call_volume(remesh_requests(0.0, 0.0, false), responses).status.ok());
  EXPECT_FALSE(responses.back().summary().surface_remeshed());
  EXPECT_FALSE(responses.back().summary().has_surface());
  EXPECT_EQ(probe_->surface_runs.load(), 0);
}

TEST_F(MeshSurfaceServiceTest, VolumeRejectsSurfaceAnglesWithoutRemeshSurface) {
  start(fixed_job(probe_, tetrahedron_front()));
  std::vector<v1::MeshVolumeResponse> responses;
  const Outcome outcome = call_volume(remesh_requests(40.0, 0.0, false), responses);
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(outcome.status.error_message(),
              HasSubstr("options.ridge_angle_deg is set, but options.remesh_surface is not"));
}

TEST_F(MeshSurfaceServiceTest, VolumeCarriesTheCurvatureAngleOnlyWithRemeshSurface) {
  start(fixed_job(probe_, tetrahedron_front()));
  std::vector<v1::MeshVolumeResponse> responses;
  std::vector<v1::MeshVolumeRequest> requests = remesh_requests(0.0, 0.0, true);
  requests[0].mutable_header()->mutable_options()->set_curvature_angle_deg(0.0);
  ASSERT_TRUE(call_volume(requests, responses).status.ok());
  EXPECT_EQ(probe_->params.curvature_angle_deg, 0.0);
  requests = remesh_requests(0.0, 0.0, false);
  requests[0].mutable_header()->mutable_options()->set_curvature_angle_deg(20.0);
  const Outcome outcome = call_volume(requests, responses);
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(outcome.status.error_message(),
              HasSubstr("options.curvature_angle_deg is set, but options.remesh_surface is not"));
  requests = remesh_requests(0.0, 0.0, false);
  requests[0].mutable_header()->mutable_options()->set_curvature_deviation(0.001);
  const Outcome deviation = call_volume(requests, responses);
  EXPECT_EQ(deviation.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(deviation.status.error_message(),
              HasSubstr("options.curvature_deviation is set, but options.remesh_surface is not"));
  requests = remesh_requests(0.0, 0.0, false);
  requests[0].mutable_header()->mutable_options()->set_wall_sizes(1.0);
  const Outcome walls = call_volume(requests, responses);
  EXPECT_EQ(walls.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(walls.status.error_message(),
              HasSubstr("options.wall_sizes is set, but options.remesh_surface is not"));
}

// A volume's front re-triangulated first bounds its thin walls unless told not to: unset is
// kVolumeFrontWallSizes (MeshSurface's own default stays none), 0 turns it off, a value reaches
// the job as it is, and a bad one is refused naming that default.
TEST_F(MeshSurfaceServiceTest, VolumeCarriesTheWallSizesWithRemeshSurface) {
  start(fixed_job(probe_, tetrahedron_front()));
  std::vector<v1::MeshVolumeResponse> responses;
  ASSERT_TRUE(call_volume(remesh_requests(0.0, 0.0, true), responses).status.ok());
  EXPECT_EQ(probe_->params.wall_sizes, kVolumeFrontWallSizes);
  EXPECT_EQ(kVolumeFrontWallSizes, 1.0);
  EXPECT_EQ(SurfaceParams{}.wall_sizes, 0.0);
  for (const double walls : {0.0, 2.5}) {
    std::vector<v1::MeshVolumeRequest> requests = remesh_requests(0.0, 0.0, true);
    requests[0].mutable_header()->mutable_options()->set_wall_sizes(walls);
    probe_->surface_runs.store(0);  // the probe keeps the first run's params
    ASSERT_TRUE(call_volume(requests, responses).status.ok());
    EXPECT_EQ(probe_->params.wall_sizes, walls);
  }
  std::vector<v1::MeshVolumeRequest> requests = remesh_requests(0.0, 0.0, true);
  requests[0].mutable_header()->mutable_options()->set_wall_sizes(-1.0);
  const Outcome outcome = call_volume(requests, responses);
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(outcome.status.error_message(),
              HasSubstr("options.wall_sizes must be in [0, 100) wall thicknesses (0: no wall "
                        "bound; unset: 1), got -1"));
}

TEST_F(MeshSurfaceServiceTest, VolumeCarriesTheCurvatureDeviationWithRemeshSurface) {
  start(fixed_job(probe_, tetrahedron_front()));
  std::vector<v1::MeshVolumeResponse> responses;
  std::vector<v1::MeshVolumeRequest> requests = remesh_requests(0.0, 0.0, true);
  requests[0].mutable_header()->mutable_options()->set_curvature_deviation(0.001);
  ASSERT_TRUE(call_volume(requests, responses).status.ok());
  EXPECT_EQ(probe_->params.curvature_deviation, 0.001);
  requests = remesh_requests(0.0, 0.0, true);
  requests[0].mutable_header()->mutable_options()->set_curvature_deviation(1.5);
  const Outcome outcome = call_volume(requests, responses);
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(outcome.status.error_message(),
              HasSubstr("options.curvature_deviation must be in [0, 1)"));
}

TEST_F(MeshSurfaceServiceTest, VolumeRejectsABadRidgeAngleWithRemeshSurface) {
  start(fixed_job(probe_, tetrahedron_front()));
  std::vector<v1::MeshVolumeResponse> responses;
  const Outcome outcome = call_volume(remesh_requests(200.0, 0.0, true), responses);
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(outcome.status.error_message(), HasSubstr("options.ridge_angle_deg"));
  EXPECT_EQ(probe_->volume_runs.load(), 0);
}

TEST_F(MeshSurfaceServiceTest, RemeshSurfaceOnAServerWithoutASurfaceJobIsUnimplemented) {
  start(SurfaceJob{});
  std::vector<v1::MeshVolumeResponse> responses;
  const Outcome outcome = call_volume(remesh_requests(0.0, 0.0, true), responses);
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::UNIMPLEMENTED);
  EXPECT_EQ(probe_->volume_runs.load(), 0);
}

}  // namespace
}  // namespace afmesh::server
