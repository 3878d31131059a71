#include "server/mesher_service.h"

#include <atomic>
#include <chrono>
#include <deque>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "afmesh/v1/mesher.grpc.pb.h"
#include "grpcpp/grpcpp.h"
#include "core/volume/estimate_elements.h"
#include "core/volume/repair_front.h"
#include "proto/call_metadata.h"
#include "server/call_auth.h"
#include "server/call_log.h"
#include "server/stall_watch.h"
#include "server/volume_environments.h"
#include "server/volume_output.h"

namespace afmesh::server {
namespace {

using Clock = std::chrono::steady_clock;
using Request = v1::MeshVolumeRequest;
using Response = v1::MeshVolumeResponse;

// Least time between two Progress events of the same stage.
constexpr auto kProgressInterval = std::chrono::milliseconds(100);

// Backpressure (issue 12, part 2): a refusal that may succeed later carries the trailing
// metadata wire::kRetryAfterKey (proto/call_metadata.h), the milliseconds to wait first.
// Refusals that cannot succeed later (input or estimate over a limit) carry none.
using wire::kRetryAfterKey;
constexpr int kRetryAfterBusyMs = 1000;    // all workers and queue slots taken
constexpr int kRetryAfterBudgetMs = 2000;  // the memory budget held by running jobs

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// absl and gRPC status codes share their numeric values (both are google.rpc.Code).
grpc::Status to_grpc(const absl::Status& status) {
  return grpc::Status(static_cast<grpc::StatusCode>(status.code()), std::string(status.message()));
}

// Runs `job`, turning exceptions into statuses: the server never dies on a request.
absl::StatusOr<VolumeJobOutput> run_guarded(const VolumeJob& job, const Mesh& front,
                                            const VolumeParams& params, Progress& progress) {
  try {
    return job(front, params, progress);
  } catch (const std::bad_alloc&) {
    return absl::ResourceExhaustedError("the server ran out of memory meshing this input");
  } catch (const std::exception& e) {
    return absl::InternalError(absl::StrCat("the mesher failed: ", e.what()));
  }
}

class MeshVolumeCall;

// The Progress a job sees: cancelled() once the call is cancelled or past its deadline;
// report() streams throttled Progress events.
class CallProgress final : public Progress {
 public:
  explicit CallProgress(MeshVolumeCall& call) : call_(call) {}
  void report(std::string_view stage, double fraction) override;
  bool cancelled() const override;

 private:
  MeshVolumeCall& call_;
};

// One MeshVolume call. Life cycle:
//   arrival   reserve a pool slot, or finish RESOURCE_EXHAUSTED at once;
//   reading   each message goes through VolumeInput; an error finishes the call;
//   half-close  final input checks, then the job is queued on the pool;
//   job done  on success the result streams (VolumeOutputStream), the Summary last;
//             on failure the job's status finishes the call, with no mesh slice sent.
// The call is finished only once its job has returned, since the job uses this object. The
// object is deleted when both gRPC (OnDone) and a running job have let go of it.
class MeshVolumeCall final : public grpc::ServerBidiReactor<Request, Response> {
 public:
  MeshVolumeCall(grpc::CallbackServerContext* context, WorkerPool& pool, CallGate& gate,
                 MemoryBudget& budget, ServerMetrics& metrics, StallWatch& stall_watch,
                 const VolumeJob& job, const ServiceOptions& options)
      : context_(context),
        stall_watch_(stall_watch),
        pool_(pool),
        gate_(gate),
        budget_(budget),
        max_elements_(options.limits.max_elements),
        job_(job),
        log_calls_(options.log_calls),
        metrics_(metrics),
        input_(options.limits),
        progress_(*this),
        deadline_(context->deadline()),
        receive_start_(Clock::now()) {
    admitted_ = gate_.try_enter();
    if (!admitted_) {
      finish_with(absl::UnavailableError(
          "the server is shutting down; retry (another replica can serve the call)"));
      return;
    }
    slot_ = pool_.try_reserve();
    if (!slot_) {
      finish_with(absl::ResourceExhaustedError(absl::StrFormat(
                      "the server is busy: all %d workers and %d queue slots are taken; retry "
                      "in about %d ms",
                      pool_.workers(), pool_.max_queue(), kRetryAfterBusyMs)),
                  kRetryAfterBusyMs);
      return;
    }
    start_read();
  }

  ~MeshVolumeCall() override {
    if (admitted_) gate_.leave();
  }

  void OnReadDone(bool ok) override {
    stall_watch_.ended(context_, StallWatch::Transfer::kRead);
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (finished_) return;
      if (ok) count_request(request_, record_);
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
    stall_watch_.ended(context_, StallWatch::Transfer::kWrite);
    {
      std::lock_guard<std::mutex> lock(mu_);
      writing_ = false;
      if (!ok) {
        // The stream is broken (the call was cancelled): nothing more can be sent.
        cancel_requested_.store(true, std::memory_order_release);
        outbox_.clear();
        output_.reset();
        if (job_state_ != JobState::kRunning) final_status_ = stop_status();
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
      final_status_ = stop_status();
    }
    pump();
  }

  void OnDone() override { release(); }

  // True once the client cancelled, the deadline passed or the server's drain ran out of time.
  bool stop_requested() const {
    return cancel_requested_.load(std::memory_order_acquire) ||
           std::chrono::system_clock::now() >= deadline_ || gate_.aborting();
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

 private:
  enum class JobState { kNotStarted, kRunning, kDone };

  absl::Status add_input() {
    try {
      return input_.add(request_);
    } catch (const std::bad_alloc&) {
      return absl::ResourceExhaustedError("the server ran out of memory receiving this input");
    }
  }

  // Half-close (or a read failing because the call was cancelled): check the whole input and
  // queue the job.
  void end_of_input() {
    if (context_->IsCancelled()) {
      finish_with(absl::CancelledError("the call was cancelled while sending its input"));
      return;
    }
    receive_seconds_ = seconds_since(receive_start_);
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
    pool_.run(std::move(slot), [this, front = input_.take_front(), params = input_.params(),
                                mode = input_.environment_mode(),
                                queued_at = Clock::now()]() mutable {
      job_start_ = Clock::now();
      run_job(front, params, mode, queued_at);
      release();
    });
  }

  // On a worker thread: the crossing environments when asked for (paper §2), then the job.
  void run_job(Mesh& front, VolumeParams& params, v1::EnvironmentMode mode,
               Clock::time_point queued_at) {
    std::vector<StageTiming> timings = {{"receive", receive_seconds_},
                                        {"queue", seconds_since(queued_at)}};
    std::vector<std::string> notes;
    absl::StatusOr<VolumeJobOutput> output = stop_status_absl();
    FrontRepairReport repair;
    if (!stop_requested()) {
      // F1 for fronts as files bring them: what can be repaired without guessing is, and said.
      const Clock::time_point repair_start = Clock::now();
      repair = repair_front(front);
      timings.push_back({"repair", seconds_since(repair_start)});
      for (std::string& note : repair.notes()) notes.push_back(std::move(note));
      const Clock::time_point start = Clock::now();
      absl::Status status = admit_by_estimate(front, params, notes);
      if (status.ok()) status = run_environments_guarded(mode, front, params, notes);
      if (mode != v1::ENVIRONMENT_MODE_NONE) {
        timings.push_back({"environments", seconds_since(start)});
      }
      output = !status.ok()       ? absl::StatusOr<VolumeJobOutput>(status)
               : stop_requested() ? absl::StatusOr<VolumeJobOutput>(stop_status_absl())
                                  : run_guarded(job_, front, params, progress_);
    }
    if (output.ok()) {
      if (absl::Status status = check_job_output(*output); !status.ok()) output = status;
    }
    if (output.ok()) {
      output->warnings.insert(output->warnings.begin(), notes.begin(), notes.end());
      output->repair = repair;
      output->estimated_tets = estimated_tets_;
    }
    complete_job(std::move(output), std::move(timings));
  }

  // Limits up front: the tets the size field asks for and the bytes the job will need, from
  // estimate_volume_mesh, against --max-elements and the server's memory budget; the bytes stay
  // reserved until the call is gone (its mesh streamed out). A size specification that cannot
  // be evaluated is the job's to report.
  absl::Status admit_by_estimate(const Mesh& front, VolumeParams& params,
                                 std::vector<std::string>& notes) {
    params.max_tets = max_elements_;  // the front stops there too, should the estimate be wrong
    absl::StatusOr<VolumeEstimate> estimate = estimate_volume_mesh(front, params);
    if (!estimate.ok()) return absl::OkStatus();
    estimated_tets_ = estimate->tets;
    if (estimate->coarse_front_triangles > 0) {
      notes.push_back(absl::StrFormat(
          "%d of the %d input triangles have edges over %g times the size asked on them (up to "
          "%.3g times): the elements on them take about their size, not the size asked, and gaps "
          "narrower than their edges may not close; re-triangulate the surface at the size first",
          estimate->coarse_front_triangles, front.triangles.size(), kCoarseFrontRatio,
          estimate->coarsest_front_ratio));
    }
    if (estimate->tets > static_cast<double>(max_elements_)) {
      return absl::ResourceExhaustedError(absl::StrFormat(
          "the size field asks for about %.3g tetrahedra (estimated before meshing from the "
          "enclosed volume and the sizes), over this server's limit of %d (--max-elements); ask "
          "for larger elements, or split the domain",
          estimate->tets, max_elements_));
    }
    const double gib = static_cast<double>(std::int64_t{1} << 30);
    if (estimate->bytes > static_cast<double>(budget_.capacity())) {
      return absl::ResourceExhaustedError(absl::StrFormat(
          "meshing this input needs about %.3g GiB (about %.3g tetrahedra), over this server's "
          "memory budget of %.3g GiB (--memory-budget-mb); ask for larger elements",
          estimate->bytes / gib, estimate->tets, static_cast<double>(budget_.capacity()) / gib));
    }
    reservation_ = budget_.try_reserve(static_cast<std::int64_t>(estimate->bytes));
    if (!reservation_) {
      {
        std::lock_guard<std::mutex> lock(mu_);
        retry_after_ms_ = kRetryAfterBudgetMs;
      }
      return absl::ResourceExhaustedError(absl::StrFormat(
          "the server's memory budget (%.3g GiB, --memory-budget-mb) is held by the jobs running "
          "now (%.3g GiB); this one needs about %.3g GiB: retry later (in about %d ms)",
          static_cast<double>(budget_.capacity()) / gib,
          static_cast<double>(budget_.in_use()) / gib, estimate->bytes / gib,
          kRetryAfterBudgetMs));
    }
    return absl::OkStatus();
  }

  // assign_environments, turning exceptions into statuses like run_guarded.
  absl::Status run_environments_guarded(v1::EnvironmentMode mode, const Mesh& front,
                                        VolumeParams& params, std::vector<std::string>& notes) {
    try {
      return assign_environments(mode, front, params, progress_, notes);
    } catch (const std::bad_alloc&) {
      return absl::ResourceExhaustedError("the server ran out of memory marking environments");
    } catch (const std::exception& e) {
      return absl::InternalError(absl::StrCat("marking environments failed: ", e.what()));
    }
  }

  // Records the job's outcome: its mesh streams unless the call was stopped meanwhile.
  void complete_job(absl::StatusOr<VolumeJobOutput> output, std::vector<StageTiming> timings) {
    {
      std::lock_guard<std::mutex> lock(mu_);
      job_state_ = JobState::kDone;
      record_.job_seconds = seconds_since(job_start_);
      if (stop_requested()) {
        final_status_ = stop_status();
      } else if (output.ok()) {
        record_.points_out = static_cast<std::int64_t>(output->volume.mesh.points.size());
        record_.triangles_out = static_cast<std::int64_t>(output->volume.mesh.triangles.size());
        record_.tets_out = static_cast<std::int64_t>(output->volume.mesh.tets.size());
        output_ = std::make_unique<VolumeOutputStream>(*std::move(output), std::move(timings));
        final_status_ = grpc::Status::OK;
      } else {
        final_status_ = to_grpc(output.status());
      }
    }
    pump();
  }

  // CANCELLED, DEADLINE_EXCEEDED when the deadline has passed, or UNAVAILABLE when the server
  // stopped the call at the end of its drain.
  absl::Status stop_status_absl() const {
    if (std::chrono::system_clock::now() >= deadline_) {
      return absl::DeadlineExceededError("the call's deadline passed; meshing stopped");
    }
    if (gate_.aborting() && !cancel_requested_.load(std::memory_order_acquire)) {
      return absl::UnavailableError(
          "the server is shutting down and its --grace-period ran out; meshing stopped: retry "
          "(another replica can serve the call)");
    }
    return absl::CancelledError("the call was cancelled; meshing stopped");
  }
  grpc::Status stop_status() const { return to_grpc(stop_status_absl()); }

  // Finishes the call with `status` (an error before any job ran), telling the client to retry
  // after `retry_after_ms` when set.
  void finish_with(const absl::Status& status, std::optional<int> retry_after_ms = std::nullopt) {
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (final_status_) return;
      final_status_ = to_grpc(status);
      if (retry_after_ms) retry_after_ms_ = retry_after_ms;
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
    } else if (output_ != nullptr && output_->next(current_)) {
      // current_ holds the next result message
    } else if (final_status_ && job_state_ != JobState::kRunning) {
      finished_ = true;
      const grpc::Status status = *final_status_;
      CallRecord record = record_;
      const std::optional<int> retry_after_ms = status.ok() ? std::nullopt : retry_after_ms_;
      lock.unlock();
      if (retry_after_ms) {
        context_->AddTrailingMetadata(kRetryAfterKey, std::to_string(*retry_after_ms));
      }
      context_->AddTrailingMetadata(wire::kFinalStatusKey, "1");
      report_finish(status, std::move(record));
      Finish(status);
      return;
    } else {
      return;
    }
    writing_ = true;
    record_.bytes_out += static_cast<std::int64_t>(current_.ByteSizeLong());
    lock.unlock();
    stall_watch_.started(context_, StallWatch::Transfer::kWrite);
    StartWrite(&current_);
  }

  // The call's end, to its log line and the metrics (call_log.h).
  void report_finish(const grpc::Status& status, CallRecord record) const {
    record.rpc = "MeshVolume";
    record.peer = context_->peer();
    record.seconds = seconds_since(receive_start_);
    record.status = status;
    report_call_end(std::move(record), log_calls_, metrics_);
  }

  // Drops one reference (gRPC's at OnDone, the job's when it returns); the last one deletes.
  void release() {
    if (references_.fetch_sub(1, std::memory_order_acq_rel) == 1) delete this;
  }

  void start_read() {
    stall_watch_.started(context_, StallWatch::Transfer::kRead);
    StartRead(&request_);
  }

  grpc::CallbackServerContext* const context_;
  StallWatch& stall_watch_;
  WorkerPool& pool_;
  CallGate& gate_;
  bool admitted_ = false;  // passed the gate: counted until this object is deleted
  MemoryBudget& budget_;
  const std::int64_t max_elements_;
  // Set by the job before it meshes: what admit_by_estimate found and took.
  double estimated_tets_ = 0.0;
  std::optional<MemoryBudget::Reservation> reservation_;
  const VolumeJob& job_;
  const bool log_calls_;
  ServerMetrics& metrics_;
  VolumeInput input_;  // touched by reads only, one at a time
  Request request_;    // the read in flight
  std::optional<WorkerPool::Slot> slot_;
  CallProgress progress_;
  const std::chrono::system_clock::time_point deadline_;
  const Clock::time_point receive_start_;
  double receive_seconds_ = 0.0;  // written before the job is queued, read by the job
  Clock::time_point job_start_;   // written and read by the job
  std::atomic<bool> cancel_requested_{false};
  std::atomic<int> references_{1};  // gRPC's, plus the job's while it is queued or running

  std::mutex mu_;
  JobState job_state_ ABSL_GUARDED_BY(mu_) = JobState::kNotStarted;
  std::deque<Response> outbox_ ABSL_GUARDED_BY(mu_);  // events waiting to be written
  std::unique_ptr<VolumeOutputStream> output_ ABSL_GUARDED_BY(mu_);
  std::optional<grpc::Status> final_status_ ABSL_GUARDED_BY(mu_);
  CallRecord record_ ABSL_GUARDED_BY(mu_);  // input counts as read, output counts once done
  std::optional<int> retry_after_ms_ ABSL_GUARDED_BY(mu_);  // sent with a failed final status
  bool writing_ ABSL_GUARDED_BY(mu_) = false;
  bool finished_ ABSL_GUARDED_BY(mu_) = false;
  Response current_;  // the write in flight; only touched while writing_ is false
  std::string last_stage_ ABSL_GUARDED_BY(mu_);
  Clock::time_point last_progress_ ABSL_GUARDED_BY(mu_);
};

void CallProgress::report(std::string_view stage, double fraction) {
  call_.post_progress(stage, fraction);
}

bool CallProgress::cancelled() const { return call_.stop_requested(); }

class MesherService final : public v1::Mesher::CallbackService {
 public:
  MesherService(WorkerPool& pool, CallGate& gate, MemoryBudget& budget, ServerMetrics& metrics,
                VolumeJob job, const ServiceOptions& options)
      : pool_(pool),
        gate_(gate),
        budget_(budget),
        metrics_(metrics),
        job_(std::move(job)),
        options_(options),
        stall_watch_(options.stall_timeout) {}

  grpc::ServerBidiReactor<Request, Response>* MeshVolume(
      grpc::CallbackServerContext* context) override {
    if (auto* refused = refuse_unauthenticated<Request, Response>(
            "MeshVolume", context, options_.bearer_token, options_.log_calls, metrics_)) {
      return refused;
    }
    return new MeshVolumeCall(context, pool_, gate_, budget_, metrics_, stall_watch_, job_,
                              options_);
  }

 private:
  WorkerPool& pool_;
  CallGate& gate_;
  MemoryBudget& budget_;
  ServerMetrics& metrics_;
  const VolumeJob job_;  // outlives the calls
  const ServiceOptions options_;
  StallWatch stall_watch_;  // outlives the calls: the server ends them before the service goes
};

}  // namespace

std::unique_ptr<grpc::Service> make_mesher_service(WorkerPool& pool, CallGate& gate,
                                                   MemoryBudget& budget, ServerMetrics& metrics,
                                                   VolumeJob job, const ServiceOptions& options) {
  return std::make_unique<MesherService>(pool, gate, budget, metrics, std::move(job), options);
}

}  // namespace afmesh::server
