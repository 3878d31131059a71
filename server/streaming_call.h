// The skeleton every streaming Mesher call shares (house style, "A reactor per RPC, short"): one
// bidirectional reactor, parameterised by what an RPC supplies (a StreamingRpc: its messages, its
// input with its options and validation, its job, its result as response messages), so that a
// new RPC adds those and nothing else. Not in the paper.
//
// Life cycle of a call:
//   arrival     the bearer token (before anything is read: UNAUTHENTICATED), the call gate
//               (UNAVAILABLE while the server drains), a pool slot (RESOURCE_EXHAUSTED with a
//               retry hint when every worker and queue slot is taken);
//   reading     each message is counted for the call log and taken by the RPC's Input, whose
//               errors (malformed stream, limits) finish the call; a read pending longer than
//               --stall-timeout cancels it (stall_watch.h);
//   half-close  Input::finish() checks the whole input, then the job is queued on the pool
//               (a "queued" Progress event);
//   job         on a worker, with a JobContext: a Progress that streams throttled events and
//               turns cancelled() once the client cancels, the deadline passes or the drain
//               runs out of time, and the memory budget to reserve from;
//   job done    on success the RPC's Output streams, message by message; on failure the job's
//               status finishes the call with nothing of a result sent;
//   end         trailers wire::kFinalStatusKey always and wire::kRetryAfterKey on a refusal that
//               may succeed later, one call log line and the metrics (call_log.h).
// The call is finished only once its job has returned, since the job uses the call. The call is
// deleted when both gRPC (OnDone) and a running job have let go of it.
#pragma once

#include <atomic>
#include <chrono>
#include <concepts>
#include <cstdint>
#include <deque>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/common/stage_timing.h"
#include "grpcpp/grpcpp.h"
#include "server/call_auth.h"
#include "server/call_gate.h"
#include "server/call_log.h"
#include "server/memory_budget.h"
#include "server/stall_watch.h"
#include "server/worker_pool.h"

namespace afmesh::server {

// What the calls of one service share. Everything referred to must outlive every call.
struct CallResources {
  WorkerPool& pool;
  CallGate& gate;
  MemoryBudget& budget;
  ServerMetrics& metrics;
  StallWatch& stall_watch;
  bool log_calls = true;     // a call_log.h line on stderr per call
  std::string bearer_token;  // when set, calls must carry it (call_auth.h)
};

// What a call hands its job on the worker. Lives as long as the call.
class JobContext {
 public:
  JobContext(Progress& progress, MemoryBudget& budget, std::vector<StageTiming> timings_before)
      : progress_(progress), budget_(budget), timings_before_(std::move(timings_before)) {}

  // Streams throttled Progress events; cancelled() once the call is to stop. A job that sees
  // it may return any status: the call then ends with the stop's own (CANCELLED,
  // DEADLINE_EXCEEDED, or UNAVAILABLE when the drain ran out of time).
  Progress& progress() const { return progress_; }

  // The call's stages before the job ran: "receive" (the input's upload), "queue".
  const std::vector<StageTiming>& timings_before() const { return timings_before_; }

  // Reserves `bytes` of the server's memory budget until the call is gone (its result streamed
  // out). RESOURCE_EXHAUSTED when `bytes` is over the whole budget ("meshing this input needs
  // about 3.1 GiB (about <elements>), over this server's memory budget ..."), or, with a retry
  // hint, when the jobs running now hold too much of it. A second call replaces the first's
  // reservation.
  absl::Status reserve_memory(double bytes, std::string_view elements);

  // Admits a job by its estimate made before any meshing: RESOURCE_EXHAUSTED when `count`
  // `elements` (e.g. "tetrahedra") are over `max_elements` ("the size field asks for about
  // 5.46e+06 surface triangles (estimated before meshing from <basis>), over this server's
  // limit of 1000 (--max-elements); ask for larger elements, or split the <whole>"), else
  // reserve_memory(bytes).
  absl::Status admit_estimate(double count, std::string_view elements, std::string_view basis,
                              std::string_view whole, double bytes, std::int64_t max_elements);

 private:
  Progress& progress_;
  MemoryBudget& budget_;
  const std::vector<StageTiming> timings_before_;
  std::optional<MemoryBudget::Reservation> reservation_;
};

// What an RPC supplies to run as a StreamingCall (mesh_volume_rpc.h is one):
//   Request, Response   its messages; Response has a `progress` event (mesher.proto Progress);
//   kName               its name in logs and metrics ("MeshVolume");
//   make_input()        an Input: add(request) takes each client message, finish() checks the
//                       whole input at half-close (absl::Status: INVALID_ARGUMENT naming the
//                       message, element or field; RESOURCE_EXHAUSTED naming the limit);
//   count_request       counts a message into the call's CallRecord;
//   run(input, context) the job on a worker (const: runs for many calls at once), returning an
//                       Output, or the status the call ends with;
//   Output::next(r)     fills the next response message; false once the last one was produced;
//   count_output        counts what the Output carries into the CallRecord.
template <class Rpc>
concept StreamingRpc =
    requires(const Rpc& rpc, typename Rpc::Input& input, const typename Rpc::Request& request,
             typename Rpc::Response& response, typename Rpc::Output& output,
             const typename Rpc::Output& done, CallRecord& record, JobContext& context) {
      { Rpc::kName } -> std::convertible_to<const char*>;
      { rpc.make_input() } -> std::same_as<typename Rpc::Input>;
      { input.add(request) } -> std::same_as<absl::Status>;
      { input.finish() } -> std::same_as<absl::Status>;
      Rpc::count_request(request, record);
      { rpc.run(std::move(input), context) } -> std::same_as<absl::StatusOr<typename Rpc::Output>>;
      { output.next(response) } -> std::same_as<bool>;
      Rpc::count_output(done, record);
      response.mutable_progress()->set_stage(std::string());
    };

namespace call_detail {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start);
// absl and gRPC status codes share their numeric values (both are google.rpc.Code).
grpc::Status to_grpc(const absl::Status& status);
// The milliseconds to wait before sending a refused call again, when its status carries them.
std::optional<int> retry_after_ms(const absl::Status& status);
// UNAVAILABLE: the gate is closed (the server drains).
absl::Status gate_closed();
// RESOURCE_EXHAUSTED with a retry hint: every worker and queue slot of `pool` is taken.
absl::Status pool_full(const WorkerPool& pool);
// Why a call stopped: DEADLINE_EXCEEDED when its deadline has passed, UNAVAILABLE when the
// server stopped it at the end of its drain (`aborting`, the client did not cancel), else
// CANCELLED.
absl::Status stopped(bool deadline_passed, bool aborting, bool client_cancelled);
// RESOURCE_EXHAUSTED: the server ran out of memory taking the input.
absl::Status out_of_memory_receiving();
// The trailers every finished call carries (see the life cycle above).
void add_final_trailers(grpc::CallbackServerContext& context, std::optional<int> retry_after_ms);

}  // namespace call_detail

template <StreamingRpc Rpc>
class StreamingCall final
    : public grpc::ServerBidiReactor<typename Rpc::Request, typename Rpc::Response> {
  using Request = typename Rpc::Request;
  using Response = typename Rpc::Response;
  using Input = typename Rpc::Input;
  using Output = typename Rpc::Output;
  using Clock = call_detail::Clock;

 public:
  StreamingCall(grpc::CallbackServerContext* context, const Rpc& rpc,
                const CallResources& resources)
      : context_(context),
        rpc_(rpc),
        resources_(resources),
        input_(rpc.make_input()),
        progress_(*this),
        deadline_(context->deadline()),
        receive_start_(Clock::now()) {
    admitted_ = resources_.gate.try_enter();
    if (!admitted_) {
      finish_with(call_detail::gate_closed());
      return;
    }
    slot_ = resources_.pool.try_reserve();
    if (!slot_) {
      finish_with(call_detail::pool_full(resources_.pool));
      return;
    }
    start_read();
  }

  ~StreamingCall() override {
    if (admitted_) resources_.gate.leave();
  }

  void OnReadDone(bool ok) override {
    resources_.stall_watch.ended(context_, StallWatch::Transfer::kRead);
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (finished_) return;
      if (ok) Rpc::count_request(request_, record_);
    }
    if (!ok) {
      end_of_input();
      return;
    }
    if (absl::Status status = add_input(); !status.ok()) {
      finish_with(status);
      return;
    }
    start_read();
  }

  void OnWriteDone(bool ok) override {
    resources_.stall_watch.ended(context_, StallWatch::Transfer::kWrite);
    {
      std::lock_guard<std::mutex> lock(mu_);
      writing_ = false;
      if (!ok) {
        // The stream is broken (the call was cancelled): nothing more can be sent.
        cancel_requested_.store(true, std::memory_order_release);
        outbox_.clear();
        output_.reset();
        if (job_state_ != JobState::kRunning) final_status_ = call_detail::to_grpc(stop_status());
      }
    }
    pump();
  }

  void OnCancel() override {
    cancel_requested_.store(true, std::memory_order_release);
    {
      std::lock_guard<std::mutex> lock(mu_);
      // A running job notices through progress_ and finishes the call when it returns.
      if (job_state_ == JobState::kRunning) return;
      output_.reset();
      outbox_.clear();
      final_status_ = call_detail::to_grpc(stop_status());
    }
    pump();
  }

  void OnDone() override { release(); }

 private:
  enum class JobState { kNotStarted, kRunning, kDone };

  // Least time between two Progress events of the same stage.
  static constexpr auto kProgressInterval = std::chrono::milliseconds(100);

  // The Progress the job sees.
  class CallProgress final : public Progress {
   public:
    explicit CallProgress(StreamingCall& call) : call_(call) {}
    void report(std::string_view stage, double fraction) override {
      call_.post_progress(stage, fraction);
    }
    bool cancelled() const override { return call_.stop_requested(); }

   private:
    StreamingCall& call_;
  };

  // True once the client cancelled, the deadline passed or the server's drain ran out of time.
  bool stop_requested() const {
    return cancel_requested_.load(std::memory_order_acquire) ||
           std::chrono::system_clock::now() >= deadline_ || resources_.gate.aborting();
  }

  absl::Status stop_status() const {
    return call_detail::stopped(std::chrono::system_clock::now() >= deadline_,
                                resources_.gate.aborting(),
                                cancel_requested_.load(std::memory_order_acquire));
  }

  // Queues a Progress event: always on a new stage, else at most every kProgressInterval
  // (and on completion); an unsent event of the same stage is replaced by the newer one.
  void post_progress(std::string_view stage, double fraction) {
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (finished_) return;
      const Clock::time_point now = Clock::now();
      const bool new_stage = stage != last_stage_;
      if (!new_stage && fraction < 1.0 && now - last_progress_ < kProgressInterval) return;
      last_stage_ = std::string(stage);
      last_progress_ = now;
      const bool replace = !new_stage && !outbox_.empty() && outbox_.back().has_progress();
      Response& event = replace ? outbox_.back() : outbox_.emplace_back();
      event.mutable_progress()->set_stage(std::string(stage));
      event.mutable_progress()->set_fraction(fraction);
    }
    pump();
  }

  absl::Status add_input() {
    try {
      return input_.add(request_);
    } catch (const std::bad_alloc&) {
      return call_detail::out_of_memory_receiving();
    }
  }

  // Half-close (or a read failing because the call was cancelled): check the whole input and
  // queue the job.
  void end_of_input() {
    if (context_->IsCancelled()) {
      finish_with(absl::CancelledError("the call was cancelled while sending its input"));
      return;
    }
    receive_seconds_ = call_detail::seconds_since(receive_start_);
    if (absl::Status status = input_.finish(); !status.ok()) {
      finish_with(status);
      return;
    }
    start_job();
  }

  void start_job() {
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (final_status_) return;  // cancelled meanwhile
      job_state_ = JobState::kRunning;
      // The job's reference. Taken inside a reaction, so before OnDone can run.
      references_.fetch_add(1, std::memory_order_relaxed);
    }
    post_progress("queued", 0.0);
    WorkerPool::Slot slot = std::move(*slot_);
    slot_.reset();
    resources_.pool.run(std::move(slot), [this, input = std::move(input_),
                                          queued_at = Clock::now()]() mutable {
      job_start_ = Clock::now();
      run_job(std::move(input), queued_at);
      release();
    });
  }

  // On a worker thread.
  void run_job(Input input, Clock::time_point queued_at) {
    JobContext& context = job_context_.emplace(
        progress_, resources_.budget,
        std::vector<StageTiming>{{"receive", receive_seconds_},
                                 {"queue", call_detail::seconds_since(queued_at)}});
    complete_job(stop_requested() ? absl::StatusOr<Output>(stop_status())
                                  : rpc_.run(std::move(input), context));
  }

  // Records the job's outcome: its result streams unless the call was stopped meanwhile.
  void complete_job(absl::StatusOr<Output> output) {
    {
      std::lock_guard<std::mutex> lock(mu_);
      job_state_ = JobState::kDone;
      record_.job_seconds = call_detail::seconds_since(job_start_);
      if (!output.ok()) {
        if (const std::optional<int> ms = call_detail::retry_after_ms(output.status())) {
          retry_after_ms_ = ms;
        }
      }
      if (stop_requested()) {
        final_status_ = call_detail::to_grpc(stop_status());
      } else if (output.ok()) {
        Rpc::count_output(*output, record_);
        output_.emplace(*std::move(output));
        final_status_ = grpc::Status::OK;
      } else {
        final_status_ = call_detail::to_grpc(output.status());
      }
    }
    pump();
  }

  // Finishes the call with `status` (an error before any job ran), with its retry hint if any.
  void finish_with(const absl::Status& status) {
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (final_status_) return;
      final_status_ = call_detail::to_grpc(status);
      if (const std::optional<int> ms = call_detail::retry_after_ms(status)) retry_after_ms_ = ms;
    }
    pump();
  }

  // Starts the next write (queued events first, then the result), or finishes the call once
  // everything is written and its final status is known. At most one write is in flight.
  void pump() {
    std::unique_lock<std::mutex> lock(mu_);
    if (writing_ || finished_) return;
    if (!outbox_.empty()) {
      current_ = std::move(outbox_.front());
      outbox_.pop_front();
    } else if (output_.has_value() && output_->next(current_)) {
      // current_ holds the next result message
    } else if (final_status_ && job_state_ != JobState::kRunning) {
      finished_ = true;
      const grpc::Status status = *final_status_;
      CallRecord record = record_;
      const std::optional<int> retry_after_ms = status.ok() ? std::nullopt : retry_after_ms_;
      lock.unlock();
      call_detail::add_final_trailers(*context_, retry_after_ms);
      record.retry_after_ms = retry_after_ms;
      report_finish(status, std::move(record));
      this->Finish(status);
      return;
    } else {
      return;
    }
    writing_ = true;
    record_.bytes_out += static_cast<std::int64_t>(current_.ByteSizeLong());
    lock.unlock();
    resources_.stall_watch.started(context_, StallWatch::Transfer::kWrite);
    this->StartWrite(&current_);
  }

  // The call's end, to its log line and the metrics (call_log.h).
  void report_finish(const grpc::Status& status, CallRecord record) const {
    record.rpc = Rpc::kName;
    record.peer = context_->peer();
    record.seconds = call_detail::seconds_since(receive_start_);
    record.status = status;
    report_call_end(std::move(record), resources_.log_calls, resources_.metrics);
  }

  // Drops one reference (gRPC's at OnDone, the job's when it returns); the last one deletes.
  void release() {
    if (references_.fetch_sub(1, std::memory_order_acq_rel) == 1) delete this;
  }

  void start_read() {
    resources_.stall_watch.started(context_, StallWatch::Transfer::kRead);
    this->StartRead(&request_);
  }

  grpc::CallbackServerContext* const context_;
  const Rpc& rpc_;
  const CallResources& resources_;
  bool admitted_ = false;  // passed the gate: counted until this object is deleted
  Input input_;            // touched by reads only, one at a time, then moved to the job
  Request request_;        // the read in flight
  std::optional<WorkerPool::Slot> slot_;
  CallProgress progress_;
  std::optional<JobContext> job_context_;  // made by the job; holds its memory reservation
  const std::chrono::system_clock::time_point deadline_;
  const Clock::time_point receive_start_;
  double receive_seconds_ = 0.0;  // written before the job is queued, read by the job
  Clock::time_point job_start_;   // written and read by the job
  std::atomic<bool> cancel_requested_{false};
  std::atomic<int> references_{1};  // gRPC's, plus the job's while it is queued or running

  std::mutex mu_;
  JobState job_state_ ABSL_GUARDED_BY(mu_) = JobState::kNotStarted;
  std::deque<Response> outbox_ ABSL_GUARDED_BY(mu_);  // events waiting to be written
  std::optional<Output> output_ ABSL_GUARDED_BY(mu_);
  std::optional<grpc::Status> final_status_ ABSL_GUARDED_BY(mu_);
  CallRecord record_ ABSL_GUARDED_BY(mu_);  // input counts as read, output counts once done
  std::optional<int> retry_after_ms_ ABSL_GUARDED_BY(mu_);  // sent with a failed final status
  bool writing_ ABSL_GUARDED_BY(mu_) = false;
  bool finished_ ABSL_GUARDED_BY(mu_) = false;
  Response current_;  // the write in flight; only touched while writing_ is false
  std::string last_stage_ ABSL_GUARDED_BY(mu_);
  Clock::time_point last_progress_ ABSL_GUARDED_BY(mu_);
};

// For an RPC's handler: the call's reactor, or one that refuses it at once when it lacks the
// bearer token (call_auth.h).
template <StreamingRpc Rpc>
grpc::ServerBidiReactor<typename Rpc::Request, typename Rpc::Response>* start_streaming_call(
    grpc::CallbackServerContext* context, const Rpc& rpc, const CallResources& resources) {
  if (auto* refused = refuse_unauthenticated<typename Rpc::Request, typename Rpc::Response>(
          Rpc::kName, context, resources.bearer_token, resources.log_calls,
          resources.metrics)) {
    return refused;
  }
  return new StreamingCall<Rpc>(context, rpc, resources);
}

}  // namespace afmesh::server
