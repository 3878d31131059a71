// What a mesh reader passed over while reading a file.
//
// Readers never drop data silently: anything in a file that does not become part of the Mesh
// (gmsh point and line elements, Medit edges and corners, vertex references, OBJ normals, ...)
// is either an error or described by one human-readable note here.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace afmesh {

struct ReadReport {
  // One sentence per kind of skipped content, in the order met, e.g.
  // "skipped 12 line elements (gmsh type 1)".
  std::vector<std::string> notes;
};

// Appends `note` to `report->notes` when `report` is not null.
inline void add_note(ReadReport* report, std::string note) {
  if (report != nullptr) report->notes.push_back(std::move(note));
}

}  // namespace afmesh
