#!/usr/bin/env bash
# scripts/main.sh: THE main-job command. Installs missing dependencies and builds Release into
# build/ (scripts/setup.sh; extra arguments go to it), then runs the main job: run_main_job below.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
BUILD_DIR=${EDGEFRONT_BUILD_DIR:-build}

die() { printf 'main: error: %s\n' "$*" >&2; exit 1; }

# run <app> <args...>: runs one built app, with a clear message when the app or a data/ input is
# missing.
run() {
  [[ -x $1 ]] || die "$1 is not built (no apps/$(basename "$1").cpp in this tree?)"
  local arg
  for arg in "${@:2}"; do
    [[ $arg != data/* || -e $arg ]] || die "input $arg does not exist"
  done
  echo "main: $*"
  "$@"
}

# ---------------------------------------------------------------------------------------------
# THE MAIN JOB: reconstruct the bundled vault shell point cloud (4000 oriented points) with growing
# cell structures and write the mesh (2000 vertices, a few seconds). --no-borders keeps the closed
# shell closed (the border creation tears thin closed shells apart, see README).
run_main_job() {
  run "$BUILD_DIR/apps/gcs-reconstruct" data/vault-shell.xyz -o out/vault.ply --vertices 2000 --no-borders
}
# ---------------------------------------------------------------------------------------------

"$ROOT/scripts/setup.sh" "$@"
mkdir -p out
run_main_job
echo "main: done"
