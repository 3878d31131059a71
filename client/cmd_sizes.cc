// afmesh sizes --spec SPEC.json [--points FILE]
// Probes a size specification: reads `x y z` per line from FILE (stdin when omitted) and prints
// the size at each point, one per line, in input order, with full double precision (%.17g).
// Blank lines are skipped. Computed locally with core's SpecSizeField over the probe points'
// bounding box: no server is involved. A background grid file named by the specification is read
// as for `afmesh volume` (client/spec_file.h); notes about it go to stderr.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "absl/strings/string_view.h"
#include "client/commands.h"
#include "client/spec_file.h"
#include "core/sizing/spec_size_field.h"
#include "core/spatial/box.h"

namespace afmesh::cli {
namespace {

struct SizesCommandOptions {
  std::string spec_path;
  std::string points_path;  // empty: stdin
};

void print_error(const absl::Status& status) {
  std::fprintf(stderr, "afmesh sizes: %s\n", std::string(status.message()).c_str());
}

// The point on `line` (three finite numbers), or nullopt for a blank line. `source` and
// `line_number` (1-based) name the line in errors.
absl::StatusOr<std::optional<Point>> parse_point_line(absl::string_view line,
                                                      const std::string& source,
                                                      int line_number) {
  const std::vector<absl::string_view> words =
      absl::StrSplit(line, absl::ByAnyChar(" \t\r"), absl::SkipEmpty());
  if (words.empty()) return std::nullopt;
  Point p;
  bool parsed = words.size() == 3;
  for (std::size_t k = 0; parsed && k < 3; ++k) {
    parsed = absl::SimpleAtod(words[k], &p[k]) && std::isfinite(p[k]);
  }
  if (!parsed) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s:%d: expected three finite numbers `x y z`, got \"%s\"", source, line_number, line));
  }
  return p;
}

// The probe points of `in`, in order.
absl::StatusOr<std::vector<Point>> read_points(std::istream& in, const std::string& source) {
  std::vector<Point> points;
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    absl::StatusOr<std::optional<Point>> p = parse_point_line(line, source, line_number);
    if (!p.ok()) return p.status();
    if (p->has_value()) points.push_back(**p);
  }
  if (in.bad()) return absl::InvalidArgumentError(absl::StrCat(source, ": read error"));
  return points;
}

absl::StatusOr<std::vector<Point>> read_probe_points(const SizesCommandOptions& options) {
  if (options.points_path.empty()) return read_points(std::cin, "<stdin>");
  std::ifstream in(options.points_path);
  if (!in) {
    return absl::InvalidArgumentError(absl::StrCat(options.points_path, ": cannot open"));
  }
  return read_points(in, options.points_path);
}

// The bounding box of `points` (not empty).
Box bounding_box(const std::vector<Point>& points) {
  Box box = empty_box();
  for (const Point& p : points) enclose(box, p);
  return box;
}

int run_sizes(const SizesCommandOptions& options) {
  ReadReport report;
  absl::StatusOr<SizeSpec> spec = read_size_spec_file(options.spec_path, &report);
  for (const std::string& note : report.notes) {
    std::fprintf(stderr, "afmesh sizes: note: %s\n", note.c_str());
  }
  if (spec.ok()) {
    if (absl::Status status = validate_size_spec(*spec); !status.ok()) {
      spec = absl::InvalidArgumentError(
          absl::StrFormat("%s: %s", options.spec_path, status.message()));
    }
  }
  if (!spec.ok()) {
    print_error(spec.status());
    return kExitBadInput;
  }
  absl::StatusOr<std::vector<Point>> points = read_probe_points(options);
  if (!points.ok()) {
    print_error(points.status());
    return kExitBadInput;
  }
  if (points->empty()) return kExitOk;
  absl::StatusOr<SpecSizeField> field = SpecSizeField::create(*spec, bounding_box(*points));
  if (!field.ok()) {
    print_error(field.status());
    return kExitBadInput;
  }
  std::vector<double> sizes(points->size());
  field->sizes_at(*points, sizes);
  for (const double size : sizes) std::printf("%.17g\n", size);
  return std::fflush(stdout) == 0 ? kExitOk : kExitInternal;
}

}  // namespace

void add_sizes_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<SizesCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "sizes", "print the size a specification asks for at given points, one per line");
  command->add_option("--spec", options->spec_path, "size specification (JSON, design.md)")
      ->required();
  command->add_option("--points", options->points_path,
                      "points to probe, `x y z` per line (default: stdin)");
  command->callback([options, &action] { action = [options] { return run_sizes(*options); }; });
}

}  // namespace afmesh::cli
