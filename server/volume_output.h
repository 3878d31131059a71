// Turns a finished job's output into the server stream of a MeshVolume call: warnings, then the
// mesh as point, triangle and tet slices of at most wire::kMaxSliceItems items
// (proto/slice_codec.h), then the Summary, one message at a time so that a large mesh is never
// copied whole into messages.
#pragma once

#include <chrono>
#include <cstddef>
#include <optional>
#include <vector>

#include "absl/status/status.h"
#include "afmesh/v1/mesher.pb.h"
#include "server/volume_job.h"

namespace afmesh::server {

// Checks that a job's mesh can be sent as a whole: tag arrays as long as their elements and
// every triangle and tet index in range. INTERNAL naming the element otherwise (a job bug: the
// service sends no part of such a mesh).
absl::Status check_mesh_output(const Mesh& mesh);
absl::Status check_job_output(const VolumeJobOutput& output);

class VolumeOutputStream {
 public:
  // `timings_before`: the stages of the call that ran before the job (e.g. "receive", "queue");
  // the Summary lists them, then the job's, then "send" (from the first next() to the Summary).
  VolumeOutputStream(VolumeJobOutput output, std::vector<StageTiming> timings_before);

  // Fills `response` with the next message; false once the Summary has been produced.
  bool next(v1::MeshVolumeResponse& response);

  // The Summary's timings: `timings_before`, the job's, then "send" (up to now).
  std::vector<StageTiming> timings() const;

  // The mesh the stream carries.
  const Mesh& mesh() const { return output_.volume.mesh; }

 private:
  enum class Part { kWarnings, kPoints, kTriangles, kTets, kSummary, kDone };

  void next_points(v1::PointSlice& slice);
  void next_triangles(v1::TriangleSlice& slice);
  void next_tets(v1::TetSlice& slice);
  void fill_summary(v1::Summary& summary) const;
  // Moves to the following part once `offset_` has passed `size` items of the current one.
  void advance_if_done(std::size_t size);

  VolumeJobOutput output_;
  std::vector<StageTiming> timings_before_;
  Part part_ = Part::kWarnings;
  std::size_t offset_ = 0;  // items of the current part already sent
  std::optional<std::chrono::steady_clock::time_point> send_start_;
};

}  // namespace afmesh::server
