// The streaming-call skeleton (server/streaming_call.h) with an RPC part of the test's own, not
// MeshVolume's: what a new RPC supplies (input, job, output) is all it takes to get admission,
// progress, streaming, the memory budget, trailers and the call's record.
#include "server/streaming_call.h"

#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "afmesh/v1/mesher.grpc.pb.h"
#include "gmock/gmock.h"
#include "grpc/grpc.h"
#include "grpcpp/grpcpp.h"
#include "gtest/gtest.h"
#include "proto/call_metadata.h"
#include "server/metrics.h"

namespace afmesh::server {
namespace {

using ::testing::ElementsAre;
using Request = v1::MeshVolumeRequest;
using Response = v1::MeshVolumeResponse;

// Counts the points it is sent (a header first), then answers with a warning and a Summary
// holding the count, after reserving `bytes` of the memory budget.
struct CountingRpc {
  using Request = v1::MeshVolumeRequest;
  using Response = v1::MeshVolumeResponse;
  static constexpr char kName[] = "Counting";

  struct Input {
    absl::Status add(const Request& request) {
      if (request.has_header()) {
        has_header = true;
        return absl::OkStatus();
      }
      if (!has_header) return absl::InvalidArgumentError("send the header first");
      points += request.points().xyz_size() / 3;
      return absl::OkStatus();
    }
    absl::Status finish() const { return absl::OkStatus(); }
    bool has_header = false;
    int points = 0;
  };

  struct Output {
    bool next(Response& response) {
      response.Clear();
      if (sent == 0) response.mutable_warning()->set_message("counted");
      if (sent == 1) response.mutable_summary()->set_point_count(points);
      return sent++ < 2;
    }
    int points = 0;
    int sent = 0;
  };

  Input make_input() const { return {}; }
  static void count_request(const Request& request, CallRecord& record) {
    server::count_request(request, record);
  }
  static void count_output(const Output& output, CallRecord& record) {
    record.points_out = output.points;
  }
  absl::StatusOr<Output> run(Input input, JobContext& context) const {
    runs->fetch_add(1);
    context.progress().report("counting", 1.0);
    if (absl::Status status = context.reserve_memory(bytes, "a few points"); !status.ok()) {
      return status;
    }
    return Output{.points = input.points};
  }

  double bytes = 0.0;
  std::atomic<int>* runs = nullptr;
};

// The Mesher service with MeshVolume answered by CountingRpc.
class CountingService final : public v1::Mesher::CallbackService {
 public:
  CountingService(const CountingRpc& rpc, const CallResources& resources)
      : rpc_(rpc), resources_(resources) {}
  grpc::ServerBidiReactor<Request, Response>* MeshVolume(
      grpc::CallbackServerContext* context) override {
    return start_streaming_call(context, rpc_, resources_);
  }

 private:
  const CountingRpc& rpc_;
  const CallResources& resources_;
};

struct Outcome {
  grpc::Status status;
  std::vector<Response> responses;
  std::multimap<std::string, std::string> trailers;
};

class StreamingCallTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    static const bool initialised = (grpc_init(), true);
    (void)initialised;
  }

  void SetUp() override {
    rpc_.runs = &runs_;
    grpc::ServerBuilder builder;
    int port = 0;
    builder.AddListeningPort("127.0.0.1:0", grpc::InsecureServerCredentials(), &port);
    builder.RegisterService(&service_);
    server_ = builder.BuildAndStart();
    ASSERT_NE(server_, nullptr);
    stub_ = v1::Mesher::NewStub(grpc::CreateChannel("127.0.0.1:" + std::to_string(port),
                                                    grpc::InsecureChannelCredentials()));
  }

  void TearDown() override { server_->Shutdown(); }

  Outcome call(const std::vector<Request>& requests) {
    grpc::ClientContext context;
    const std::unique_ptr<grpc::ClientReaderWriter<Request, Response>> stream =
        stub_->MeshVolume(&context);
    for (const Request& request : requests) stream->Write(request);
    stream->WritesDone();
    Outcome outcome;
    Response response;
    while (stream->Read(&response)) outcome.responses.push_back(response);
    outcome.status = stream->Finish();
    for (const auto& [key, value] : context.GetServerTrailingMetadata()) {
      outcome.trailers.emplace(std::string(key.data(), key.size()),
                               std::string(value.data(), value.size()));
    }
    return outcome;
  }

  static std::vector<Request> header_and_points(int points) {
    std::vector<Request> requests(2);
    requests[0].mutable_header();
    for (int i = 0; i < 3 * points; ++i) requests[1].mutable_points()->add_xyz(i);
    return requests;
  }

  CallGate gate_;
  WorkerPool pool_{1, 1};
  MemoryBudget budget_{1000};
  ServerMetrics metrics_{gate_, pool_, budget_};
  StallWatch stall_watch_{std::chrono::seconds(60)};
  CallResources resources_{.pool = pool_,
                           .gate = gate_,
                           .budget = budget_,
                           .metrics = metrics_,
                           .stall_watch = stall_watch_,
                           .log_calls = false,
                           .bearer_token = {}};
  std::atomic<int> runs_{0};
  CountingRpc rpc_;
  CountingService service_{rpc_, resources_};
  std::unique_ptr<grpc::Server> server_;
  std::unique_ptr<v1::Mesher::Stub> stub_;
};

std::vector<std::string> events(const std::vector<Response>& responses) {
  std::vector<std::string> names;
  for (const Response& response : responses) {
    if (response.has_progress()) names.push_back("progress " + response.progress().stage());
    if (response.has_warning()) names.push_back("warning " + response.warning().message());
    if (response.has_summary()) {
      names.push_back("summary " + std::to_string(response.summary().point_count()));
    }
  }
  return names;
}

TEST_F(StreamingCallTest, AnRpcOfItsOwnGetsProgressItsOutputAndTheFinalStatusTrailer) {
  const Outcome outcome = call(header_and_points(5));
  ASSERT_TRUE(outcome.status.ok()) << outcome.status.error_message();
  EXPECT_THAT(events(outcome.responses), ElementsAre("progress queued", "progress counting",
                                                     "warning counted", "summary 5"));
  EXPECT_EQ(outcome.trailers.count(wire::kFinalStatusKey), 1u);
  EXPECT_EQ(outcome.trailers.count(wire::kRetryAfterKey), 0u);
  EXPECT_EQ(runs_.load(), 1);
}

TEST_F(StreamingCallTest, AnInputErrorEndsTheCallBeforeAnyJob) {
  std::vector<Request> requests = header_and_points(2);
  std::swap(requests[0], requests[1]);
  const Outcome outcome = call(requests);
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(outcome.status.error_message(), "send the header first");
  EXPECT_TRUE(outcome.responses.empty());
  EXPECT_EQ(outcome.trailers.count(wire::kFinalStatusKey), 1u);
  EXPECT_EQ(runs_.load(), 0);
}

TEST_F(StreamingCallTest, AJobRefusedByAHeldMemoryBudgetTellsTheClientWhenToRetry) {
  rpc_.bytes = 600;
  std::optional<MemoryBudget::Reservation> held = budget_.try_reserve(500);
  ASSERT_TRUE(held.has_value());
  const Outcome outcome = call(header_and_points(1));
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_THAT(outcome.status.error_message(), ::testing::HasSubstr("retry later"));
  const auto hint = outcome.trailers.find(wire::kRetryAfterKey);
  ASSERT_NE(hint, outcome.trailers.end());
  EXPECT_EQ(hint->second, "2000");
  EXPECT_EQ(outcome.trailers.count(wire::kFinalStatusKey), 1u);
}

TEST_F(StreamingCallTest, AJobOverTheWholeBudgetIsRefusedWithoutARetryHint) {
  rpc_.bytes = 2000;
  const Outcome outcome = call(header_and_points(1));
  EXPECT_EQ(outcome.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_THAT(outcome.status.error_message(), ::testing::HasSubstr("(about a few points)"));
  EXPECT_EQ(outcome.trailers.count(wire::kRetryAfterKey), 0u);
}

TEST_F(StreamingCallTest, TheBudgetIsGivenBackOnceTheCallIsGone) {
  rpc_.bytes = 600;
  ASSERT_TRUE(call(header_and_points(1)).status.ok());
  // The call is deleted once gRPC and its job have let go of it, just after its end.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (budget_.in_use() != 0 && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_EQ(budget_.in_use(), 0);
}

}  // namespace
}  // namespace afmesh::server
