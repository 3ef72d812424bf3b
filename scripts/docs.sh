#!/usr/bin/env bash
# scripts/docs.sh: the API reference. Runs Doxygen (docs/Doxyfile) over the public headers of
# edgefront/, twist/, gcs/ and render/, writes HTML to build/docs/html (or $EDGEFRONT_DOCS_DIR/html;
# $EDGEFRONT_BUILD_DIR/docs/html when only EDGEFRONT_BUILD_DIR is set)
# and fails on any Doxygen warning (an undocumented public name, a \param that names no parameter,
# a broken reference, ...), printing every warning as file:line: text.
#
#   scripts/docs.sh                            build/docs/html/index.html
#   EDGEFRONT_DOCS_DIR=/tmp/api scripts/docs.sh   /tmp/api/html/index.html
#
# Needs doxygen (Debian's doxygen package; scripts/setup.sh --deps-only installs it).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
OUT_DIR=${EDGEFRONT_DOCS_DIR:-${EDGEFRONT_BUILD_DIR:-build}/docs}

command -v doxygen >/dev/null \
  || { echo "docs: error: doxygen not found (scripts/setup.sh --deps-only installs it)" >&2; exit 1; }

mkdir -p "$OUT_DIR"
log=$(mktemp "${TMPDIR:-/tmp}/edgefront-docs.XXXXXX")
trap 'rm -f "$log"' EXIT

echo "docs: $(doxygen --version | head -n1): doxygen docs/Doxyfile -> $OUT_DIR/html"
# The Doxyfile is read from stdin so that OUTPUT_DIRECTORY can be overridden; relative paths in it
# stay relative to the repository root (the working directory).
rc=0
{ cat docs/Doxyfile; printf 'OUTPUT_DIRECTORY = "%s"\n' "$OUT_DIR"; } | doxygen - >"$log" 2>&1 || rc=$?

# Doxygen (WARN_AS_ERROR = FAIL_ON_WARNINGS) prints warnings as "file:line: error: ..." or
# "warning: ...", some followed by indented continuation lines; QUIET = YES keeps progress out.
count=$(grep -cE '(^|: )(warning|error):' "$log" || true)
if ((rc != 0 || count > 0)); then
  sed "s|^$ROOT/||" "$log" >&2
  echo "docs: FAILED: $count warning(s) (doxygen exit $rc)" >&2
  exit 1
fi
echo "docs: 0 warnings; open $OUT_DIR/html/index.html"
