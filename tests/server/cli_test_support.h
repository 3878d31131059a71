// What the tests that run the afmesh and afmesh-server binaries share: the tiny
// front they mesh, shell quoting, reading a file back, and a server process
// started and stopped around a test.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

namespace afmesh::cli_test {

// The boundary of the unit corner tetrahedron, outward-oriented, as a Medit
// file (tag 7).
inline constexpr const char* kTetrahedronFront = R"(MeshVersionFormatted 2
Dimension 3
Vertices
4
0 0 0 0
1 0 0 0
0 1 0 0
0 0 1 0
Triangles
4
1 3 2 7
1 2 4 7
1 4 3 7
2 3 4 7
End
)";

// `path` in single quotes, for the shell.
inline std::string shell_quoted(const std::filesystem::path& path) {
  std::string text(1, '\'');
  text.append(path.string()).push_back('\'');
  return text;
}

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The exit code of a std::system() or waitpid() status; -1 when killed by a
// signal.
inline int exit_status(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : -1; }

// Starts the afmesh-server at `binary` with `args`, its stderr to `log` when
// given; returns its pid (negative when fork failed).
inline pid_t start_server_process(const std::string& binary, const std::vector<std::string>& args,
                                  const std::filesystem::path& log = {}) {
  const pid_t pid = fork();
  if (pid != 0) return pid;
  if (!log.empty() && freopen(log.c_str(), "w", stderr) == nullptr) _exit(126);
  std::vector<std::string> copies = {binary};
  copies.insert(copies.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& arg : copies) argv.push_back(arg.data());
  argv.push_back(nullptr);
  execv(binary.c_str(), argv.data());
  _exit(127);
}

// Waits up to 10 s for a unix socket to appear; false if it did not.
inline bool wait_for_socket(const std::filesystem::path& socket) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!std::filesystem::exists(socket)) {
    if (std::chrono::steady_clock::now() >= give_up) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

// SIGTERM, then the exit status (-1 when killed by a signal or not waitable).
inline int stop_server_process(pid_t pid) {
  kill(pid, SIGTERM);
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1;
  return exit_status(status);
}

}  // namespace afmesh::cli_test
