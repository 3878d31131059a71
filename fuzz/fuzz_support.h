// Shared by the fuzz targets: the oracle every reader's result must pass, and a Progress that
// bounds the work of one input deterministically.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string_view>

#include "core/common/progress.h"
#include "core/io/mesh_checks.h"
#include "core/mesh/mesh.h"

namespace afmesh::fuzz {

// The bytes libFuzzer hands over, as the string_view the readers take.
inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// A reader that says OK must hand out a mesh the rest of afmesh can use: indices in range, tag
// arrays as long as their element arrays, finite coordinates (what every writer checks first).
// Anything else is a bug in the reader, reported as a crash so that libFuzzer keeps the input.
inline void require_usable(const Mesh& mesh, const char* reader) {
  const absl::Status status = check_mesh_for_writing(mesh);
  if (!status.ok()) {
    std::fprintf(stderr, "%s said OK but the mesh is unusable: %s\n", reader,
                 std::string(status.message()).c_str());
    std::abort();
  }
}

// Cancels after `budget` polls of cancelled(): one input's meshing stops after a fixed amount
// of work (the core polls every few thousand elements at most), the same on every run, so a
// slow input shows up as a timeout only when the polling itself is missing.
class BudgetProgress final : public Progress {
 public:
  explicit BudgetProgress(std::int64_t budget) : left_(budget) {}
  bool cancelled() const override { return --left_ < 0; }

 private:
  mutable std::int64_t left_;
};

}  // namespace afmesh::fuzz
