#!/usr/bin/env bash
# Builds the afmesh image with no Docker daemon and no registry, then meshes through it:
#   1. mmdebstrap: a debian:bookworm base from apt only (cached in build/image/),
#   2. buildah (vfs storage, chroot isolation; a private store in build/image/storage):
#      that base tagged docker.io/library/debian:bookworm, then deploy/Dockerfile built unchanged,
#   3. smoke test: the image's afmesh-server started with `buildah run`, its HEALTHCHECK command
#      run inside the image, and examples/lblock/lblock.stl meshed through it by the host CLI
#      (build/release/client/afmesh, built first if missing), checked by `afmesh stats`.
# Usage: deploy/build-image.sh [--no-smoke | --smoke-only]
#   (as root; TAG=localhost/afmesh:dev, PORT=50061; --smoke-only: step 3 on the built image)
set -euo pipefail
cd "$(dirname "$0")/.."
root_dir=$PWD
tag="${TAG:-localhost/afmesh:dev}"
port="${PORT:-50061}"
work="$root_dir/build/image"
[[ $(id -u) -eq 0 ]] || { echo "build-image: needs root (buildah chroot isolation, vfs)" >&2; exit 1; }
scripts/install-deps.sh --image
mkdir -p "$work"
bah() { buildah --root "$work/storage" --runroot "$work/run" --storage-driver vfs "$@"; }
mode="${1:-}"
if [[ "$mode" != "--smoke-only" ]]; then

echo "== 1. debian:bookworm base by mmdebstrap"
if [[ ! -s "$work/bookworm.tar" ]]; then
  mmdebstrap --variant=minbase --format=tar bookworm "$work/bookworm.tar.part" \
    "deb http://deb.debian.org/debian bookworm main" \
    "deb http://deb.debian.org/debian bookworm-updates main" \
    "deb http://deb.debian.org/debian-security bookworm-security main"
  mv "$work/bookworm.tar.part" "$work/bookworm.tar"
fi
if ! bah inspect --type image docker.io/library/debian:bookworm >/dev/null 2>&1; then
  ctr=$(bah from scratch)
  bah add "$ctr" "$work/bookworm.tar" /
  bah config --cmd /bin/bash "$ctr"
  bah commit --quiet --rm "$ctr" docker.io/library/debian:bookworm
fi

echo "== 2. buildah bud deploy/Dockerfile -> $tag"
start=$(date +%s)
bah bud --isolation chroot --pull=never --format docker --layers=false \
  -f deploy/Dockerfile --ignorefile deploy/Dockerfile.dockerignore -t "$tag" .
echo "build-image: built $tag in $(( $(date +%s) - start )) s"
bah images --format '{{.Name}}:{{.Tag}} {{.Size}}' "$tag"
bah inspect --format 'user={{.Docker.Config.User}} entrypoint={{.Docker.Config.Entrypoint}} cmd={{.Docker.Config.Cmd}} ports={{.Docker.Config.ExposedPorts}} healthcheck={{.Docker.Config.Healthcheck.Test}}' "$tag"

fi
[[ "$mode" == "--no-smoke" ]] && exit 0
echo "== 3. smoke test: the image's server on 127.0.0.1:$port, meshed from the host CLI"
[[ -x build/release/client/afmesh ]] || { cmake --preset release >/dev/null && cmake --build --preset release --target afmesh; }
ctr=$(bah from --pull=never "$tag")
run_pid= server_pid=
log="$work/server-from-image.log"
cleanup() {
  # chroot isolation has no pid namespace: the server's pid (printed by its shell) is a host
  # pid. SIGTERM drains it and it exits 0; then buildah run returns.
  [[ -n "$server_pid" ]] && kill -TERM "$server_pid" 2>/dev/null
  [[ -n "$run_pid" ]] && wait "$run_pid" 2>/dev/null
  [[ -f "$log" ]] && sed 's/^/  server: /' "$log"
  bah rm "$ctr" >/dev/null 2>&1 || true
}
trap cleanup EXIT
bah run --isolation chroot "$ctr" -- sh -c 'id; for b in /usr/local/bin/afmesh /usr/local/bin/afmesh-server; do ldd $b | grep "not found" && exit 1; done; echo "all libraries found"'
bah run --isolation chroot "$ctr" -- \
  sh -c 'echo "pid $$"; exec afmesh-server --listen "$0"' "127.0.0.1:$port" >"$log" 2>&1 &
run_pid=$!
for _ in $(seq 50); do
  server_pid=$(sed -n 's/^pid //p' "$log")
  [[ -n "$server_pid" ]] && break
  sleep 0.1
done
sleep 0.5
# Only a host pid whose executable is afmesh-server is ever signalled (a pid namespace would
# make $$ mean something else on the host).
if [[ "$(readlink "/proc/$server_pid/exe" 2>/dev/null)" != */afmesh-server ]]; then
  echo "build-image: pid '$server_pid' is not the image's afmesh-server on this host" >&2
  server_pid=
  exit 1
fi
for _ in $(seq 50); do
  bah run --isolation chroot "$ctr" -- afmesh-health-probe "127.0.0.1:$port" 2>/dev/null && break
  sleep 0.2
done
bah run --isolation chroot "$ctr" -- afmesh-health-probe "127.0.0.1:$port"
echo "build-image: HEALTHCHECK command (afmesh-health-probe) inside the image: SERVING"
out="$work/lblock-from-image.msh"
build/release/client/afmesh volume examples/lblock/lblock.stl -o "$out" --size 0.25 \
  --server "127.0.0.1:$port"
build/release/client/afmesh stats "$out"
echo "build-image: meshed examples/lblock/lblock.stl through $tag: $out"
