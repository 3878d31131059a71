#include "core/io/obj.h"

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_join.h"
#include "core/io/mesh_checks.h"
#include "core/io/return_if_error.h"
#include "core/io/string_util.h"
#include "core/io/text_scanner.h"

namespace afmesh {
namespace {

constexpr std::int64_t kMaxPoints = std::numeric_limits<Index>::max();

// Statements read and dropped: attributes the mesh has no place for, and point/line elements.
constexpr std::array<std::string_view, 8> kIgnoredStatements = {"vn",     "vt",     "vp", "s",
                                                                "mtllib", "usemtl", "l",  "p"};

// The n of a group named "tag_<n>", if it is one.
bool parse_tag_name(std::string_view name, Index& tag) {
  std::int64_t value = 0;
  if (!name.starts_with("tag_") || !parse_int(name.substr(4), value)) return false;
  if (value < std::numeric_limits<Index>::min() || value > std::numeric_limits<Index>::max()) {
    return false;
  }
  tag = static_cast<Index>(value);
  return true;
}

class ObjParser {
 public:
  ObjParser(std::string_view text, std::string_view source_name)
      : scanner_(text, source_name, '#') {}

  absl::StatusOr<Mesh> parse(ReadReport* report) {
    if (scanner_.at_end()) {
      return absl::InvalidArgumentError(
          str_cat(scanner_.source_name(), ": the file is empty (no OBJ statements)"));
    }
    while (!scanner_.at_end()) {
      AFMESH_RETURN_IF_ERROR(parse_statement(scanner_.next_token()));
    }
    assign_group_tags(report);
    note_ignored(report);
    return std::move(mesh_);
  }

 private:
  absl::Status parse_statement(std::string_view keyword) {
    if (keyword == "v") return parse_point();
    if (keyword == "f") return parse_face();
    if (keyword == "g" || keyword == "o") {
      start_group(scanner_.rest_of_line());
      return absl::OkStatus();
    }
    for (std::size_t i = 0; i < kIgnoredStatements.size(); ++i) {
      if (keyword == kIgnoredStatements[i]) {
        ++ignored_counts_[i];
        scanner_.skip_line();
        return absl::OkStatus();
      }
    }
    return scanner_.error(
        str_cat("unknown OBJ statement '", keyword,
                "' (read: v, f, g, o; ignored: ", "vn, vt, vp, s, mtllib, usemtl, l, p", ")"));
  }

  // `v x y z` with up to 4 further numbers (a weight, or a colour as r g b [a]).
  absl::Status parse_point() {
    if (static_cast<std::int64_t>(mesh_.points.size()) >= kMaxPoints) {
      return scanner_.error(str_cat("more than ", kMaxPoints, " points"));
    }
    Point& point = mesh_.points.emplace_back();
    for (double& coordinate : point) {
      if (scanner_.at_line_end()) return scanner_.error("a 'v' line needs 3 coordinates");
      AFMESH_RETURN_IF_ERROR(scanner_.read_double(coordinate, "a vertex coordinate"));
    }
    for (int extra = 0; !scanner_.at_line_end(); ++extra) {
      if (extra == 4) {
        return scanner_.unexpected("the end of the 'v' line", scanner_.next_token());
      }
      double ignored = 0;
      AFMESH_RETURN_IF_ERROR(scanner_.read_any_double(ignored, "a vertex weight or colour"));
    }
    return absl::OkStatus();
  }

  // `f a b c`: exactly three corners.
  absl::Status parse_face() {
    Triangle triangle;
    int corners = 0;
    while (!scanner_.at_line_end()) {
      const std::string_view token = scanner_.next_token();
      Index index = kInvalidIndex;
      AFMESH_RETURN_IF_ERROR(parse_corner(token, index));
      if (corners < 3) triangle[corners] = index;
      ++corners;
    }
    if (corners != 3) {
      return scanner_.error(
          corners < 3
              ? str_cat("a face needs 3 corners, found ", corners)
              : str_cat("face with ", corners,
                        " corners: only triangles are supported (triangulate before export)"));
    }
    mesh_.triangles.push_back(triangle);
    mesh_.triangle_tags.push_back(current_group_);
    return absl::OkStatus();
  }

  // One corner `v`, `v/vt`, `v//vn` or `v/vt/vn`, as a 0-based point index.
  absl::Status parse_corner(std::string_view token, Index& index) {
    constexpr std::string_view kForms = "a corner 'v', 'v/vt', 'v//vn' or 'v/vt/vn'";
    const std::size_t slash = token.find('/');
    std::int64_t value = 0;
    if (!parse_int(token.substr(0, slash), value)) return scanner_.unexpected(kForms, token);
    if (slash != std::string_view::npos) {
      const std::string_view rest = token.substr(slash + 1);
      const std::size_t second = rest.find('/');
      std::int64_t attribute = 0;
      const std::string_view texture = rest.substr(0, second);
      const std::string_view normal =
          second == std::string_view::npos ? std::string_view() : rest.substr(second + 1);
      if ((!texture.empty() && !parse_int(texture, attribute)) ||
          (second != std::string_view::npos && !parse_int(normal, attribute))) {
        return scanner_.unexpected(kForms, token);
      }
    }
    const auto defined = static_cast<std::int64_t>(mesh_.points.size());
    const std::int64_t resolved = value > 0 ? value - 1 : defined + value;
    if (value == 0 || resolved < 0 || resolved >= defined) {
      return scanner_.error(str_cat("vertex index ", value, " is out of range: ", defined,
                                    " vertices are defined before this face (indices run "
                                    "from 1, or from -1 backwards)"));
    }
    index = static_cast<Index>(resolved);
    return absl::OkStatus();
  }

  // Faces from here on belong to group `name` (none when it is empty). The group's slot
  // (1-based) is stored as the face tag until assign_group_tags() replaces it.
  void start_group(std::string_view name) {
    if (name.empty()) {
      current_group_ = 0;
      return;
    }
    const auto [it, inserted] =
        slot_of_group_.try_emplace(std::string(name), static_cast<Index>(group_names_.size() + 1));
    if (inserted) group_names_.emplace_back(name);
    current_group_ = it->second;
  }

  // Turns group slots into tags: tag_<n> names give n; otherwise groups are numbered in order
  // of first appearance (slot numbers), and the mapping is noted.
  void assign_group_tags(ReadReport* report) {
    if (group_names_.empty()) return;
    std::vector<bool> used(group_names_.size() + 1, false);
    for (const Index slot : mesh_.triangle_tags) used[slot] = true;
    std::vector<Index> tag_of_slot(group_names_.size() + 1, 0);
    bool all_tag_names = true;
    for (std::size_t slot = 1; slot <= group_names_.size(); ++slot) {
      if (used[slot] && !parse_tag_name(group_names_[slot - 1], tag_of_slot[slot])) {
        all_tag_names = false;
      }
    }
    if (!all_tag_names) {
      std::vector<std::string> mapping;
      for (std::size_t slot = 1; slot <= group_names_.size(); ++slot) {
        tag_of_slot[slot] = static_cast<Index>(slot);
        if (used[slot]) mapping.push_back(str_cat("'", group_names_[slot - 1], "' -> ", slot));
      }
      add_note(report, str_cat("OBJ groups numbered as tags: ", absl::StrJoin(mapping, ", ")));
    }
    for (Index& tag : mesh_.triangle_tags) tag = tag_of_slot[tag];
  }

  void note_ignored(ReadReport* report) const {
    std::vector<std::string> counts;
    for (std::size_t i = 0; i < kIgnoredStatements.size(); ++i) {
      if (ignored_counts_[i] > 0) {
        counts.push_back(str_cat(ignored_counts_[i], " '", kIgnoredStatements[i], "'"));
      }
    }
    if (!counts.empty()) {
      add_note(report, str_cat("ignored OBJ statements: ", absl::StrJoin(counts, ", ")));
    }
  }

  TextScanner scanner_;
  Mesh mesh_;
  Index current_group_ = 0;
  std::vector<std::string> group_names_;
  absl::flat_hash_map<std::string, Index> slot_of_group_;
  std::array<std::int64_t, kIgnoredStatements.size()> ignored_counts_ = {};
};

void write_point(const Point& p, OutputBuffer& out) {
  out.put("v ");
  out.put_double(p[0]);
  out.put(' ');
  out.put_double(p[1]);
  out.put(' ');
  out.put_double(p[2]);
  out.put('\n');
}

}  // namespace

absl::StatusOr<Mesh> parse_obj(std::string_view text, std::string_view source_name,
                               ReadReport* report) {
  return ObjParser(text, source_name).parse(report);
}

absl::Status write_obj(const Mesh& mesh, OutputBuffer& out) {
  AFMESH_RETURN_IF_ERROR(check_mesh_for_writing(mesh));
  AFMESH_RETURN_IF_ERROR(check_triangles_only(mesh, "OBJ"));
  out.put(str_cat("# afmesh OBJ: ", mesh.points.size(), " points, ", mesh.triangles.size(),
                  " triangles; 'g tag_<n>' groups carry triangle tags\n"));
  for (const Point& p : mesh.points) write_point(p, out);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (i == 0 || mesh.triangle_tags[i] != mesh.triangle_tags[i - 1]) {
      out.put("g tag_");
      out.put_int(mesh.triangle_tags[i]);
      out.put('\n');
    }
    out.put('f');
    for (const Index v : mesh.triangles[i]) {
      out.put(' ');
      out.put_int(std::int64_t{v} + 1);
    }
    out.put('\n');
  }
  return out.flush();
}

}  // namespace afmesh
