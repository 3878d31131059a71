#include "client/progress_display.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace afmesh::cli {
namespace {

constexpr int kBarWidth = 30;
constexpr auto kRedrawInterval = std::chrono::milliseconds(50);

}  // namespace

ProgressDisplay::Mode ProgressDisplay::mode_for(std::FILE* out, bool quiet) {
  if (quiet) return Mode::kQuiet;
  return isatty(fileno(out)) ? Mode::kBar : Mode::kLines;
}

void ProgressDisplay::update(std::string_view stage, double fraction) {
  if (mode_ == Mode::kQuiet) return;
  const bool new_stage = stage != stage_;
  if (new_stage) {
    stage_ = std::string(stage);
    last_decile_ = -1;
  }
  if (mode_ == Mode::kBar) {
    const auto now = std::chrono::steady_clock::now();
    if (!new_stage && fraction < 1.0 && now - last_draw_ < kRedrawInterval) return;
    last_draw_ = now;
    draw_bar(fraction);
    return;
  }
  const int decile = fraction < 0 ? -1 : static_cast<int>(std::floor(10 * std::min(fraction, 1.0)));
  if (!new_stage && decile <= last_decile_) return;
  last_decile_ = decile;
  print_line(fraction);
}

void ProgressDisplay::finish() {
  if (bar_open_) {
    std::fputc('\n', out_);
    std::fflush(out_);
    bar_open_ = false;
  }
}

// "\r  front     [###########...................]  37%" then erase to the end of the line.
void ProgressDisplay::draw_bar(double fraction) {
  if (fraction < 0) {
    std::fprintf(out_, "\r  %-10s working...\x1b[K", stage_.c_str());
  } else {
    const double clamped = std::clamp(fraction, 0.0, 1.0);
    const int filled = static_cast<int>(std::lround(clamped * kBarWidth));
    std::fprintf(out_, "\r  %-10s [%s%s] %3d%%\x1b[K", stage_.c_str(),
                 std::string(filled, '#').c_str(), std::string(kBarWidth - filled, '.').c_str(),
                 static_cast<int>(std::lround(100 * clamped)));
  }
  std::fflush(out_);
  bar_open_ = true;
}

void ProgressDisplay::print_line(double fraction) {
  if (fraction < 0) {
    std::fprintf(out_, "afmesh: %s\n", stage_.c_str());
  } else {
    std::fprintf(out_, "afmesh: %s %d%%\n", stage_.c_str(),
                 static_cast<int>(std::lround(100 * std::clamp(fraction, 0.0, 1.0))));
  }
  std::fflush(out_);
}

}  // namespace afmesh::cli
