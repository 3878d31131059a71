#!/usr/bin/env bash
# deploy/k8s offline: yamllint, then deploy/k8s/validate/validate.cjs (Kubernetes schemas from
# the npm package kubernetes-models, unknown fields, cross-references, afmesh-server's flags)
# with its self-tests. kubernetes-models is installed by `npm ci` from deploy/k8s/validate's
# lock file into a cache outside the repository (AFMESH_NPM_CACHE, default ~/.cache/afmesh),
# once per lock file. When npm cannot install it (registry unreachable), this test FAILS: the
# manifests were not validated, and a skip would read as a pass.
# Usage: k8s_manifests_test.sh SOURCE_DIR SERVER_BINARY
set -euo pipefail
src="$1" server="$2"
validate="$src/deploy/k8s/validate"
echo "== yamllint -s -c deploy/.yamllint deploy/k8s"
yamllint -s -c "$src/deploy/.yamllint" "$src/deploy/k8s"
echo "yamllint: ok"

lock_hash=$(sha256sum "$validate/package-lock.json" | cut -c1-16)
modules="${AFMESH_NPM_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/afmesh}/k8s-validate-$lock_hash"
if [[ ! -f "$modules/node_modules/.package-lock.json" ]]; then
  echo "== npm ci (kubernetes-models, yaml) into $modules"
  rm -rf "$modules" && mkdir -p "$modules"
  cp "$validate/package.json" "$validate/package-lock.json" "$modules/"
  if ! (cd "$modules" && npm ci --no-audit --no-fund --ignore-scripts); then
    rm -rf "$modules"
    echo "FAILED: npm could not install kubernetes-models (registry unreachable?):" \
         "the manifests were NOT validated against the Kubernetes schemas" >&2
    exit 1
  fi
fi
echo "== node $(node --version): validate.cjs deploy/k8s --self-test"
node "$validate/validate.cjs" "$modules" "$src/deploy/k8s" "$server" --self-test
