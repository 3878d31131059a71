// What afmesh-server says when it starts listening: the address, who can reach it, and what it
// asks of clients, so that a server open to other hosts without TLS is never a surprise.
#pragma once

#include <string>
#include <vector>

#include "server/credentials.h"

namespace afmesh::server {

// The start-up lines, without a program prefix: "listening on 127.0.0.1:50051 (loopback only;
// use --listen 0.0.0.0:50051 to serve other hosts); plaintext, no token", followed by a warning
// when other hosts can reach a plaintext server.
std::vector<std::string> listen_note(const std::string& address, const ServerSecurity& security);

// The start-up line for --metrics, `address` as bound: "metrics on
// http://127.0.0.1:9464/metrics (loopback only; plain HTTP, no token: call counts and sizes,
// never meshes)", or "other hosts can connect" in place of "loopback only".
std::string metrics_note(const std::string& address);

}  // namespace afmesh::server
