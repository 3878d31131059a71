#!/usr/bin/env bash
# The server's security flags seen from the CLI (issue 12, part 5): certificates made here by
# openssl (a CA, a server certificate for localhost, a client certificate of that CA and one of
# another CA), a server with --tls-cert/--tls-key/--tls-client-ca/--token-file on loopback, and
# one CLI call per case: plaintext, TLS without a client certificate, a certificate of another
# CA, mutual TLS without the token, with a wrong token, and with everything (served). Prints
# each call's last lines and exit code, then the server's start line and its exit code after
# SIGTERM. The same cases are asserted by tests/server/cli_security_test.cc and
# tls_server_test.cc; this is the demonstration, not the test.
# Usage: scripts/security-demo.sh [BUILD_DIR]   (default build/release, built)
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="${1:-$root/build/release}/client"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
ssl() { openssl "$@" >/dev/null 2>&1 || { echo "openssl $1 failed" >&2; exit 1; }; }
ssl req -x509 -newkey rsa:2048 -nodes -keyout ca.key -out ca.pem -days 2 -subj /CN=demo-ca
ssl req -x509 -newkey rsa:2048 -nodes -keyout other.key -out other.pem -days 2 -subj /CN=other-ca
printf 'subjectAltName=DNS:localhost,IP:127.0.0.1\n' >san.ext
sign() {  # sign NAME CA SUBJECT [EXTFILE]
  ssl req -newkey rsa:2048 -nodes -keyout "$1.key" -out "$1.csr" -subj "$3"
  ssl x509 -req -in "$1.csr" -CA "$2.pem" -CAkey "$2.key" -CAcreateserial -out "$1.pem" \
    -days 2 ${4:+-extfile "$4"}
}
sign server ca /CN=localhost san.ext
sign client ca /CN=client
sign intruder other /CN=intruder
echo "demo-token-$RANDOM$RANDOM" >token
echo wrong-token >wrong
port=$((20000 + RANDOM % 20000))
"$bin/afmesh-server" --listen "127.0.0.1:$port" --tls-cert server.pem --tls-key server.key \
  --tls-client-ca ca.pem --token-file token >server.log 2>&1 &
pid=$!
sleep 1
call() {  # call TITLE FLAGS...
  echo "## $1"
  shift
  "$bin/afmesh" volume "$root/examples/lblock/lblock.stl" -o out.msh --size 0.2 --retries 0 \
    --server "localhost:$port" "$@" 2>&1 | grep -v '^afmesh: send' | tail -2
  echo "exit ${PIPESTATUS[0]}"
}
call "plaintext client"
call "TLS, no client certificate" --tls-ca ca.pem --token-file token
call "TLS, a client certificate of another CA" --tls-ca ca.pem --tls-cert intruder.pem \
  --tls-key intruder.key --token-file token
call "mutual TLS, no token" --tls-ca ca.pem --tls-cert client.pem --tls-key client.key
call "mutual TLS, a wrong token" --tls-ca ca.pem --tls-cert client.pem --tls-key client.key \
  --token-file wrong
call "mutual TLS and the token" --tls-ca ca.pem --tls-cert client.pem --tls-key client.key \
  --token-file token
kill -TERM "$pid"
wait "$pid"
echo "server exit $? after SIGTERM; its start line:"
head -1 server.log
