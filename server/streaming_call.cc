#include "server/streaming_call.h"

#include <cstdint>
#include <string>

#include "absl/strings/cord.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_format.h"
#include "proto/call_metadata.h"

namespace afmesh::server {
namespace {

// Backpressure (issue 12, part 2): a refusal that may succeed later carries the trailing
// metadata wire::kRetryAfterKey (proto/call_metadata.h), the milliseconds to wait first; on its
// way to the trailer it travels in the refusal's absl::Status as the wire::kRetryAfterPayload
// payload. Refusals that cannot succeed later (input or estimate over a limit) carry none.
constexpr int kRetryAfterBusyMs = 1000;    // all workers and queue slots taken
constexpr int kRetryAfterBudgetMs = 2000;  // the memory budget held by running jobs

absl::Status with_retry_after(absl::Status status, int ms) {
  status.SetPayload(wire::kRetryAfterPayload, absl::Cord(std::to_string(ms)));
  return status;
}

}  // namespace

absl::Status JobContext::reserve_memory(double bytes, std::string_view elements) {
  const double gib = static_cast<double>(std::int64_t{1} << 30);
  if (bytes > static_cast<double>(budget_.capacity())) {
    return absl::ResourceExhaustedError(absl::StrFormat(
        "meshing this input needs about %.3g GiB (about %s), over this server's memory budget "
        "of %.3g GiB (--memory-budget-mb); ask for larger elements",
        bytes / gib, elements, static_cast<double>(budget_.capacity()) / gib));
  }
  // A later estimate of the same job (remesh_surface: the surface's, then the volume's)
  // replaces the earlier one rather than adding to it.
  reservation_.reset();
  reservation_ = budget_.try_reserve(static_cast<std::int64_t>(bytes));
  if (!reservation_) {
    return with_retry_after(
        absl::ResourceExhaustedError(absl::StrFormat(
            "the server's memory budget (%.3g GiB, --memory-budget-mb) is held by the jobs "
            "running now (%.3g GiB); this one needs about %.3g GiB: retry later (in about %d ms)",
            static_cast<double>(budget_.capacity()) / gib,
            static_cast<double>(budget_.in_use()) / gib, bytes / gib, kRetryAfterBudgetMs)),
        kRetryAfterBudgetMs);
  }
  return absl::OkStatus();
}

absl::Status JobContext::admit_estimate(double count, std::string_view elements,
                                       std::string_view basis, std::string_view whole,
                                       double bytes, std::int64_t max_elements) {
  if (count > static_cast<double>(max_elements)) {
    return absl::ResourceExhaustedError(absl::StrFormat(
        "the size field asks for about %.3g %s (estimated before meshing from %s), over this "
        "server's limit of %d (--max-elements); ask for larger elements, or split the %s",
        count, elements, basis, max_elements, whole));
  }
  return reserve_memory(bytes, absl::StrFormat("%.3g %s", count, elements));
}

namespace call_detail {

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

grpc::Status to_grpc(const absl::Status& status) {
  return grpc::Status(static_cast<grpc::StatusCode>(status.code()), std::string(status.message()));
}

std::optional<int> retry_after_ms(const absl::Status& status) {
  const auto payload = status.GetPayload(wire::kRetryAfterPayload);
  int ms = 0;
  if (!payload || !absl::SimpleAtoi(std::string(*payload), &ms)) return std::nullopt;
  return ms;
}

absl::Status gate_closed() {
  return absl::UnavailableError(
      "the server is shutting down; retry (another replica can serve the call)");
}

absl::Status pool_full(const WorkerPool& pool) {
  return with_retry_after(
      absl::ResourceExhaustedError(absl::StrFormat(
          "the server is busy: all %d workers and %d queue slots are taken; retry in about %d ms",
          pool.workers(), pool.max_queue(), kRetryAfterBusyMs)),
      kRetryAfterBusyMs);
}

absl::Status stopped(bool deadline_passed, bool aborting, bool client_cancelled) {
  if (deadline_passed) {
    return absl::DeadlineExceededError("the call's deadline passed; meshing stopped");
  }
  if (aborting && !client_cancelled) {
    return absl::UnavailableError(
        "the server is shutting down and its --grace-period ran out; meshing stopped: retry "
        "(another replica can serve the call)");
  }
  return absl::CancelledError("the call was cancelled; meshing stopped");
}

absl::Status out_of_memory_receiving() {
  return absl::ResourceExhaustedError("the server ran out of memory receiving this input");
}

void add_final_trailers(grpc::CallbackServerContext& context, std::optional<int> retry_after_ms) {
  if (retry_after_ms) {
    context.AddTrailingMetadata(wire::kRetryAfterKey, std::to_string(*retry_after_ms));
  }
  context.AddTrailingMetadata(wire::kFinalStatusKey, "1");
}

}  // namespace call_detail
}  // namespace afmesh::server
