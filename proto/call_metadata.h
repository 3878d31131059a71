// Trailing metadata the Mesher service sends with a call's final status, read by the CLI: the
// wire's names in one place for both sides (not in the paper; design.md's wire contract).
#pragma once

namespace afmesh::wire {

// On a refusal that may succeed if sent again later (a full server, a held memory budget): the
// milliseconds to wait first. Refusals that cannot succeed later carry none.
inline constexpr char kRetryAfterKey[] = "retry-after-ms";

// Where a kRetryAfterKey hint travels inside a program: an absl::Status payload of this type
// holding the milliseconds as text (the server's refusal on its way to the trailer, the CLI's
// failed call on its way to the retry loop).
inline constexpr char kRetryAfterPayload[] = "type.afmesh.dev/retry-after-ms";

// On every status the service itself finishes a MeshVolume call with ("1"). A failed status
// without it did not come from a server that saw the call through: gRPC or a proxy on the way
// made it (a replica killed mid-call behind nginx gives INTERNAL "Received RST_STREAM", behind
// haproxy UNKNOWN "Stream removed"). Meshing is idempotent, so such a call can be sent again.
inline constexpr char kFinalStatusKey[] = "afmesh-final-status";

}  // namespace afmesh::wire
