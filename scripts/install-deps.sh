#!/usr/bin/env bash
# Installs what afmesh needs to build and test, from Debian 12's apt only.
# Usage: scripts/install-deps.sh [--peers | --fuzz]
#   --peers adds gmsh, netgen, tetgen for bench/; --fuzz adds clang-14 and its libFuzzer and
#   sanitizer runtimes for the fuzz preset (fuzz/run.sh).
# Does nothing when everything is present; needs root (or sudo) to install what is missing.
set -euo pipefail

packages=(
  g++ cmake ninja-build ccache pkg-config
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler
  libabsl-dev libeigen3-dev libgtest-dev libgmock-dev libcli11-dev
  python3-minimal python3-numpy python3-meshio python3-gmsh python3-vtk9  # cross-checks: /usr/bin/python3 with meshio, gmsh and VTK
)
if [[ "${1:-}" == "--peers" ]]; then
  packages+=(gmsh python3-gmsh netgen python3-netgen tetgen time)
elif [[ "${1:-}" == "--fuzz" ]]; then
  packages+=(clang-14 libclang-rt-14-dev)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "afmesh: installing missing packages: ${missing[*]}" >&2
if [[ $(id -u) -eq 0 ]]; then
  apt_get=(apt-get)
elif command -v sudo >/dev/null && sudo -n true 2>/dev/null; then
  apt_get=(sudo apt-get)
else
  echo "afmesh: these Debian packages are missing and this user cannot install them:" >&2
  echo "  apt-get install ${missing[*]}" >&2
  echo "Run that as root, then run this command again." >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${apt_get[@]}" update -qq
"${apt_get[@]}" install -y -qq --no-install-recommends "${missing[@]}"
