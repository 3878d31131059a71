// The one line afmesh-server logs per finished call, in logfmt (key=value pairs, values with
// spaces or quotes quoted), so that log pipelines can parse it without a grammar of ours:
//   call id=12 rpc=MeshVolume peer=ipv4:127.0.0.1:50522 messages_in=3 bytes_in=412 points_in=4
//   triangles_in=4 seconds=0.012 outcome=ok code=OK points_out=4 tets_out=1 message=""
// (one line; wrapped here).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "afmesh/v1/mesher.pb.h"
#include "grpcpp/support/status.h"

namespace afmesh::server {

class ServerMetrics;

struct CallRecord {
  std::uint64_t id = 0;  // next_call_id() when the line is written (calls numbered as they end)
  std::string rpc;       // "MeshVolume"
  std::string peer;      // grpc::ServerContext::peer()
  // What the client sent: messages, their serialised bytes, and the points and triangles they
  // carried (counted as they arrive, so a call that fails mid-stream shows how far it got).
  std::int64_t messages_in = 0;
  std::int64_t bytes_in = 0;
  std::int64_t points_in = 0;
  std::int64_t triangles_in = 0;
  double seconds = 0.0;  // from the call's arrival to its end
  grpc::Status status;
  // The mesh handed out (0 unless the call succeeded).
  std::int64_t points_out = 0;
  std::int64_t triangles_out = 0;
  std::int64_t tets_out = 0;
  // Serialised bytes of the messages the server wrote (events, mesh slices, Summary).
  std::int64_t bytes_out = 0;
  // How long the call's job ran on a worker; unset when none ran (refused or stopped before).
  std::optional<double> job_seconds;
  // The retry hint (retry-after-ms) sent with a refusal that may pass later; unset otherwise.
  std::optional<int> retry_after_ms;
};

// Counts `request` into record's messages_in, bytes_in, points_in and triangles_in.
void count_request(const v1::MeshVolumeRequest& request, CallRecord& record);
void count_request(const v1::MeshSurfaceRequest& request, CallRecord& record);

// A number for each call, unique in the process (shared by every server in it).
std::uint64_t next_call_id();

// The status code's name, as gRPC spells it ("OK", "UNAUTHENTICATED", ...).
const char* code_name(grpc::StatusCode code);

// What happened, coarser than the code, for dashboards: ok, bad_input (INVALID_ARGUMENT),
// refused (UNAUTHENTICATED, PERMISSION_DENIED), busy (RESOURCE_EXHAUSTED with a retry hint, or
// UNAVAILABLE: asking again later may pass), over_limit (RESOURCE_EXHAUSTED without a hint: the
// request is over a limit, and asking again cannot help), stopped (CANCELLED,
// DEADLINE_EXCEEDED), mesh_failed (FAILED_PRECONDITION), error (the rest).
const char* outcome_of(grpc::StatusCode code, bool retry_hint = true);

// The line, without a trailing newline.
std::string format_call_log(const CallRecord& record);

// The one place a finished call is observed, whichever way it ended: numbers `record`
// (next_call_id), writes its line on stderr when `log` is set and counts it into `metrics`.
void report_call_end(CallRecord record, bool log, ServerMetrics& metrics);

}  // namespace afmesh::server
