// afmesh-server's Prometheus endpoint (--metrics ADDR): plain HTTP, GET /metrics in Prometheus'
// text format, on its own port and threads (prometheus-cpp's Exposer, on civetweb), so that a
// scrape never waits behind meshing calls and a metrics port can be opened to a monitoring
// network without opening the gRPC one.
#pragma once

#include <memory>
#include <string>

#include "absl/status/statusor.h"

namespace prometheus {
class Collectable;
class Exposer;
}  // namespace prometheus

namespace afmesh::server {

class MetricsEndpoint {
 public:
  // Serves `metrics` at http://ADDRESS/metrics. ADDRESS is IPV4:PORT (0.0.0.0 for every
  // interface) or localhost:PORT; port 0 picks a free one. INVALID_ARGUMENT naming --metrics for
  // any other form (IPv6 too: Debian's civetweb is built without it); UNAVAILABLE naming
  // --metrics when the address cannot be bound (port in use, not an address of this host).
  static absl::StatusOr<std::unique_ptr<MetricsEndpoint>> start(
      const std::string& address, const std::shared_ptr<prometheus::Collectable>& metrics);
  // Stops serving: once it returns, no scrape is running or will run.
  ~MetricsEndpoint();
  MetricsEndpoint(const MetricsEndpoint&) = delete;
  MetricsEndpoint& operator=(const MetricsEndpoint&) = delete;

  // IPV4:PORT as bound, with the port chosen when ADDRESS asked for 0.
  const std::string& address() const { return address_; }

 private:
  MetricsEndpoint() = default;

  std::unique_ptr<prometheus::Exposer> exposer_;
  std::string host_;  // as bound
  int port_ = 0;
  std::string address_;
};

}  // namespace afmesh::server
