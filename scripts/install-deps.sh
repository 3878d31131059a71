#!/usr/bin/env bash
# Installs what afmesh needs to build and test, from Debian 12's apt only.
# Usage: scripts/install-deps.sh [--peers] [--image] [--fuzz] [--balancers]
#   --peers adds gmsh, netgen, tetgen, CGAL for bench/; --image adds buildah and mmdebstrap for
#   deploy/build-image.sh; --fuzz adds clang-14 and its libFuzzer and sanitizer runtimes for the
#   fuzz preset (fuzz/run.sh); --balancers adds nginx and haproxy for the scale-out run
#   (bench/load/scaleout.sh, run unprivileged on loopback ports: the packages' own services are
#   not needed).
# Does nothing when everything is present; needs root (or sudo) to install what is missing.
set -euo pipefail

packages=(
  g++ cmake ninja-build ccache pkg-config
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler
  libabsl-dev libeigen3-dev libgtest-dev libgmock-dev libcli11-dev
  libssl-dev openssl  # security/: PEM checks at start-up; the TLS tests make their certificates with openssl
  prometheus-cpp-dev  # afmesh-server --metrics (prometheus-cpp 1.0: core, and pull on civetweb)
  python3-minimal python3-numpy python3-meshio python3-gmsh python3-vtk9  # cross-checks: /usr/bin/python3 with meshio, gmsh and VTK
  yamllint  # deploy/k8s
  occt-misc  # OCCT's sample data: raw CAD tessellations the volume tests mesh as given
  python3-grpcio python3-protobuf  # deploy/health_probe.py and the load driver (bench/load/)
)
for arg in "$@"; do
  case "$arg" in
    --peers) packages+=(gmsh python3-gmsh netgen python3-netgen tetgen time libcgal-dev libgmp-dev libmpfr-dev) ;;
    --image) packages+=(buildah mmdebstrap) ;;
    --fuzz) packages+=(clang-14 libclang-rt-14-dev) ;;
    --balancers) packages+=(nginx haproxy) ;;
    *) echo "install-deps: unknown option $arg" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# deploy/k8s's schema check runs on node + npm (Debian's nodejs 18 and npm 9 suffice); a node
# from elsewhere that bundles npm (and conflicts with Debian's npm package) counts as present.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  missing+=(nodejs npm)
fi
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
