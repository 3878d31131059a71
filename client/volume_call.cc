#include "client/volume_call.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "absl/strings/cord.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "afmesh/v1/mesher.grpc.pb.h"
#include "google/protobuf/util/json_util.h"
#include "grpcpp/grpcpp.h"
#include "proto/call_metadata.h"
#include "proto/size_spec_convert.h"

namespace afmesh::cli {
namespace {

// The server's retry hint (server/mesher_service.cc) and where it travels in an absl::Status.
using wire::kRetryAfterKey;
constexpr char kRetryAfterPayload[] = "type.afmesh.dev/retry-after-ms";
constexpr char kCutOnTheWayPayload[] = "type.afmesh.dev/cut-on-the-way";

using Request = v1::MeshVolumeRequest;
using Response = v1::MeshVolumeResponse;
using Stream = grpc::ClientReaderWriter<Request, Response>;

// Points or triangles per request slice: 32768 points are 768 KiB, well under gRPC's 4 MiB.
constexpr std::size_t kSliceItems = 32768;

Request header_request(const Mesh& front, const VolumeCallOptions& options) {
  Request request;
  v1::MeshVolumeHeader& header = *request.mutable_header();
  if (options.spec) {
    *header.mutable_options()->mutable_size() = size_spec_to_proto(*options.spec);
    // The background grid, whatever its size, follows in slices (grid_requests).
    header.mutable_options()->mutable_size()->clear_background();
    if (options.spec->background) {
      header.set_grid_point_count(options.spec->background->points.size());
      header.set_grid_tet_count(options.spec->background->tets.size());
    }
  } else {
    header.mutable_options()->mutable_size()->set_max_size(options.size);
    header.mutable_options()->mutable_size()->set_growth(options.growth);
  }
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
  header.set_point_count(front.points.size());
  header.set_triangle_count(front.triangles.size());
  return request;
}

Request points_request(const Mesh& front, std::size_t begin, std::size_t end) {
  Request request;
  auto& xyz = *request.mutable_points()->mutable_xyz();
  xyz.Reserve(static_cast<int>(3 * (end - begin)));
  for (std::size_t p = begin; p < end; ++p) {
    for (const double c : front.points[p]) xyz.Add(c);
  }
  return request;
}

Request triangles_request(const Mesh& front, std::size_t begin, std::size_t end) {
  Request request;
  v1::TriangleSlice& slice = *request.mutable_triangles();
  slice.mutable_indices()->Reserve(static_cast<int>(3 * (end - begin)));
  slice.mutable_tags()->Reserve(static_cast<int>(end - begin));
  for (std::size_t t = begin; t < end; ++t) {
    for (const Index i : front.triangles[t]) slice.add_indices(i);
    slice.add_tags(t < front.triangle_tags.size() ? front.triangle_tags[t] : 0);
  }
  return request;
}

// Streams the background grid in slices, each of one kind (points, sizes or tets) and at most
// kSliceItems of it: under 1 MiB each, built one at a time. False once a write fails.
bool send_grid(Stream& stream, const BackgroundGridSpec& grid) {
  bool open = true;
  for (std::size_t begin = 0; open && begin < grid.points.size(); begin += kSliceItems) {
    const std::size_t end = std::min(grid.points.size(), begin + kSliceItems);
    Request request;
    auto& xyz = *request.mutable_background_grid()->mutable_xyz();
    xyz.Reserve(static_cast<int>(3 * (end - begin)));
    for (std::size_t p = begin; p < end; ++p) {
      for (const double c : grid.points[p]) xyz.Add(c);
    }
    open = stream.Write(request);
  }
  for (std::size_t begin = 0; open && begin < grid.sizes.size(); begin += kSliceItems) {
    const std::size_t end = std::min(grid.sizes.size(), begin + kSliceItems);
    Request request;
    request.mutable_background_grid()->mutable_sizes()->Add(
        grid.sizes.begin() + static_cast<std::ptrdiff_t>(begin),
        grid.sizes.begin() + static_cast<std::ptrdiff_t>(end));
    open = stream.Write(request);
  }
  for (std::size_t begin = 0; open && begin < grid.tets.size(); begin += kSliceItems) {
    const std::size_t end = std::min(grid.tets.size(), begin + kSliceItems);
    Request request;
    auto& tets = *request.mutable_background_grid()->mutable_tets();
    tets.Reserve(static_cast<int>(4 * (end - begin)));
    for (std::size_t t = begin; t < end; ++t) {
      for (const Index i : grid.tets[t]) tets.Add(i);
    }
    open = stream.Write(request);
  }
  return open;
}

// Header, background grid slices, point slices, triangle slices, half-close. Stops early when a
// write fails: the server ended the call, and Finish() says why.
void send_front(Stream& stream, const Mesh& front, const VolumeCallOptions& options,
                const ProgressCallback& on_progress) {
  const double total = static_cast<double>(front.points.size() + front.triangles.size());
  bool open = stream.Write(header_request(front, options));
  if (open && options.spec && options.spec->background) {
    open = send_grid(stream, *options.spec->background);
  }
  for (std::size_t begin = 0; open && begin < front.points.size(); begin += kSliceItems) {
    const std::size_t end = std::min(front.points.size(), begin + kSliceItems);
    open = stream.Write(points_request(front, begin, end));
    on_progress("send", static_cast<double>(end) / total);
  }
  for (std::size_t begin = 0; open && begin < front.triangles.size(); begin += kSliceItems) {
    const std::size_t end = std::min(front.triangles.size(), begin + kSliceItems);
    open = stream.Write(triangles_request(front, begin, end));
    on_progress("send", static_cast<double>(front.points.size() + end) / total);
  }
  stream.WritesDone();
}

// Appends the mesh slice carried by `response` to `mesh`.
void append_slice(const Response& response, Mesh& mesh) {
  if (response.has_points()) {
    const auto& xyz = response.points().xyz();
    for (int i = 0; i + 2 < xyz.size(); i += 3) {
      mesh.points.push_back({xyz[i], xyz[i + 1], xyz[i + 2]});
    }
  } else if (response.has_triangles()) {
    const auto& indices = response.triangles().indices();
    for (int i = 0; i + 2 < indices.size(); i += 3) {
      mesh.triangles.push_back({indices[i], indices[i + 1], indices[i + 2]});
    }
    mesh.triangle_tags.insert(mesh.triangle_tags.end(), response.triangles().tags().begin(),
                              response.triangles().tags().end());
  } else if (response.has_tets()) {
    const auto& indices = response.tets().indices();
    for (int i = 0; i + 3 < indices.size(); i += 4) {
      mesh.tets.push_back({indices[i], indices[i + 1], indices[i + 2], indices[i + 3]});
    }
    mesh.tet_tags.insert(mesh.tet_tags.end(), response.tets().tags().begin(),
                         response.tets().tags().end());
  }
}

// DATA_LOSS unless the slices received add up to the counts the Summary announces.
absl::Status check_whole(const Mesh& mesh, const v1::Summary& summary) {
  if (mesh.points.size() != summary.point_count() ||
      mesh.triangles.size() != summary.triangle_count() ||
      mesh.tets.size() != summary.tet_count() ||
      mesh.triangle_tags.size() != mesh.triangles.size() ||
      mesh.tet_tags.size() != mesh.tets.size()) {
    return absl::DataLossError(absl::StrFormat(
        "the server's mesh is incomplete: received %d points, %d triangles (%d tags), %d tets "
        "(%d tags); its summary announces %d, %d and %d",
        mesh.points.size(), mesh.triangles.size(), mesh.triangle_tags.size(), mesh.tets.size(),
        mesh.tet_tags.size(), summary.point_count(), summary.triangle_count(),
        summary.tet_count()));
  }
  return absl::OkStatus();
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
  plain.validation_passed = summary.validation().passed();
  plain.validation_messages.assign(summary.validation().messages().begin(),
                                   summary.validation().messages().end());
  for (const v1::StageTiming& timing : summary.timings()) {
    plain.timings.emplace_back(timing.stage(), timing.seconds());
  }
  google::protobuf::util::JsonPrintOptions json_options;
  json_options.add_whitespace = true;
  json_options.always_print_primitive_fields = true;
  (void)google::protobuf::util::MessageToJsonString(summary, &plain.json, json_options);
  return plain;
}

// Sends the front and collects the answer (see call_mesh_volume).
absl::StatusOr<VolumeCallResult> run_call(Stream& stream, const Mesh& front,
                                          const VolumeCallOptions& options,
                                          const ProgressCallback& on_progress,
                                          const WarningCallback& on_warning) {
  send_front(stream, front, options, on_progress);

  VolumeCallResult result;
  std::optional<v1::Summary> summary;
  Response response;
  while (stream.Read(&response)) {
    if (response.has_progress()) {
      on_progress(response.progress().stage(), response.progress().fraction());
    } else if (response.has_warning()) {
      on_warning(response.warning().message());
    } else if (response.has_summary()) {
      summary = response.summary();
    } else {
      append_slice(response, result.mesh);
      on_progress("receive", -1.0);
    }
  }
  const grpc::Status status = stream.Finish();
  if (!status.ok()) {
    return absl::Status(static_cast<absl::StatusCode>(status.error_code()), status.error_message());
  }
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

absl::StatusOr<VolumeCallResult> call_mesh_volume(const std::string& address, const Mesh& front,
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
  const std::unique_ptr<Stream> stream = stub->MeshVolume(&context);
  if (options.canceller != nullptr) options.canceller->attach(&context);
  absl::StatusOr<VolumeCallResult> result =
      run_call(*stream, front, options, on_progress, on_warning);
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
