#!/usr/bin/env bash
# scripts/bench-geodesics.sh: the geodesic accuracy and speed benchmarks, end to end.
#
#   scripts/bench-geodesics.sh [--quick] [--no-accuracy] [--no-speed] [--models "a b ..."]
#
# 1. fetches the test models if missing (data/fetch-models.sh);
# 2. builds Release with CGAL (when found) into $EDGEFRONT_BUILD_DIR (default build-bench-geo):
#    cgal_geodesic_reference, geodesic_accuracy, geodesic_speed;
# 3. computes CGAL's reference distances (exact Surface_mesh_shortest_path; heat method, intrinsic
#    Delaunay) into $GEO_REF_DIR (default /tmp/geo-ref; large .bin files, never in the repository),
#    one folder per mesh content hash, reusing what is already there;
# 4. runs bench/geodesic_accuracy (synthetic planar/cylinder/cone cases, then every model with
#    $SOURCES random sources and $PAIRS symmetry pairs) and bench/geodesic_speed;
# 5. writes markdown to bench/results/geodesic-{synthetic,accuracy,speed}.md, each headed by the
#    commit, whether the library sources differ from it, the machine and its load.
#
# Without CGAL the exact/heat references are skipped: the synthetic mode still runs (closed-form
# references) and the model tables are left out. Environment: SOURCES (5), PAIRS (1000), SEED (1),
# EDGEFRONT_BUILD_DIR, GEO_REF_DIR. --quick: 2 sources, 100 pairs, one subdivision level and a
# 500x500 large grid (a smoke test, not a measurement).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${EDGEFRONT_BUILD_DIR:-$ROOT/build-bench-geo}
REF=${GEO_REF_DIR:-/tmp/geo-ref}
OUT=$ROOT/bench/results
SOURCES=${SOURCES:-5}
PAIRS=${PAIRS:-1000}
SEED=${SEED:-1}
MODELS="elephant homer ChineseDragon-10kv man armadillo bunny00"
SPEED_ARGS=()
do_accuracy=1
do_speed=1

while [ $# -gt 0 ]; do
  case "$1" in
    --quick) SOURCES=2; PAIRS=100; SPEED_ARGS=(--subdiv 1 --large 500 --reps 1 --sources 2 --queries 50) ;;
    --no-accuracy) do_accuracy=0 ;;
    --no-speed) do_speed=0 ;;
    --models) shift; MODELS="$1" ;;
    -h|--help) sed -n '2,24p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench-geodesics: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done

log() { echo "bench-geodesics: $*" >&2; }

# 1. Models.
"$ROOT/data/fetch-models.sh"

# 2. Build.
log "configuring $BUILD (Release)"
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DEDGEFRONT_BUILD_TESTS=OFF -DEDGEFRONT_BUILD_APPS=OFF >/dev/null
have_cgal=0
# (not `| grep -q`: with pipefail, grep's early exit breaks cmake's pipe and fails the test)
build_targets=$(cmake --build "$BUILD" --target help)
if grep -q cgal_geodesic_reference <<<"$build_targets"; then
  have_cgal=1
  targets=(cgal_geodesic_reference geodesic_accuracy geodesic_speed)
else
  log "CGAL not found: no exact or heat-method references; synthetic cases use closed forms only"
  targets=(geodesic_accuracy geodesic_speed)
fi
log "building ${targets[*]}"
cmake --build "$BUILD" -j"$(nproc)" --target "${targets[@]}"
BIN=$BUILD/bench

mkdir -p "$OUT" "$REF"

header() {
  local commit dirty
  commit=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
  dirty=$(git -C "$ROOT" status --porcelain -- edgefront 2>/dev/null | head -c 1)
  echo "<!-- written by scripts/bench-geodesics.sh -->"
  echo "Commit $commit$([ -n "$dirty" ] && echo ' **with uncommitted changes in edgefront/**'), $(date -u '+%Y-%m-%d %H:%M UTC')," \
    "$(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | cut -d: -f2 | sed 's/^ //' || echo unknown cpu))," \
    "load average $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown) at start."
}

hash_of() { cat "$@" | sha1sum | cut -c1-12; }

# 3 + 4a. Synthetic cases; CGAL exact distances for the cylinders and cones.
if [ "$do_accuracy" = 1 ]; then
  tmp_shapes=$(mktemp -d)
  trap 'rm -rf "$tmp_shapes"' EXIT
  "$BIN/geodesic_accuracy" --write-shapes "$tmp_shapes" >/dev/null
  shapes_dir=$REF/shapes-$(hash_of "$tmp_shapes"/*.off "$tmp_shapes"/*.sources)
  mkdir -p "$shapes_dir"
  cp -n "$tmp_shapes"/* "$shapes_dir"/ 2>/dev/null || true
  ref_args=()
  if [ "$have_cgal" = 1 ]; then
    for off in "$shapes_dir"/*.off; do
      name=$(basename "$off" .off)
      log "CGAL exact reference: $name"
      "$BIN/cgal_geodesic_reference" "$off" --sources "$(cat "$shapes_dir/$name.sources")" \
        -o "$shapes_dir/$name" --skip-existing >/dev/null
    done
    ref_args=(--ref-dir "$shapes_dir")
  fi
  log "accuracy: synthetic cases"
  { header; echo; echo "## Geodesic accuracy: synthetic cases"; "$BIN/geodesic_accuracy" --synthetic "${ref_args[@]}"; } \
    > "$OUT/geodesic-synthetic.md"

  # 3 + 4b. Models.
  if [ "$have_cgal" = 1 ]; then
    {
      header
      echo
      echo "## Geodesic accuracy on CGAL's sample meshes ($SOURCES random sources each, seed $SEED; $PAIRS symmetry pairs)"
    } > "$OUT/geodesic-accuracy.md"
    for m in $MODELS; do
      mesh=$ROOT/data/models/$m.off
      [ -s "$mesh" ] || { log "missing $mesh, skipped"; continue; }
      dir=$REF/$m-$(hash_of "$mesh")
      mkdir -p "$dir"
      sources=$("$BIN/cgal_geodesic_reference" "$mesh" --random "$SOURCES" --seed "$SEED" --print-sources)
      log "CGAL references: $m, sources $sources (exact can take a minute per source)"
      "$BIN/cgal_geodesic_reference" "$mesh" --sources "$sources" -o "$dir/$m" --heat --skip-existing >/dev/null
      log "accuracy: $m"
      "$BIN/geodesic_accuracy" "$mesh" --ref "$dir/$m" --sources "$sources" --pairs "$PAIRS" --seed "$SEED" \
        >> "$OUT/geodesic-accuracy.md"
    done
  fi
fi

# 4c. Speed.
if [ "$do_speed" = 1 ]; then
  log "speed: full field on the subdivided armadillo, d_max queries on two grids"
  { header; echo; echo "## Geodesic speed"; "$BIN/geodesic_speed" --model "$ROOT/data/models/armadillo.off" "${SPEED_ARGS[@]}"; } \
    > "$OUT/geodesic-speed.md"
fi

log "results in $OUT:"
ls -1 "$OUT"/geodesic-*.md >&2
