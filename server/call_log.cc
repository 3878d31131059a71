#include "server/call_log.h"

#include <atomic>
#include <cstdio>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "server/metrics.h"

namespace afmesh::server {
namespace {

// `text` as a logfmt value: as it is when it needs no quotes, else in double quotes with `"`,
// `\` and control characters escaped.
std::string logfmt_value(const std::string& text) {
  bool plain = !text.empty();
  for (const char c : text) {
    if (c <= ' ' || c == '"' || c == '\\' || c == '=' || c == 0x7f) plain = false;
  }
  if (plain) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      quoted.push_back('\\');
      quoted.push_back(c);
    } else if (c == '\n') {
      quoted += "\\n";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      quoted += absl::StrFormat("\\x%02x", static_cast<unsigned char>(c));
    } else {
      quoted.push_back(c);
    }
  }
  quoted.push_back('"');
  return quoted;
}

}  // namespace

namespace {

// Both requests have `points` and `triangles` parts.
template <class Request>
void count_mesh_request(const Request& request, CallRecord& record) {
  record.messages_in += 1;
  record.bytes_in += static_cast<std::int64_t>(request.ByteSizeLong());
  if (request.has_points()) record.points_in += request.points().xyz_size() / 3;
  if (request.has_triangles()) record.triangles_in += request.triangles().indices_size() / 3;
}

}  // namespace

void count_request(const v1::MeshVolumeRequest& request, CallRecord& record) {
  count_mesh_request(request, record);
}

void count_request(const v1::MeshSurfaceRequest& request, CallRecord& record) {
  count_mesh_request(request, record);
}

std::uint64_t next_call_id() {
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1, std::memory_order_relaxed);
}

const char* code_name(grpc::StatusCode code) {
  switch (code) {
    case grpc::StatusCode::OK:
      return "OK";
    case grpc::StatusCode::CANCELLED:
      return "CANCELLED";
    case grpc::StatusCode::UNKNOWN:
      return "UNKNOWN";
    case grpc::StatusCode::INVALID_ARGUMENT:
      return "INVALID_ARGUMENT";
    case grpc::StatusCode::DEADLINE_EXCEEDED:
      return "DEADLINE_EXCEEDED";
    case grpc::StatusCode::NOT_FOUND:
      return "NOT_FOUND";
    case grpc::StatusCode::ALREADY_EXISTS:
      return "ALREADY_EXISTS";
    case grpc::StatusCode::PERMISSION_DENIED:
      return "PERMISSION_DENIED";
    case grpc::StatusCode::RESOURCE_EXHAUSTED:
      return "RESOURCE_EXHAUSTED";
    case grpc::StatusCode::FAILED_PRECONDITION:
      return "FAILED_PRECONDITION";
    case grpc::StatusCode::ABORTED:
      return "ABORTED";
    case grpc::StatusCode::OUT_OF_RANGE:
      return "OUT_OF_RANGE";
    case grpc::StatusCode::UNIMPLEMENTED:
      return "UNIMPLEMENTED";
    case grpc::StatusCode::INTERNAL:
      return "INTERNAL";
    case grpc::StatusCode::UNAVAILABLE:
      return "UNAVAILABLE";
    case grpc::StatusCode::DATA_LOSS:
      return "DATA_LOSS";
    case grpc::StatusCode::UNAUTHENTICATED:
      return "UNAUTHENTICATED";
    default:
      return "UNKNOWN";
  }
}

const char* outcome_of(grpc::StatusCode code, bool retry_hint) {
  switch (code) {
    case grpc::StatusCode::OK:
      return "ok";
    case grpc::StatusCode::INVALID_ARGUMENT:
      return "bad_input";
    case grpc::StatusCode::UNAUTHENTICATED:
    case grpc::StatusCode::PERMISSION_DENIED:
      return "refused";
    case grpc::StatusCode::RESOURCE_EXHAUSTED:
      return retry_hint ? "busy" : "over_limit";
    case grpc::StatusCode::UNAVAILABLE:
      return "busy";
    case grpc::StatusCode::CANCELLED:
    case grpc::StatusCode::DEADLINE_EXCEEDED:
      return "stopped";
    case grpc::StatusCode::FAILED_PRECONDITION:
      return "mesh_failed";
    default:
      return "error";
  }
}

std::string format_call_log(const CallRecord& record) {
  return absl::StrFormat(
      "call id=%d rpc=%s peer=%s messages_in=%d bytes_in=%d points_in=%d triangles_in=%d "
      "seconds=%.3f outcome=%s code=%s points_out=%d tets_out=%d message=%s",
      record.id, logfmt_value(record.rpc), logfmt_value(record.peer), record.messages_in,
      record.bytes_in, record.points_in, record.triangles_in, record.seconds,
      outcome_of(record.status.error_code(), record.retry_after_ms.has_value()),
      code_name(record.status.error_code()),
      record.points_out, record.tets_out,
      record.status.ok() ? std::string("\"\"") : logfmt_value(record.status.error_message()));
}

void report_call_end(CallRecord record, bool log, ServerMetrics& metrics) {
  record.id = next_call_id();
  if (log) std::fprintf(stderr, "%s\n", format_call_log(record).c_str());
  metrics.observe_call(record);
}

}  // namespace afmesh::server
