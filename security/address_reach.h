// Who can reach a gRPC address: the server says it when it starts, and the CLI warns before it
// sends a bearer token in plaintext to an address other hosts can see.
#pragma once

#include <string>

namespace afmesh::security {

enum class Reach {
  kLocalSocket,  // unix: or unix-abstract: address
  kLoopback,     // 127.0.0.0/8, localhost or [::1]
  kOtherHosts,   // anything else (0.0.0.0, [::], a host name or a public address)
};

// Who can connect to (or listen with) `address`: "host:port", "[v6]:port" or "unix:PATH".
Reach reach_of(const std::string& address);

// The port of "host:port" ("" when it has none, as for unix: addresses).
std::string port_of(const std::string& address);

}  // namespace afmesh::security
