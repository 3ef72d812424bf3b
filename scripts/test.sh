#!/usr/bin/env bash
# scripts/test.sh: THE test command. Installs missing dependencies and builds Release into build/
# with warnings as errors (scripts/setup.sh), then runs every test with ctest. Exits non-zero on
# any failure, including a build that yields no tests. Extra arguments go to scripts/setup.sh
# (e.g. --with-cgal, -DVAR=VALUE).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
BUILD_DIR=${EDGEFRONT_BUILD_DIR:-build}

"$ROOT/scripts/setup.sh" -DEDGEFRONT_WERROR=ON -DEDGEFRONT_BUILD_TESTS=ON "$@"

echo "test: ctest --test-dir $BUILD_DIR --output-on-failure -j2"
# --no-tests=error: a build that lost its tests fails instead of passing silently.
# --timeout: a hung test fails after 5 minutes (each test should take well under a second).
ctest --test-dir "$BUILD_DIR" --output-on-failure --no-tests=error --timeout 300 -j2
