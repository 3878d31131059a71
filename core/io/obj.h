// Wavefront OBJ reading and writing (triangle surfaces).
//
// Reading
//  - `v x y z [w | r g b]`: a point (extra numbers are checked and ignored).
//  - `f a b c`: a triangle; each corner may be written `v`, `v/vt`, `v//vn` or `v/vt/vn`, and
//    negative indices count back from the last point defined (-1 is the latest). Indices must
//    refer to points defined before the face. Faces with more than 3 corners are an error
//    naming the line: fanning a polygon is only right when it is convex and planar, which the
//    reader cannot promise, so triangulate before export.
//  - Tags travel as groups: `g name` or `o name` puts the following faces in group `name`
//    (the latest of either wins; a bare `g` ends grouping, tag 0). When every group name is
//    `tag_<n>`, the faces get tag n; otherwise the groups are numbered 1, 2, ... in order of
//    first appearance (a note lists the mapping). Faces before any group get tag 0.
//  - `vn`, `vt`, `vp`, `s`, `mtllib`, `usemtl` are ignored and `l`, `p` elements skipped, with
//    a note counting them; any other statement (free-form curves and surfaces, ...) is an
//    error, since it would carry geometry the mesh would lose. `#` starts a comment.
//
// Writing: `v` lines with shortest round-trip doubles, then the faces with one `g tag_<n>` line
// before each run of consecutive triangles with equal tag n. A mesh with tetrahedra is refused.
#pragma once

#include <string_view>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/io/output_buffer.h"
#include "core/io/read_report.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// The mesh in the OBJ text `text`; `source_name` starts error messages.
absl::StatusOr<Mesh> parse_obj(std::string_view text, std::string_view source_name,
                               ReadReport* report = nullptr);

// Writes `mesh` (points N×3, triangles M×3 with tags) as OBJ to `out` and flushes it.
absl::Status write_obj(const Mesh& mesh, OutputBuffer& out);

}  // namespace afmesh
