#!/usr/bin/env bash
# deploy/build-image.sh end to end (mmdebstrap base, buildah bud of deploy/Dockerfile, the
# image's server meshing examples/lblock/lblock.stl for the host CLI). It compiles afmesh inside
# the image (many minutes on 2 cores), so it runs only when AFMESH_IMAGE_TEST=1 and buildah is
# installed; otherwise it says it did NOT run and exits 77, which CTest reports as Skipped.
set -euo pipefail
src="$1"
if [[ "${AFMESH_IMAGE_TEST:-}" != 1 ]]; then
  echo "NOT RUN: the container image was not built (set AFMESH_IMAGE_TEST=1 to run deploy/build-image.sh)"
  exit 77
fi
if ! command -v buildah >/dev/null || ! command -v mmdebstrap >/dev/null; then
  echo "NOT RUN: buildah or mmdebstrap is not installed (scripts/install-deps.sh --image)"
  exit 77
fi
exec "$src/deploy/build-image.sh"
