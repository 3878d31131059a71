// The bearer-token check every Mesher handler makes first, before it reads any input: a call
// without the right "authorization: Bearer <token>" metadata ends UNAUTHENTICATED at once.
// Health and reflection are not checked (they carry no meshes, and orchestrators probe health
// without credentials).
#pragma once

#include <string>
#include <string_view>
#include <utility>

#include "grpcpp/grpcpp.h"
#include "server/call_log.h"

namespace afmesh::server {

// OK when `token` is empty (none asked for) or the call's metadata holds exactly one
// "authorization" entry equal to "Bearer <token>" (the scheme's case ignored, RFC 7235),
// compared in constant time; UNAUTHENTICATED otherwise, saying what is missing but nothing of
// the token.
grpc::Status check_bearer_token(const grpc::ServerContextBase& context, std::string_view token);

// A bidirectional-streaming call ended with `status` as soon as it starts: no message is read
// and none is written. Deletes itself when gRPC is done with it.
template <class Request, class Response>
class RefusedBidiCall final : public grpc::ServerBidiReactor<Request, Response> {
 public:
  explicit RefusedBidiCall(const grpc::Status& status) { this->Finish(status); }
  void OnDone() override { delete this; }
};

// For the top of each bidirectional handler: null when the call may go on, else a reactor that
// refuses it (reported with nothing read: a call_log.h line on stderr when `log` is set, and
// counted into `metrics`), to be returned instead of the call's own.
template <class Request, class Response>
grpc::ServerBidiReactor<Request, Response>* refuse_unauthenticated(
    const char* rpc, grpc::CallbackServerContext* context, std::string_view token, bool log,
    ServerMetrics& metrics) {
  const grpc::Status status = check_bearer_token(*context, token);
  if (status.ok()) return nullptr;
  CallRecord record;
  record.rpc = rpc;
  record.peer = context->peer();
  record.status = status;
  report_call_end(std::move(record), log, metrics);
  return new RefusedBidiCall<Request, Response>(status);
}

}  // namespace afmesh::server
