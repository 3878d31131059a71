// Progress of a long command on stderr: a bar redrawn in place on a terminal, plain lines
// otherwise (logs, CI), nothing when quiet.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <string_view>

namespace afmesh::cli {

class ProgressDisplay {
 public:
  enum class Mode { kQuiet, kBar, kLines };

  // kBar when `out` is a terminal, kLines otherwise; kQuiet when `quiet`.
  static Mode mode_for(std::FILE* out, bool quiet);

  ProgressDisplay(std::FILE* out, Mode mode) : out_(out), mode_(mode) {}
  // Ends the bar's line.
  ~ProgressDisplay() { finish(); }
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

  // `stage` at `fraction` in [0, 1] (negative: unknown). Bar: redrawn at most every 50 ms and
  // on a new stage. Lines: one on a new stage and one per 10% step.
  void update(std::string_view stage, double fraction);

  // Ends the bar's line so that later output starts on a fresh one.
  void finish();

 private:
  void draw_bar(double fraction);
  void print_line(double fraction);

  std::FILE* out_;
  Mode mode_;
  std::string stage_;
  int last_decile_ = -1;
  bool bar_open_ = false;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace afmesh::cli
