#include "client/volume_call.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "absl/strings/cord.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "afmesh/v1/mesher.grpc.pb.h"
#include "google/protobuf/util/json_util.h"
#include "grpcpp/grpcpp.h"
#include "proto/call_metadata.h"
#include "proto/size_spec_convert.h"
#include "proto/slice_codec.h"

namespace afmesh::cli {
namespace {

// The server's retry hint (server/streaming_call.cc) and where it travels in an absl::Status.
using wire::kRetryAfterKey;
using wire::kRetryAfterPayload;
constexpr char kCutOnTheWayPayload[] = "type.afmesh.dev/cut-on-the-way";

template <class Request, class Response>
using Stream = grpc::ClientReaderWriter<Request, Response>;

// The size and the counts of a MeshVolumeHeader or MeshSurfaceHeader (the same fields).
template <class Header>
void set_size_and_counts(const Mesh& front, const VolumeCallOptions& options, Header& header) {
  if (options.spec) {
    *header.mutable_options()->mutable_size() = size_spec_to_proto(*options.spec);
    // The background grid, whatever its size, follows in slices (send_grid).
    header.mutable_options()->mutable_size()->clear_background();
    if (options.spec->background) {
      header.set_grid_point_count(options.spec->background->points.size());
      header.set_grid_tet_count(options.spec->background->tets.size());
    }
  } else {
    header.mutable_options()->mutable_size()->set_max_size(options.size);
    header.mutable_options()->mutable_size()->set_growth(options.growth);
  }
  header.set_point_count(front.points.size());
  header.set_triangle_count(front.triangles.size());
}

v1::MeshSurfaceRequest header_request(const Mesh& front, const VolumeCallOptions& options,
                                      const v1::MeshSurfaceRequest* /*type*/) {
  v1::MeshSurfaceRequest request;
  v1::MeshSurfaceHeader& header = *request.mutable_header();
  set_size_and_counts(front, options, header);
  header.mutable_options()->set_ridge_angle_deg(options.ridge_angle_deg);
  header.mutable_options()->set_corner_angle_deg(options.corner_angle_deg);
  if (options.curvature_angle_deg) {
    header.mutable_options()->set_curvature_angle_deg(*options.curvature_angle_deg);
  }
  if (options.curvature_deviation) {
    header.mutable_options()->set_curvature_deviation(*options.curvature_deviation);
  }
  if (options.wall_sizes) header.mutable_options()->set_wall_sizes(*options.wall_sizes);
  return request;
}

v1::MeshVolumeRequest header_request(const Mesh& front, const VolumeCallOptions& options,
                                     const v1::MeshVolumeRequest* /*type*/) {
  v1::MeshVolumeRequest request;
  v1::MeshVolumeHeader& header = *request.mutable_header();
  set_size_and_counts(front, options, header);
  if (options.remesh_surface) {
    header.mutable_options()->set_remesh_surface(true);
    header.mutable_options()->set_ridge_angle_deg(options.ridge_angle_deg);
    header.mutable_options()->set_corner_angle_deg(options.corner_angle_deg);
    if (options.curvature_angle_deg) {
      header.mutable_options()->set_curvature_angle_deg(*options.curvature_angle_deg);
    }
    if (options.curvature_deviation) {
      header.mutable_options()->set_curvature_deviation(*options.curvature_deviation);
    }
    if (options.wall_sizes) header.mutable_options()->set_wall_sizes(*options.wall_sizes);
  }
  if (options.max_reruns) header.mutable_options()->set_max_reruns(*options.max_reruns);
  switch (options.environments) {
    case EnvironmentSource::kNone:
      header.mutable_options()->set_environments(v1::ENVIRONMENT_MODE_NONE);
      break;
    case EnvironmentSource::kTags:
      header.mutable_options()->set_environments(v1::ENVIRONMENT_MODE_TAGS);
      break;
    case EnvironmentSource::kAuto:
      header.mutable_options()->set_environments(v1::ENVIRONMENT_MODE_AUTO);
      break;
  }
  return request;
}

// Streams the background grid in slices, each of one kind (points, sizes or tets) and at most
// wire::kMaxSliceItems of it: under 1 MiB each, built one at a time. False once a write fails.
template <class Request, class Response>
bool send_grid(Stream<Request, Response>& stream, const BackgroundGridSpec& grid) {
  bool open = true;
  for (std::size_t begin = 0; open && begin < grid.points.size(); begin += wire::kMaxSliceItems) {
    Request request;
    wire::encode_grid_points(grid.points, begin, wire::slice_end(begin, grid.points.size()),
                             *request.mutable_background_grid());
    open = stream.Write(request);
  }
  for (std::size_t begin = 0; open && begin < grid.sizes.size(); begin += wire::kMaxSliceItems) {
    Request request;
    wire::encode_grid_sizes(grid.sizes, begin, wire::slice_end(begin, grid.sizes.size()),
                            *request.mutable_background_grid());
    open = stream.Write(request);
  }
  for (std::size_t begin = 0; open && begin < grid.tets.size(); begin += wire::kMaxSliceItems) {
    Request request;
    wire::encode_grid_tets(grid.tets, begin, wire::slice_end(begin, grid.tets.size()),
                           *request.mutable_background_grid());
    open = stream.Write(request);
  }
  return open;
}

// Header, background grid slices, point slices, triangle slices, half-close. Stops early when a
// write fails: the server ended the call, and Finish() says why.
template <class Request, class Response>
void send_front(Stream<Request, Response>& stream, const Mesh& front,
                const VolumeCallOptions& options, const ProgressCallback& on_progress) {
  const double total = static_cast<double>(front.points.size() + front.triangles.size());
  bool open = stream.Write(header_request(front, options, static_cast<const Request*>(nullptr)));
  if (open && options.spec && options.spec->background) {
    open = send_grid(stream, *options.spec->background);
  }
  for (std::size_t begin = 0; open && begin < front.points.size();
       begin += wire::kMaxSliceItems) {
    const std::size_t end = wire::slice_end(begin, front.points.size());
    Request request;
    wire::encode_points(front.points, begin, end, *request.mutable_points());
    open = stream.Write(request);
    on_progress("send", static_cast<double>(end) / total);
  }
  for (std::size_t begin = 0; open && begin < front.triangles.size();
       begin += wire::kMaxSliceItems) {
    const std::size_t end = wire::slice_end(begin, front.triangles.size());
    Request request;
    wire::encode_triangles(front.triangles, front.triangle_tags, begin, end,
                           *request.mutable_triangles());
    open = stream.Write(request);
    on_progress("send", static_cast<double>(front.points.size() + end) / total);
  }
  stream.WritesDone();
}

// Appends the mesh slice carried by `response` (the server's message `number`) to `mesh`;
// DATA_LOSS when the slice is malformed.
template <class Response>
absl::Status append_slice(const Response& response, std::int64_t number, Mesh& mesh) {
  const std::string where = absl::StrCat("message ", number);
  absl::Status status;
  if (response.has_points()) {
    status = wire::append_points(response.points(), where, mesh.points);
  } else if (response.has_triangles()) {
    status = wire::append_triangles(response.triangles(), where, mesh.triangles,
                                    mesh.triangle_tags);
  } else if constexpr (requires { response.has_tets(); }) {
    if (response.has_tets()) {
      status = wire::append_tets(response.tets(), where, mesh.tets, mesh.tet_tags);
    }
  }
  if (status.ok()) return status;
  return absl::DataLossError(absl::StrCat("the server's answer is malformed: ", status.message()));
}

// The tets a Summary announces (a SurfaceSummary: none).
std::uint64_t tet_count(const v1::Summary& summary) { return summary.tet_count(); }
std::uint64_t tet_count(const v1::SurfaceSummary& /*summary*/) { return 0; }

// DATA_LOSS unless the slices received add up to the counts the Summary announces.
template <class Summary>
absl::Status check_whole(const Mesh& mesh, const Summary& summary) {
  if (mesh.points.size() != summary.point_count() ||
      mesh.triangles.size() != summary.triangle_count() ||
      mesh.tets.size() != tet_count(summary) ||
      mesh.triangle_tags.size() != mesh.triangles.size() ||
      mesh.tet_tags.size() != mesh.tets.size()) {
    return absl::DataLossError(absl::StrFormat(
        "the server's mesh is incomplete: received %d points, %d triangles (%d tags), %d tets "
        "(%d tags); its summary announces %d, %d and %d",
        mesh.points.size(), mesh.triangles.size(), mesh.triangle_tags.size(), mesh.tets.size(),
        mesh.tet_tags.size(), summary.point_count(), summary.triangle_count(),
        tet_count(summary)));
  }
  return absl::OkStatus();
}

// `summary` in protobuf's JSON mapping, every field printed.
std::string summary_json(const google::protobuf::Message& summary) {
  google::protobuf::util::JsonPrintOptions json_options;
  json_options.add_whitespace = true;
  json_options.always_print_primitive_fields = true;
  std::string json;
  (void)google::protobuf::util::MessageToJsonString(summary, &json, json_options);
  return json;
}

VolumeSummary plain_summary(const v1::Summary& summary) {
  VolumeSummary plain;
  plain.point_count = summary.point_count();
  plain.triangle_count = summary.triangle_count();
  plain.tet_count = summary.tet_count();
  plain.min_dihedral_deg = summary.quality().min_dihedral_deg();
  plain.max_dihedral_deg = summary.quality().max_dihedral_deg();
  plain.share_below_10_deg = summary.quality().share_below_10_deg();
  plain.share_below_20_deg = summary.quality().share_below_20_deg();
  plain.min_radius_ratio = summary.quality().min_radius_ratio();
  plain.mean_radius_ratio = summary.quality().mean_radius_ratio();
  plain.boundary_min_angle_deg = summary.quality().boundary_min_angle_deg();
  plain.boundary_sliver_count = summary.quality().boundary_sliver_count();
  plain.tets_away_from_slivers = summary.quality().tets_away_from_slivers();
  plain.min_dihedral_away_from_slivers_deg =
      summary.quality().min_dihedral_away_from_slivers_deg();
  plain.share_away_from_slivers_below_20_deg =
      summary.quality().share_away_from_slivers_below_20_deg();
  plain.validation_passed = summary.validation().passed();
  plain.validation_messages.assign(summary.validation().messages().begin(),
                                   summary.validation().messages().end());
  for (const v1::StageTiming& timing : summary.timings()) {
    plain.timings.emplace_back(timing.stage(), timing.seconds());
  }
  plain.surface_remeshed = summary.surface_remeshed();
  plain.json = summary_json(summary);
  return plain;
}

SurfaceSummary plain_summary(const v1::SurfaceSummary& summary) {
  SurfaceSummary plain;
  plain.point_count = summary.point_count();
  plain.triangle_count = summary.triangle_count();
  plain.min_angle_deg = summary.quality().min_angle_deg();
  plain.max_angle_deg = summary.quality().max_angle_deg();
  plain.share_below_30_deg = summary.quality().share_below_30_deg();
  plain.count_below_15_deg = summary.quality().count_below_15_deg();
  plain.count_below_15_deg_at_thinner_input =
      summary.quality().count_below_15_deg_at_thinner_input();
  plain.patches = summary.features().patches();
  plain.lines = summary.features().lines();
  plain.corners = summary.features().corners();
  plain.patches_from_input = summary.features().patches_from_input();
  plain.hausdorff = summary.distance().hausdorff();
  plain.max_vertex_distance = summary.distance().max_vertex_distance();
  plain.model_size = summary.distance().model_size();
  for (const v1::StageTiming& timing : summary.timings()) {
    plain.timings.emplace_back(timing.stage(), timing.seconds());
  }
  plain.json = summary_json(summary);
  return plain;
}

// Sends the front and collects the answer (see call_mesh_volume).
template <class Result, class Request, class Response>
absl::StatusOr<Result> run_call(Stream<Request, Response>& stream, const Mesh& front,
                                const VolumeCallOptions& options,
                                const ProgressCallback& on_progress,
                                const WarningCallback& on_warning) {
  send_front(stream, front, options, on_progress);

  Result result;
  std::optional<std::decay_t<decltype(Response().summary())>> summary;
  Response response;
  std::int64_t received = 0;
  absl::Status malformed;
  while (stream.Read(&response)) {
    ++received;
    if (response.has_progress()) {
      on_progress(response.progress().stage(), response.progress().fraction());
    } else if (response.has_warning()) {
      on_warning(response.warning().message());
    } else if (response.has_summary()) {
      summary = response.summary();
    } else {
      if (malformed.ok()) malformed = append_slice(response, received, result.mesh);
      on_progress("receive", -1.0);
    }
  }
  const grpc::Status status = stream.Finish();
  if (!status.ok()) {
    return absl::Status(static_cast<absl::StatusCode>(status.error_code()), status.error_message());
  }
  if (!malformed.ok()) return malformed;
  if (!summary) return absl::DataLossError("the server's answer ended without a summary");
  if (absl::Status whole = check_whole(result.mesh, *summary); !whole.ok()) return whole;
  result.summary = plain_summary(*summary);
  return result;
}

}  // namespace

void CallCanceller::cancel() {
  std::lock_guard<std::mutex> lock(mu_);
  cancelled_ = true;
  if (context_ != nullptr) context_->TryCancel();
}

bool CallCanceller::cancelled() const {
  std::lock_guard<std::mutex> lock(mu_);
  return cancelled_;
}

void CallCanceller::attach(grpc::ClientContext* context) {
  std::lock_guard<std::mutex> lock(mu_);
  context_ = context;
  if (context_ != nullptr && cancelled_) context_->TryCancel();
}

namespace {

// One call of `Result`'s RPC (MeshVolume or MeshSurface; see call_mesh_volume): the channel,
// the deadline, the canceller, the call, and the retry hint or the cut kept in the status.
template <class Result>
absl::StatusOr<Result> call_mesher(const std::string& address, const Mesh& front,
                                   const VolumeCallOptions& options,
                                   const ProgressCallback& on_progress,
                                   const WarningCallback& on_warning) {
  // Issue 13 part 4: round_robin spreads calls over every address of the target (dns:/// names
  // resolving to several, ipv4:/ipv6: lists) and skips the ones that cannot be reached; with one
  // address it changes nothing.
  grpc::ChannelArguments arguments;
  arguments.SetLoadBalancingPolicyName("round_robin");
  const std::shared_ptr<grpc::Channel> channel =
      grpc::CreateCustomChannel(channel_target(address, std::random_device{}()),
                                options.security.channel_credentials(), arguments);
  const std::unique_ptr<v1::Mesher::Stub> stub = v1::Mesher::NewStub(channel);
  grpc::ClientContext context;
  options.security.add_to(context);
  if (options.timeout_seconds > 0) {
    context.set_deadline(std::chrono::system_clock::now() +
                         std::chrono::duration_cast<std::chrono::system_clock::duration>(
                             std::chrono::duration<double>(options.timeout_seconds)));
  }
  const auto stream = [&] {
    if constexpr (std::is_same_v<Result, SurfaceCallResult>) {
      return stub->MeshSurface(&context);
    } else {
      return stub->MeshVolume(&context);
    }
  }();
  if (options.canceller != nullptr) options.canceller->attach(&context);
  absl::StatusOr<Result> result =
      run_call<Result>(*stream, front, options, on_progress, on_warning);
  if (options.canceller != nullptr) options.canceller->attach(nullptr);
  if (!result.ok()) {
    const auto& trailers = context.GetServerTrailingMetadata();
    absl::Status status = result.status();
    if (const auto hint = trailers.find(kRetryAfterKey); hint != trailers.end()) {
      status.SetPayload(kRetryAfterPayload,
                        absl::Cord(std::string(hint->second.data(), hint->second.size())));
    }
    if (trailers.find(wire::kFinalStatusKey) == trailers.end()) {
      status.SetPayload(kCutOnTheWayPayload, absl::Cord(std::string("1")));
    }
    return status;
  }
  return result;
}

}  // namespace

absl::StatusOr<VolumeCallResult> call_mesh_volume(const std::string& address, const Mesh& front,
                                                  const VolumeCallOptions& options,
                                                  const ProgressCallback& on_progress,
                                                  const WarningCallback& on_warning) {
  return call_mesher<VolumeCallResult>(address, front, options, on_progress, on_warning);
}

absl::StatusOr<SurfaceCallResult> call_mesh_surface(const std::string& address,
                                                    const Mesh& input,
                                                    const VolumeCallOptions& options,
                                                    const ProgressCallback& on_progress,
                                                    const WarningCallback& on_warning) {
  return call_mesher<SurfaceCallResult>(address, input, options, on_progress, on_warning);
}

std::string channel_target(const std::string& address, std::uint64_t seed) {
  const bool bare_list = address.find(',') != std::string::npos &&
                         !absl::StartsWith(address, "ipv4:") && !absl::StartsWith(address, "ipv6:");
  if (!bare_list) return address;
  // gRPC 1.51's round_robin starts every new channel at the first address, and each afmesh
  // command is a new channel: shuffled, the list spreads commands too, not only the calls of one.
  std::vector<std::string> addresses = absl::StrSplit(address, ',', absl::SkipEmpty());
  std::mt19937_64 random(seed);
  std::shuffle(addresses.begin(), addresses.end(), random);
  return "ipv4:" + absl::StrJoin(addresses, ",");
}

bool cut_on_the_way(const absl::Status& status) {
  return status.GetPayload(kCutOnTheWayPayload).has_value();
}

bool worth_retrying(const absl::Status& status, bool shared_server) {
  if (retry_after(status)) return true;
  if (!shared_server) return false;
  switch (status.code()) {
    case absl::StatusCode::kUnavailable:
      return true;
    case absl::StatusCode::kInternal:
    case absl::StatusCode::kUnknown:
      return cut_on_the_way(status);
    default:
      return false;
  }
}

std::optional<std::chrono::milliseconds> retry_after(const absl::Status& status) {
  const auto payload = status.GetPayload(kRetryAfterPayload);  // absl::optional<absl::Cord>
  int ms = 0;
  if (!payload || !absl::SimpleAtoi(std::string(*payload), &ms) || ms < 0) return std::nullopt;
  return std::chrono::milliseconds(ms);
}

}  // namespace afmesh::cli
