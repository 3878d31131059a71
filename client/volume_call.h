// The client side of one MeshVolume call: streams a front up in slices, collects the events
// and the mesh coming back, checks the answer is whole. No generated gRPC types in this header,
// so that only volume_call.cc compiles them.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/status/statusor.h"
#include "client/channel_credentials.h"
#include "core/mesh/mesh.h"
#include "core/sizing/size_spec.h"

namespace grpc {
class ClientContext;
}

namespace afmesh::cli {

// Cancels a call from another thread (e.g. on Ctrl-C): the call ends CANCELLED and the server
// stops its job.
class CallCanceller {
 public:
  // Cancels the call in progress, or the next one as soon as it starts.
  void cancel();
  bool cancelled() const;

  // For call_mesh_volume: the context of the call in progress (null when none).
  void attach(grpc::ClientContext* context);

 private:
  mutable std::mutex mu_;
  grpc::ClientContext* context_ ABSL_GUARDED_BY(mu_) = nullptr;
  bool cancelled_ ABSL_GUARDED_BY(mu_) = false;
};

// Where the front's crossing environments come from (VolumeOptions.environments, paper §2).
enum class EnvironmentSource { kNone, kTags, kAuto };

struct VolumeCallOptions {
  double size = 0.0;    // SizeSpec.max_size (> 0)
  double growth = 1.0;  // SizeSpec.growth (>= 1)
  // When set, the whole size specification is sent (its max_size and growth replace `size` and
  // `growth`).
  std::optional<SizeSpec> spec;
  // Crossing environments: none, the triangle tags, or found by the server.
  EnvironmentSource environments = EnvironmentSource::kNone;
  // Deadline of the whole call in seconds; 0 means none.
  double timeout_seconds = 0.0;
  // When set, cancels the call on request.
  CallCanceller* canceller = nullptr;
  // TLS and the bearer token (channel_credentials.h); default: plaintext, no token.
  ClientSecurity security;
  // MeshVolume: re-triangulate the front on the server first (VolumeOptions.remesh_surface).
  bool remesh_surface = false;
  // MeshVolume: at most how many times a front that stops is meshed again
  // (VolumeOptions.max_reruns); unset: the server's default.
  std::optional<int> max_reruns;
  // MeshSurface, and MeshVolume with remesh_surface: ridge and corner angles in degrees
  // (SurfaceOptions; 0: the server's defaults, 30 and 60), and the curvature angle (unset: the
  // server's default, 30; 0: no curvature bound) and deviation (a fraction of the model size;
  // unset: the server's default, none; 0: none), and the wall sizes (elements per wall
  // thickness; unset: the server's default, none; 0: none). `environments` is MeshVolume's only.
  double ridge_angle_deg = 0.0;
  double corner_angle_deg = 0.0;
  std::optional<double> curvature_angle_deg;
  std::optional<double> curvature_deviation;
  std::optional<double> wall_sizes;
};

// Where the call is, for the progress display: the client's own stages ("send", "receive")
// and the server's Progress events; `fraction` in [0, 1] or negative when unknown.
using ProgressCallback = std::function<void(std::string_view stage, double fraction)>;
using WarningCallback = std::function<void(std::string_view message)>;

// The Summary message, as plain values.
struct VolumeSummary {
  std::uint64_t point_count = 0;
  std::uint64_t triangle_count = 0;
  std::uint64_t tet_count = 0;
  double min_dihedral_deg = 0.0;
  double max_dihedral_deg = 0.0;
  double share_below_10_deg = 0.0;
  double share_below_20_deg = 0.0;
  double min_radius_ratio = 0.0;
  double mean_radius_ratio = 0.0;
  // The boundary's slivers and the tets away from them (QualityFigures in mesher.proto).
  double boundary_min_angle_deg = 0.0;
  std::uint64_t boundary_sliver_count = 0;
  std::uint64_t tets_away_from_slivers = 0;
  double min_dihedral_away_from_slivers_deg = 0.0;
  double share_away_from_slivers_below_20_deg = 0.0;
  bool validation_passed = false;
  std::vector<std::string> validation_messages;
  std::vector<std::pair<std::string, double>> timings;  // stage, seconds
  // The boundary is a re-triangulation of the input (remesh_surface).
  bool surface_remeshed = false;
  // The Summary in protobuf's JSON mapping (lowerCamelCase fields, as mesher.proto documents).
  std::string json;
};

struct VolumeCallResult {
  Mesh mesh;  // points, the boundary triangles with tags, tets with tags
  VolumeSummary summary;
};

// The SurfaceSummary message, as plain values (the rest is in `json`).
struct SurfaceSummary {
  std::uint64_t point_count = 0;
  std::uint64_t triangle_count = 0;
  double min_angle_deg = 0.0;
  double max_angle_deg = 0.0;
  double share_below_30_deg = 0.0;
  std::uint64_t count_below_15_deg = 0;
  std::uint64_t count_below_15_deg_at_thinner_input = 0;  // at input triangles or corners as thin
  std::uint64_t patches = 0;
  std::uint64_t lines = 0;
  std::uint64_t corners = 0;
  std::uint64_t patches_from_input = 0;  // re-triangulated from their input: a front stopped
  double hausdorff = 0.0;
  double max_vertex_distance = 0.0;
  double model_size = 0.0;
  std::vector<std::pair<std::string, double>> timings;  // stage, seconds
  std::string json;  // protobuf's JSON mapping
};

struct SurfaceCallResult {
  Mesh mesh;  // points, triangles with their patch tags
  SurfaceSummary summary;
};

// The server's hint on a failed call that may succeed if sent again later (the trailing
// metadata retry-after-ms of a refusal for a full server or a held memory budget); nullopt when
// the server sent none, i.e. asking again unchanged cannot help.
std::optional<std::chrono::milliseconds> retry_after(const absl::Status& status);

// True when the failed call's status did not come from the service (no wire::kFinalStatusKey
// trailer): gRPC or a proxy on the way ended it, e.g. a replica killed mid-call.
bool cut_on_the_way(const absl::Status& status);

// Whether the CLI sends a failed call again: always when the server gave a retry hint; against
// a shared server (--server) also UNAVAILABLE (a replica draining or gone), and INTERNAL or
// UNKNOWN when cut_on_the_way (a balancer's answer for a replica killed mid-call). Never
// INVALID_ARGUMENT, FAILED_PRECONDITION, a refusal without a hint, CANCELLED, DEADLINE_EXCEEDED,
// or an INTERNAL the service itself sent (a mesh that failed validation fails again).
bool worth_retrying(const absl::Status& status, bool shared_server);

// The gRPC target for --server ADDR: ADDR itself (host:port, unix:PATH, dns:///name:port,
// ipv4:a:p,b:p, ...), except that a bare comma list of IPv4 addresses "a:p,b:p" becomes the
// ipv4: list gRPC reads, in an order shuffled by `seed`, so that calls spread over its replicas.
std::string channel_target(const std::string& address, std::uint64_t seed);

// Runs MeshSurface against `address` with `input` (points N×3, triangles M×3 with tags), with
// the size, angles, timeout, canceller and security of `options`. Errors as call_mesh_volume's.
absl::StatusOr<SurfaceCallResult> call_mesh_surface(const std::string& address,
                                                    const Mesh& input,
                                                    const VolumeCallOptions& options,
                                                    const ProgressCallback& on_progress,
                                                    const WarningCallback& on_warning);

// Runs MeshVolume against `address` with `front` (points N×3, triangles M×3 with tags).
// Errors: the call's gRPC status as the absl::Status of the same code and message;
// DATA_LOSS when the server's answer holds a malformed slice (proto/slice_codec.h), ends
// without a Summary or disagrees with it. A retry hint travels as a payload of the status
// (retry_after).
absl::StatusOr<VolumeCallResult> call_mesh_volume(const std::string& address, const Mesh& front,
                                                  const VolumeCallOptions& options,
                                                  const ProgressCallback& on_progress,
                                                  const WarningCallback& on_warning);

}  // namespace afmesh::cli
