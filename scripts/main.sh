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
# THE MAIN JOB: its one line below is what later work replaces. Planned:
#   run "$BUILD_DIR/apps/gcs-reconstruct" data/vault-shell.xyz -o out/vault.ply
run_main_job() {
  # Until the reconstructor exists: a geodesic distance field and the edge-front levels from
  # vertex 0 of the bundled bumpy sphere, as colored PLY files.
  run "$BUILD_DIR/apps/ef-distance" data/bumpy-sphere.off --source 0 -o out/bumpy-sphere-distance.ply
  run "$BUILD_DIR/apps/ef-front" data/bumpy-sphere.off --source 0 -o out/bumpy-sphere-levels.ply
}
# ---------------------------------------------------------------------------------------------

"$ROOT/scripts/setup.sh" "$@"
mkdir -p out
run_main_job
echo "main: done"
