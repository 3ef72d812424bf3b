#!/usr/bin/env bash
# scripts/bench-noise.sh: reconstruction of noisy clouds against the TRUE surface (issue 6).
#
#   scripts/bench-noise.sh [BUILD_DIR]        (default: build; needs gcs-reconstruct, gcs-eval, ef-shapes,
#                                              and bench/cgal_reconstruct_reference when CGAL was found)
#
# For synthetic shapes sampled with Gaussian noise along the normal (ef-shapes --noise), and CGAL's
# sphere_20k.xyz (data/fetch-models.sh; its true surface taken as the unit sphere), it runs
#   - gcs-reconstruct (default: a noisy cloud is smoothed first, ReconstructOptions::smooth_noise_ratio),
#   - gcs-reconstruct --keep-noise (the loop on the raw points),
#   - CGAL's advancing front (interpolates the points), when available,
# and measures each mesh with gcs-eval against a fine mesh of the exact shape ("truth") and against
# the noisy points themselves ("cloud"), as Chamfer-L1 in % of the bounding-box diagonal.
# Prints a markdown table on stdout. Work files go to $NOISE_DIR (default /tmp/ef-noise).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:-$ROOT/build}
WORK=${NOISE_DIR:-/tmp/ef-noise}
APPS=$BUILD/apps
AF=$BUILD/bench/cgal_reconstruct_reference
mkdir -p "$WORK"

chamfer() {  # MESH GT -> "0.1234%"
  "$APPS/gcs-eval" "$1" "$2" 2>/dev/null | awk '/^chamfer-L1:/ { gsub(/[()]/, "", $3); print $3; exit }'
}
shape_of() {  # MESH -> "closed" or "N loops"
  "$APPS/gcs-eval" "$1" "$1" 2>/dev/null | awk '/^components:/ { if ($0 ~ /closed/) print "closed"; else { sub(/,$/, "", $5); print $5 " loops" }; exit }'
}

row() {  # NAME CLOUD TRUTH VERTICES
  local name=$1 cloud=$2 truth=$3 vertices=$4 out
  local ratio=""
  out=$("$APPS/gcs-reconstruct" "$cloud" -o "$WORK/$name-gcs.ply" --vertices "$vertices" -q)
  ratio=$(echo "$out" | sed -n 's/.*cloud smoothed first (noise \([0-9.e-]*\) of the point spacing).*/\1/p')
  [[ -n $ratio ]] && ratio=$(printf '%.3f' "$ratio")
  "$APPS/gcs-reconstruct" "$cloud" -o "$WORK/$name-raw.ply" --vertices "$vertices" -q --keep-noise > /dev/null
  local af_truth="-" af_cloud="-"
  if [[ -x $AF ]]; then
    "$AF" "$cloud" -o "$WORK/af-$name" > /dev/null 2>&1 || true
    local af; af=$(ls "$WORK/af-$name"/*-advancing-front.off 2>/dev/null | head -1 || true)
    if [[ -n $af ]]; then af_truth=$(chamfer "$af" "$truth"); af_cloud=$(chamfer "$af" "$cloud"); fi
  fi
  echo "| $name | ${ratio:-below 0.05: not smoothed} | $(chamfer "$WORK/$name-gcs.ply" "$truth") ($(shape_of "$WORK/$name-gcs.ply")) | $(chamfer "$WORK/$name-raw.ply" "$truth") ($(shape_of "$WORK/$name-raw.ply")) | $af_truth | $(chamfer "$WORK/$name-gcs.ply" "$cloud") | $(chamfer "$WORK/$name-raw.ply" "$cloud") | $af_cloud |"
}

echo "| cloud | estimated noise / spacing | truth: gcs (default) | truth: gcs --keep-noise | truth: advancing front | cloud: gcs | cloud: --keep-noise | cloud: advancing front |"
echo "|---|---|---|---|---|---|---|---|"
"$APPS/ef-shapes" bumpy-sphere --mesh --resolution 256 -o "$WORK/bumpy-truth.off" > /dev/null
for sigma in 0 0.0007 0.0015 0.003 0.006; do
  "$APPS/ef-shapes" bumpy-sphere --points 5210 --noise "$sigma" -o "$WORK/bumpy-$sigma.xyz" > /dev/null
  row "bumpy-sphere-s$sigma" "$WORK/bumpy-$sigma.xyz" "$WORK/bumpy-truth.off" 5000
done
for shape in torus pointed-vault; do
  "$APPS/ef-shapes" $shape --mesh --resolution 128 -o "$WORK/$shape-truth.off" > /dev/null
  "$APPS/ef-shapes" $shape --points 8000 --noise 0.006 -o "$WORK/$shape-0.006.xyz" > /dev/null
  row "$shape-s0.006" "$WORK/$shape-0.006.xyz" "$WORK/$shape-truth.off" 5000
done
if [[ -f $ROOT/data/models/sphere_20k.xyz ]]; then
  "$APPS/ef-shapes" icosphere --mesh --resolution 256 -o "$WORK/unit-sphere.off" > /dev/null
  row sphere_20k "$ROOT/data/models/sphere_20k.xyz" "$WORK/unit-sphere.off" 10000
fi
