#include "client/interrupt_watcher.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <thread>

namespace afmesh::cli {

struct InterruptWatcher::State {
  std::function<void()> on_interrupt;
  std::atomic<int> signal{0};
};

InterruptWatcher::InterruptWatcher(std::function<void()> on_interrupt)
    : state_(std::make_shared<State>()) {
  state_->on_interrupt = std::move(on_interrupt);
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  // Detached: it waits for a signal for as long as the process lives.
  std::thread([state = state_, signals] {
    int received = 0;
    while (sigwait(&signals, &received) != 0) {
    }
    state->signal.store(received);
    state->on_interrupt();
    while (sigwait(&signals, &received) != 0) {
    }
    _exit(128 + received);
  }).detach();
}

int InterruptWatcher::signal() const { return state_->signal.load(); }

}  // namespace afmesh::cli
