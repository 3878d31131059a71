#include "server/metrics_endpoint.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <thread>
#include <utility>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "prometheus/exposer.h"

namespace afmesh::server {
namespace {

// Scrapes served at once; Prometheus sends one at a time, a person with curl may add another.
constexpr std::size_t kHttpThreads = 2;

struct BindAddress {
  std::string host;  // an IPv4 address
  int port = 0;
};

absl::Status bad_address(const std::string& address, const std::string& why) {
  return absl::InvalidArgumentError(
      absl::StrCat("--metrics ", address, ": ", why,
                   "; expected IPV4:PORT, e.g. 127.0.0.1:9464 (loopback) or 0.0.0.0:9464 (every "
                   "interface); port 0 picks a free one"));
}

absl::StatusOr<BindAddress> parse_address(const std::string& address) {
  const std::string::size_type colon = address.rfind(':');
  if (colon == std::string::npos) return bad_address(address, "no port");
  BindAddress bind{.host = address.substr(0, colon), .port = 0};
  const std::string port = address.substr(colon + 1);
  if (port.empty() || port.size() > 5 ||
      !std::all_of(port.begin(), port.end(), absl::ascii_isdigit) ||
      !absl::SimpleAtoi(port, &bind.port) || bind.port > 65535) {
    return bad_address(address, absl::StrCat("port '", port, "' is not a number from 0 to 65535"));
  }
  if (absl::StartsWith(bind.host, "[") || bind.host.find(':') != std::string::npos) {
    return bad_address(address, "IPv6 is not supported (Debian's civetweb is built without it)");
  }
  if (absl::EqualsIgnoreCase(bind.host, "localhost")) bind.host = "127.0.0.1";
  in_addr v4{};
  if (inet_pton(AF_INET, bind.host.c_str(), &v4) != 1) {
    return bad_address(address, bind.host.empty()
                                    ? "no host"
                                    : absl::StrCat("'", bind.host, "' is not an IPv4 address"));
  }
  return bind;
}

// Opens and closes a connection to `host`:`port` (0.0.0.0 is reached on loopback).
void knock(const std::string& host, int port) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  if (host == "0.0.0.0" || inet_pton(AF_INET, host.c_str(), &address.sin_addr) != 1) {
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  }
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return;
  connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address));
  close(fd);
}

}  // namespace

absl::StatusOr<std::unique_ptr<MetricsEndpoint>> MetricsEndpoint::start(
    const std::string& address, const std::shared_ptr<prometheus::Collectable>& metrics) {
  absl::StatusOr<BindAddress> bind = parse_address(address);
  if (!bind.ok()) return bind.status();
  std::unique_ptr<MetricsEndpoint> endpoint(new MetricsEndpoint());
  try {
    endpoint->exposer_ = std::make_unique<prometheus::Exposer>(
        absl::StrCat(bind->host, ":", bind->port), kHttpThreads);
  } catch (const std::exception&) {
    // civetweb says only "null context when constructing CivetServer".
    return absl::UnavailableError(absl::StrCat("--metrics ", address,
                                               ": cannot listen there (the port is in use, or ",
                                               bind->host, " is not an address of this host)"));
  }
  const std::vector<int> ports = endpoint->exposer_->GetListeningPorts();
  if (ports.empty()) {
    return absl::UnavailableError(absl::StrCat("--metrics ", address, ": no port was bound"));
  }
  endpoint->exposer_->RegisterCollectable(metrics);
  endpoint->host_ = bind->host;
  endpoint->port_ = ports.front();
  endpoint->address_ = absl::StrCat(bind->host, ":", ports.front());
  return endpoint;
}

// civetweb's accept loop polls its socket in 2 s quanta and sees that it should stop only
// between polls, so stopping takes up to 2 s (measured 1.7 s) unless a connection wakes it: knock
// until the Exposer is gone (about 10 ms).
MetricsEndpoint::~MetricsEndpoint() {
  if (exposer_ == nullptr) return;
  std::atomic<bool> stopped{false};
  std::thread knocker([this, &stopped] {
    while (!stopped.load(std::memory_order_acquire)) {
      knock(host_, port_);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
  exposer_.reset();
  stopped.store(true, std::memory_order_release);
  knocker.join();
}

}  // namespace afmesh::server
