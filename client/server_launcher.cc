#include "client/server_launcher.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "grpcpp/grpcpp.h"

namespace afmesh::cli {
namespace {

using Clock = std::chrono::steady_clock;

constexpr auto kStartTimeout = std::chrono::seconds(10);
constexpr auto kStopTimeout = std::chrono::seconds(10);
constexpr auto kPollInterval = std::chrono::milliseconds(5);
constexpr auto kSocketPollInterval = std::chrono::milliseconds(1);
// The server's socket in its folder.
constexpr char kSocketName[] = "mesher.sock";
// Longest unix socket path (sockaddr_un::sun_path holds 108 bytes with the terminating NUL).
constexpr std::size_t kMaxSocketPath = 107;
// The private server takes any input the machine can hold: indices are int32.
constexpr const char* kNoLimit = "2147483647";

absl::Status unavailable(const std::string& what) {
  return absl::UnavailableError(absl::StrCat("cannot start a private afmesh-server: ", what));
}

// afmesh-server in the folder of the running afmesh binary.
absl::StatusOr<std::string> server_binary() {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return unavailable(absl::StrCat("/proc/self/exe: ", error.message()));
  const std::filesystem::path server = self.parent_path() / "afmesh-server";
  if (access(server.c_str(), X_OK) != 0) {
    return unavailable(absl::StrCat("no executable ", server.string(),
                                    " beside afmesh; install it there or pass --server ADDR"));
  }
  return server.string();
}

// A fresh private folder under $TMPDIR (or /tmp when that path is too long for a socket).
absl::StatusOr<std::string> make_private_dir() {
  const char* tmpdir = std::getenv("TMPDIR");
  std::string base = tmpdir != nullptr && *tmpdir != '\0' ? tmpdir : "/tmp";
  if (base.size() + 32 > kMaxSocketPath) base = "/tmp";
  std::string pattern = base + "/afmesh-XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) {
    return unavailable(absl::StrCat("mkdtemp ", pattern, ": ", std::strerror(errno)));
  }
  return pattern;
}

// Reconnects quickly while the server is still starting (gRPC's default first backoff is 1 s).
std::shared_ptr<grpc::Channel> eager_channel(const std::string& address) {
  grpc::ChannelArguments arguments;
  arguments.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, 10);
  arguments.SetInt(GRPC_ARG_MIN_RECONNECT_BACKOFF_MS, 10);
  arguments.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 100);
  return grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), arguments);
}

// Waits up to `timeout` for child `pid` to exit; true when it did (and was reaped).
bool wait_for_exit(pid_t pid, std::chrono::milliseconds timeout, int* wait_status) {
  const Clock::time_point give_up = Clock::now() + timeout;
  for (;;) {
    const pid_t done = waitpid(pid, wait_status, WNOHANG);
    if (done == pid || (done < 0 && errno != EINTR)) return true;
    if (Clock::now() >= give_up) return false;
    std::this_thread::sleep_for(kPollInterval);
  }
}

std::string describe_exit(int wait_status) {
  if (WIFEXITED(wait_status)) return absl::StrCat("exit status ", WEXITSTATUS(wait_status));
  if (WIFSIGNALED(wait_status)) return absl::StrCat("signal ", WTERMSIG(wait_status));
  return "unknown status";
}

}  // namespace

absl::StatusOr<std::unique_ptr<PrivateServer>> PrivateServer::start() {
  absl::StatusOr<std::string> binary = server_binary();
  if (!binary.ok()) return binary.status();
  std::unique_ptr<PrivateServer> server(new PrivateServer());
  absl::StatusOr<std::string> dir = make_private_dir();
  if (!dir.ok()) return dir.status();
  server->dir_ = *dir;
  server->address_ = absl::StrCat("unix:", server->dir_, "/", kSocketName);
  server->log_path_ = server->dir_ + "/server.log";
  if (absl::Status status = server->spawn(*binary); !status.ok()) return status;
  if (absl::Status status = server->wait_until_serving(); !status.ok()) return status;
  return server;
}

PrivateServer::~PrivateServer() { stop(); }

// fork + exec, so that the child can ask to die with its parent before it runs the server.
absl::Status PrivateServer::spawn(const std::string& binary) {
  // No grace period: the server is stopped only once the command's one call has ended and its
  // result has been read (or the call was cancelled), so nothing is left to drain or to read,
  // and the drain's grace would only delay the command's exit (by 200 ms).
  std::vector<std::string> args = {binary,   "--listen",        address_, "--workers",
                                   "1",      "--max-queue",     "0",      "--max-points",
                                   kNoLimit, "--max-triangles", kNoLimit,    "--max-grid-points",
                                   kNoLimit, "--max-grid-tets", kNoLimit,    "--grace-period",
                                   "0"};
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);

  const int log = open(log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (log < 0) return unavailable(absl::StrCat(log_path_, ": ", std::strerror(errno)));
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    // In the child only async-signal-safe calls until exec.
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(127);
    const int null = open("/dev/null", O_RDONLY);
    if (null >= 0) dup2(null, STDIN_FILENO);
    dup2(log, STDOUT_FILENO);
    dup2(log, STDERR_FILENO);
    execv(argv[0], argv.data());
    _exit(127);
  }
  const int fork_errno = errno;
  close(log);
  if (pid < 0) return unavailable(absl::StrCat("fork: ", std::strerror(fork_errno)));
  pid_ = pid;
  return absl::OkStatus();
}

absl::Status PrivateServer::wait_until_serving() {
  const std::shared_ptr<grpc::Channel> channel = eager_channel(address_);
  const std::unique_ptr<grpc::health::v1::Health::Stub> health =
      grpc::health::v1::Health::NewStub(channel);
  const Clock::time_point give_up = Clock::now() + kStartTimeout;
  // UNAVAILABLE once the server has exited, OK while it runs.
  const auto still_running = [this]() -> absl::Status {
    int wait_status = 0;
    if (waitpid(pid_, &wait_status, WNOHANG) != pid_) return absl::OkStatus();
    pid_ = -1;
    return unavailable(
        absl::StrCat("it ended (", describe_exit(wait_status), ") before serving", log_tail()));
  };
  // The socket appears when the server listens: waiting for it first makes the health check's
  // first connection succeed, where a refused one would wait out the channel's reconnect
  // backoff (10 to 100 ms) before the next try.
  const std::string socket = absl::StrCat(dir_, "/", kSocketName);
  std::error_code no_socket;
  while (Clock::now() < give_up && !std::filesystem::exists(socket, no_socket)) {
    if (absl::Status running = still_running(); !running.ok()) return running;
    std::this_thread::sleep_for(kSocketPollInterval);
  }
  while (Clock::now() < give_up) {
    if (absl::Status running = still_running(); !running.ok()) return running;
    grpc::ClientContext context;
    context.set_wait_for_ready(true);
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(250));
    grpc::health::v1::HealthCheckResponse response;
    if (health->Check(&context, {}, &response).ok() &&
        response.status() == grpc::health::v1::HealthCheckResponse::SERVING) {
      return absl::OkStatus();
    }
    std::this_thread::sleep_for(kPollInterval);
  }
  return unavailable(absl::StrCat("it did not report SERVING within ",
                                  std::chrono::seconds(kStartTimeout).count(), " s", log_tail()));
}

std::string PrivateServer::log_tail() const {
  constexpr std::streamoff kTail = 4000;
  std::ifstream in(log_path_, std::ios::binary | std::ios::ate);
  if (!in) return "";
  const std::streamoff size = in.tellg();
  in.seekg(size > kTail ? size - kTail : 0);
  std::ostringstream text;
  text << in.rdbuf();
  if (text.str().empty()) return "";
  return absl::StrCat("\nafmesh-server log (", log_path_, "):\n", text.str());
}

void PrivateServer::stop() {
  if (pid_ > 0) {
    kill(pid_, SIGTERM);
    int wait_status = 0;
    if (!wait_for_exit(pid_, kStopTimeout, &wait_status)) {
      kill(pid_, SIGKILL);
      waitpid(pid_, &wait_status, 0);
    }
    pid_ = -1;
  }
  if (!dir_.empty()) {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
    dir_.clear();
  }
}

}  // namespace afmesh::cli
