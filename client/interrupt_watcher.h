// Ctrl-C (SIGINT) and SIGTERM for a command that holds resources: instead of dying on the spot
// (leaving a private server's folder behind), the command cancels its call and cleans up.
#pragma once

#include <functional>
#include <memory>

namespace afmesh::cli {

class InterruptWatcher {
 public:
  // Blocks SIGINT and SIGTERM in the calling thread, and so in every thread it starts later
  // (construct it before any other thread exists), and waits for them on a thread of its own.
  // The first signal runs `on_interrupt` on that thread; a second one ends the process at once
  // with status 128 + signal.
  explicit InterruptWatcher(std::function<void()> on_interrupt);

  // The first signal received, or 0.
  int signal() const;

 private:
  struct State;
  std::shared_ptr<State> state_;  // shared with the watching thread, which outlives this object
};

}  // namespace afmesh::cli
