#include "security/address_reach.h"

#include <arpa/inet.h>
#include <netinet/in.h>

#include "absl/strings/match.h"

namespace afmesh::security {
namespace {

// The ':' before the port of "host:port" / "[v6]:port", or npos when there is no port.
std::string::size_type port_colon(const std::string& address) {
  const std::string::size_type colon = address.rfind(':');
  const std::string::size_type bracket = address.rfind(']');
  if (colon == std::string::npos) return colon;
  if (bracket != std::string::npos && colon < bracket) return std::string::npos;  // "[::1]"
  if (bracket == std::string::npos && address.find(':') != colon) {
    return std::string::npos;  // a bare IPv6 address such as "::1"
  }
  return colon;
}

// `address` without gRPC's "ipv4:" / "ipv6:" scheme, which names an address as it is.
std::string without_scheme(const std::string& address) {
  if (absl::StartsWith(address, "ipv4:") || absl::StartsWith(address, "ipv6:")) {
    return address.substr(5);
  }
  return address;
}

// True for an IPv4 address in 127.0.0.0/8, IPv6 ::1 or an IPv4-mapped 127.x address.
bool is_loopback_ip(const std::string& host) {
  in_addr v4{};
  if (inet_pton(AF_INET, host.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;
  std::string bare = host;
  if (bare.size() >= 2 && bare.front() == '[' && bare.back() == ']') {
    bare = bare.substr(1, bare.size() - 2);
  }
  in6_addr v6{};
  if (inet_pton(AF_INET6, bare.c_str(), &v6) != 1) return false;
  return IN6_IS_ADDR_LOOPBACK(&v6) || (IN6_IS_ADDR_V4MAPPED(&v6) && v6.s6_addr[12] == 127);
}

}  // namespace

Reach reach_of(const std::string& address) {
  if (absl::StartsWith(address, "unix:") || absl::StartsWith(address, "unix-abstract:")) {
    return Reach::kLocalSocket;
  }
  const std::string target = without_scheme(address);
  std::string host = target;
  if (const std::string::size_type colon = port_colon(target); colon != std::string::npos) {
    host = target.substr(0, colon);
  }
  if (is_loopback_ip(host) || absl::EqualsIgnoreCase(host, "localhost")) {
    return Reach::kLoopback;
  }
  return Reach::kOtherHosts;
}

std::string port_of(const std::string& address) {
  if (reach_of(address) == Reach::kLocalSocket) return "";
  const std::string target = without_scheme(address);
  const std::string::size_type colon = port_colon(target);
  return colon == std::string::npos ? "" : target.substr(colon + 1);
}

}  // namespace afmesh::security
