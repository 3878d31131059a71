// Which failed MeshVolume calls the CLI sends again (client/volume_call.h, worth_retrying):
// a status the service finished the call with carries wire::kFinalStatusKey, and is retried only
// when the service said so; a status made on the way (a balancer whose replica was killed
// mid-call answers INTERNAL or UNKNOWN) is retried against a shared server.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "afmesh/v1/mesher.grpc.pb.h"
#include "client/volume_call.h"
#include "grpc/grpc.h"
#include "grpcpp/generic/async_generic_service.h"
#include "grpcpp/grpcpp.h"
#include "server/server.h"
#include "tests/server/request_support.h"

namespace afmesh::cli {
namespace {

using afmesh::testing::tetrahedron_front;

absl::Status call(const std::string& address) {
  VolumeCallOptions options;
  options.size = 1.0;
  return call_mesh_volume(address, tetrahedron_front(), options, [](std::string_view, double) {},
                          [](std::string_view) {})
      .status();
}

// Answers every call with `status` at once, as nginx does for a replica that died mid-call.
class StandInProxy final : public grpc::CallbackGenericService {
 public:
  explicit StandInProxy(grpc::Status status) : status_(std::move(status)) {}
  grpc::ServerGenericBidiReactor* CreateReactor(grpc::GenericCallbackServerContext*) override {
    class Reactor final : public grpc::ServerGenericBidiReactor {
     public:
      explicit Reactor(const grpc::Status& status) { Finish(status); }
      void OnDone() override { delete this; }
    };
    return new Reactor(status_);
  }

 private:
  const grpc::Status status_;
};

class VolumeCallRetryTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    static const bool initialised = (grpc_init(), true);
    (void)initialised;
  }

  // Serves `proxy` on a port picked by the system; returns its address.
  std::string serve(StandInProxy& proxy) {
    grpc::ServerBuilder builder;
    int port = 0;
    builder.AddListeningPort("127.0.0.1:0", grpc::InsecureServerCredentials(), &port);
    builder.RegisterCallbackGenericService(&proxy);
    proxy_server_ = builder.BuildAndStart();
    return "127.0.0.1:" + std::to_string(port);
  }

  void TearDown() override {
    if (proxy_server_ != nullptr) proxy_server_->Shutdown();
  }

  std::unique_ptr<grpc::Server> proxy_server_;
};

TEST_F(VolumeCallRetryTest, AStreamResetByAProxyIsRetriedAgainstASharedServer) {
  for (const grpc::Status& cut :
       {grpc::Status(grpc::StatusCode::INTERNAL, "Received RST_STREAM with error code 2"),
        grpc::Status(grpc::StatusCode::UNKNOWN, "Stream removed")}) {
    StandInProxy proxy(cut);
    const absl::Status status = call(serve(proxy));
    EXPECT_EQ(static_cast<int>(status.code()), static_cast<int>(cut.error_code()));
    EXPECT_TRUE(cut_on_the_way(status)) << status;
    EXPECT_TRUE(worth_retrying(status, /*shared_server=*/true)) << status;
    EXPECT_FALSE(worth_retrying(status, /*shared_server=*/false)) << status;
    proxy_server_->Shutdown();
    proxy_server_.reset();
  }
}

TEST_F(VolumeCallRetryTest, FinalAnswersOnTheWayAreNotRetried) {
  for (grpc::StatusCode code : {grpc::StatusCode::INVALID_ARGUMENT, grpc::StatusCode::CANCELLED,
                                grpc::StatusCode::FAILED_PRECONDITION}) {
    StandInProxy proxy(grpc::Status(code, "no"));
    const absl::Status status = call(serve(proxy));
    EXPECT_FALSE(worth_retrying(status, true)) << status;
    proxy_server_->Shutdown();
    proxy_server_.reset();
  }
}

TEST_F(VolumeCallRetryTest, AnInternalErrorTheServiceSentIsNotRetried) {
  server::ServerOptions options;
  options.listen = "127.0.0.1:0";
  options.workers = 1;
  options.service.log_calls = false;
  absl::StatusOr<std::unique_ptr<server::MesherServer>> server = server::MesherServer::start(
      options, [](const Mesh&, const VolumeParams&, Progress&)
                   -> absl::StatusOr<server::VolumeJobOutput> {
        return absl::InternalError("the volume mesh failed validation");
      });
  ASSERT_TRUE(server.ok()) << server.status();
  const absl::Status status = call((*server)->address());
  EXPECT_EQ(status.code(), absl::StatusCode::kInternal) << status;
  EXPECT_FALSE(cut_on_the_way(status));
  EXPECT_FALSE(worth_retrying(status, true));
  (*server)->shutdown();
}

// Answers every MeshVolume call with `responses` and OK, whatever it is sent.
class ScriptedMesher final : public v1::Mesher::CallbackService {
 public:
  explicit ScriptedMesher(std::vector<v1::MeshVolumeResponse> responses)
      : responses_(std::move(responses)) {}
  grpc::ServerBidiReactor<v1::MeshVolumeRequest, v1::MeshVolumeResponse>* MeshVolume(
      grpc::CallbackServerContext*) override {
    class Reactor final
        : public grpc::ServerBidiReactor<v1::MeshVolumeRequest, v1::MeshVolumeResponse> {
     public:
      explicit Reactor(const std::vector<v1::MeshVolumeResponse>& responses)
          : responses_(responses) {
        OnWriteDone(true);
      }
      void OnWriteDone(bool ok) override {
        if (ok && next_ < responses_.size()) {
          StartWrite(&responses_[next_++]);
        } else {
          Finish(grpc::Status::OK);
        }
      }
      void OnDone() override { delete this; }

     private:
      const std::vector<v1::MeshVolumeResponse>& responses_;
      std::size_t next_ = 0;
    };
    return new Reactor(responses_);
  }

 private:
  const std::vector<v1::MeshVolumeResponse> responses_;
};

// The CLI decodes the server's slices with the checks the server applies to its input: a slice
// whose length is not a whole number of items is refused, not cut short.
TEST(VolumeCall, AMalformedSliceFromTheServerIsDataLossNamingIt) {
  std::vector<v1::MeshVolumeResponse> responses(2);
  for (const double c : {0.0, 1.0, 2.0, 3.0}) responses[0].mutable_points()->add_xyz(c);
  responses[1].mutable_summary()->set_point_count(1);
  ScriptedMesher mesher(responses);
  grpc::ServerBuilder builder;
  int port = 0;
  builder.AddListeningPort("127.0.0.1:0", grpc::InsecureServerCredentials(), &port);
  builder.RegisterService(&mesher);
  const std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  ASSERT_NE(server, nullptr);
  const absl::Status status = call("127.0.0.1:" + std::to_string(port));
  EXPECT_EQ(status.code(), absl::StatusCode::kDataLoss) << status;
  EXPECT_EQ(status.message(),
            "the server's answer is malformed: message 1: points slice has 4 coordinates, not a "
            "multiple of 3");
  server->Shutdown();
}

TEST_F(VolumeCallRetryTest, AnUnreachableSharedServerIsRetried) {
  const absl::Status status = call("unix:/nonexistent/afmesh.sock");
  EXPECT_EQ(status.code(), absl::StatusCode::kUnavailable) << status;
  EXPECT_TRUE(worth_retrying(status, true));
  EXPECT_FALSE(worth_retrying(status, false));
}

// call_mesh_surface against the service in-process with a fake surface job: the surface comes
// back whole with its tags, the summary as plain values and JSON, and the angles reach the job;
// call_mesh_volume's remesh_surface runs the surface job first.
class SurfaceCallTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    static const bool initialised = (grpc_init(), true);
    (void)initialised;
  }

  void SetUp() override {
    server::ServerOptions options;
    options.listen = "127.0.0.1:0";
    options.workers = 1;
    options.service.log_calls = false;
    absl::StatusOr<std::unique_ptr<server::MesherServer>> server = server::MesherServer::start(
        options,
        [](const Mesh& front, const VolumeParams&,
           Progress&) -> absl::StatusOr<server::VolumeJobOutput> {
          server::VolumeJobOutput output;
          output.volume.mesh = front;
          output.volume.mesh.tets = {{0, 1, 2, 3}};
          output.volume.mesh.tet_tags = {0};
          output.validation.passed = true;
          return output;
        },
        [this](const Mesh& input, const SurfaceParams& params,
               Progress&) -> absl::StatusOr<SurfaceResult> {
          seen_ = params;
          SurfaceResult result;
          result.mesh = input;
          result.report.corners = 4;
          result.report.hausdorff = 0.5;
          return result;
        });
    ASSERT_TRUE(server.ok()) << server.status();
    server_ = *std::move(server);
  }

  void TearDown() override { server_->shutdown(); }

  std::unique_ptr<server::MesherServer> server_;
  SurfaceParams seen_;
};

TEST_F(SurfaceCallTest, TheSurfaceComesBackWholeWithTagsAndItsSummary) {
  VolumeCallOptions options;
  options.size = 0.5;
  options.ridge_angle_deg = 42.0;
  options.corner_angle_deg = 99.0;
  options.curvature_angle_deg = 0.0;  // set: the bound off
  absl::StatusOr<SurfaceCallResult> result =
      call_mesh_surface(server_->address(), tetrahedron_front(), options,
                        [](std::string_view, double) {}, [](std::string_view) {});
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(result->mesh.triangles, tetrahedron_front().triangles);
  EXPECT_EQ(result->mesh.triangle_tags, tetrahedron_front().triangle_tags);
  EXPECT_TRUE(result->mesh.tets.empty());
  EXPECT_EQ(result->summary.triangle_count, 4u);
  EXPECT_EQ(result->summary.corners, 4u);
  EXPECT_EQ(result->summary.hausdorff, 0.5);
  EXPECT_NEAR(result->summary.min_angle_deg, 45.0, 1e-9);
  EXPECT_NE(result->summary.json.find("\"hausdorff\": 0.5"), std::string::npos)
      << result->summary.json;
  EXPECT_EQ(seen_.ridge_angle_deg, 42.0);
  EXPECT_EQ(seen_.corner_angle_deg, 99.0);
  EXPECT_EQ(seen_.curvature_angle_deg, 0.0);
  EXPECT_EQ(seen_.size, 0.5);
}

TEST_F(SurfaceCallTest, RemeshSurfaceRunsTheSurfaceJobInTheVolumeCall) {
  VolumeCallOptions options;
  options.size = 0.5;
  options.remesh_surface = true;
  options.ridge_angle_deg = 33.0;
  absl::StatusOr<VolumeCallResult> result =
      call_mesh_volume(server_->address(), tetrahedron_front(), options,
                       [](std::string_view, double) {}, [](std::string_view) {});
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_TRUE(result->summary.surface_remeshed);
  EXPECT_EQ(seen_.ridge_angle_deg, 33.0);
  EXPECT_NE(result->summary.json.find("\"surfaceRemeshed\": true"), std::string::npos);
}

}  // namespace
}  // namespace afmesh::cli
