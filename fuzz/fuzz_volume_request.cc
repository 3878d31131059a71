// The input side of a MeshVolume call as the service runs it (server/streaming_call.h): each
// client message goes through VolumeInput::add, then VolumeInput::finish at half-close, then
// the job's first steps on the assembled front: repair_front and validate_front.
//
// Input: up to 32 messages, each a 2-byte little-endian length and that many bytes of a
// serialized afmesh.v1.MeshVolumeRequest (a message that protobuf refuses to parse ends the
// stream, as a broken read would). The server's limits are small here so that the checks, not
// the allocations, take the time.
#include <cstddef>
#include <cstdint>

#include "afmesh/v1/mesher.pb.h"
#include "core/volume/generate_volume_mesh.h"
#include "core/volume/repair_front.h"
#include "fuzz/fuzz_support.h"
#include "server/volume_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const afmesh::server::InputLimits limits{
      .max_points = 512, .max_triangles = 1024, .max_grid_points = 512, .max_grid_tets = 1024};
  afmesh::server::VolumeInput input(limits);
  std::size_t at = 0;
  for (int message = 0; message < 32 && at + 2 <= size; ++message) {
    const std::size_t length = data[at] | (std::size_t{data[at + 1]} << 8);
    at += 2;
    if (length > size - at) return 0;
    afmesh::v1::MeshVolumeRequest request;
    if (!request.ParseFromArray(data + at, static_cast<int>(length))) return 0;
    at += length;
    if (!input.add(request).ok()) return 0;
  }
  if (!input.finish().ok()) return 0;
  afmesh::Mesh front = input.take_front();
  afmesh::fuzz::require_usable(front, "VolumeInput::finish");
  afmesh::repair_front(front);
  (void)afmesh::validate_front(front);
  return 0;
}
