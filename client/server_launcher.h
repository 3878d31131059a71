// The CLI's private afmesh-server: started for one command on a unix socket in a fresh
// temporary folder, stopped (SIGTERM, then SIGKILL if it will not go) when the command ends,
// whatever the outcome. It dies with the CLI too (PR_SET_PDEATHSIG), so it is never left
// running.
#pragma once

#include <sys/types.h>

#include <memory>
#include <string>

#include "absl/status/statusor.h"

namespace afmesh::cli {

class PrivateServer {
 public:
  // Starts the afmesh-server found beside the running afmesh binary and waits (at most 10 s)
  // until its health service reports SERVING. UNAVAILABLE, with the server's own log when it
  // wrote one, if it is missing, exits or does not come up.
  static absl::StatusOr<std::unique_ptr<PrivateServer>> start();

  // Stops the server and removes its folder.
  ~PrivateServer();
  PrivateServer(const PrivateServer&) = delete;
  PrivateServer& operator=(const PrivateServer&) = delete;

  // The gRPC address to dial ("unix:/tmp/afmesh-XXXXXX/mesher.sock").
  const std::string& address() const { return address_; }

 private:
  PrivateServer() = default;
  absl::Status spawn(const std::string& binary);
  absl::Status wait_until_serving();
  // The end of the server's log, for error messages ("" when it wrote nothing).
  std::string log_tail() const;
  void stop();

  std::string dir_;
  std::string address_;
  std::string log_path_;
  pid_t pid_ = -1;
};

}  // namespace afmesh::cli
