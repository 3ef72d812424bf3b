#!/usr/bin/env bash
# scripts/setup.sh: install EdgeFront's build dependencies (Debian 12 packages) if any is missing,
# then configure and build Release into build/. Safe to run again: installed packages are skipped
# (no apt-get at all when nothing is missing) and the build is incremental.
#
#   scripts/setup.sh                       deps + Release build in build/
#   scripts/setup.sh --with-cgal           also install libcgal-dev (only the cgal_* benchmarks use it)
#   scripts/setup.sh --with-fuzz           also install clang and libFuzzer (only fuzz/ uses them)
#   scripts/setup.sh --with-peers          also install python3-open3d (only bench/python compares with it)
#   scripts/setup.sh --deps-only           install the packages, do not build
#   scripts/setup.sh -DEDGEFRONT_WERROR=ON extra -D options are passed to the cmake configure step
#   scripts/setup.sh --target gcs-reconstruct   build only this target (and what it needs)
#
# Runs as root, or through sudo when not root (sudo is used only then). The build folder can be
# moved with EDGEFRONT_BUILD_DIR (default: build).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
BUILD_DIR=${EDGEFRONT_BUILD_DIR:-build}

# Libraries, tests and apps. libpng-dev: PNG pictures (render/). doxygen: the API reference
# (scripts/docs.sh, CI phase docs). pybind11-dev python3-dev python3-numpy: the Python package
# (python/); python3-pytest: its tests; python3-dask python3-distributed: the Dask examples and
# their test.
PACKAGES=(build-essential cmake libopenmesh-dev libnanoflann-dev libeigen3-dev
          libgtest-dev libgmock-dev libcli11-dev libpng-dev doxygen
          pybind11-dev python3-dev python3-numpy python3-pytest python3-dask python3-distributed)
CGAL_PACKAGES=(libcgal-dev)
FUZZ_PACKAGES=(clang libfuzzer-14-dev)
PEER_PACKAGES=(python3-open3d)

say() { printf 'setup: %s\n' "$*"; }
die() { printf 'setup: error: %s\n' "$*" >&2; exit 1; }
usage() { sed -n '2,15s/^# \{0,1\}//p' "${BASH_SOURCE[0]}"; }

with_cgal=0
with_fuzz=0
with_peers=0
deps_only=0
cmake_args=()
targets=()
while (($#)); do
  case $1 in
    --with-cgal) with_cgal=1 ;;
    --with-fuzz) with_fuzz=1 ;;
    --with-peers) with_peers=1 ;;
    --deps-only) deps_only=1 ;;
    -D?*) cmake_args+=("$1") ;;
    --target)
      (($# >= 2)) || die "--target needs a target name"
      targets+=(--target "$2")
      shift
      ;;
    -h | --help) usage; exit 0 ;;
    *) die "unknown argument '$1' (see scripts/setup.sh --help)" ;;
  esac
  shift
done

wanted=("${PACKAGES[@]}")
((with_cgal)) && wanted+=("${CGAL_PACKAGES[@]}")
((with_fuzz)) && wanted+=("${FUZZ_PACKAGES[@]}")
((with_peers)) && wanted+=("${PEER_PACKAGES[@]}")

is_installed() { dpkg -s "$1" 2>/dev/null | grep -q '^Status: install ok installed$'; }

install_missing_packages() {
  if ! command -v dpkg >/dev/null || ! command -v apt-get >/dev/null; then
    die "dpkg/apt-get not found: this script supports Debian 12; install these yourself: ${wanted[*]}"
  fi

  local missing=() pkg
  for pkg in "${wanted[@]}"; do
    is_installed "$pkg" || missing+=("$pkg")
  done
  if ((${#missing[@]} == 0)); then
    say "all ${#wanted[@]} packages already installed"
    return
  fi

  local sudo=()
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || die "not root and no sudo: cannot install ${missing[*]}"
    sudo=(sudo)
  fi

  local log
  log=$(mktemp "${TMPDIR:-/tmp}/edgefront-apt.XXXXXX")
  # Quiet apt: its output goes to a log, shown only when apt fails. The lock timeout covers a
  # fresh machine where unattended-upgrades still holds the dpkg lock.
  run_apt() {
    "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -q -y -o DPkg::Lock::Timeout=600 "$@" \
      </dev/null >"$log" 2>&1 || { cat "$log" >&2; rm -f "$log"; die "apt-get $1 failed (output above)"; }
  }
  say "installing ${#missing[@]} missing package(s): ${missing[*]}"
  say "apt-get update"
  run_apt update
  say "apt-get install"
  run_apt install --no-install-recommends "${missing[@]}"
  rm -f "$log"

  for pkg in "${missing[@]}"; do
    is_installed "$pkg" || die "package $pkg is still not installed after apt-get install"
  done
  say "installed: ${missing[*]}"
}

install_missing_packages
((deps_only)) && exit 0

jobs=$(nproc 2>/dev/null || echo 2)
say "configure: cmake -S . -B $BUILD_DIR -DCMAKE_BUILD_TYPE=Release ${cmake_args[*]}"
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "${cmake_args[@]}"
say "build: cmake --build $BUILD_DIR -j$jobs ${targets[*]}"
cmake --build "$BUILD_DIR" -j"$jobs" "${targets[@]}"
say "Release build ready in $BUILD_DIR/"
