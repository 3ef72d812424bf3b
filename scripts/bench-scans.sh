#!/usr/bin/env bash
# scripts/bench-scans.sh: the reconstructor on a real one-sided scan (issue 6).
#
#   scripts/bench-scans.sh [BUILD_DIR] [SEEDS]      (default: build, 3; needs data/fetch-models.sh)
#
# CGAL's hippo1.ply (6,104 oriented points, scanned from one side: an open sheet whose head and
# legs lie apart from the body where the scan saw them behind other parts) at 5,000 vertices,
# with its normals and without them (--ignore-normals: the points alone), judged by gcs-eval against the points
# (Chamfer-L1 and the 95th percentile of the Hausdorff distance in % of the diagonal, F-score at
# 1%, orientation consistency against the scan's normals). With BUILD_DIR/bench/
# cgal_reconstruct_reference (CGAL installed) also CGAL's advancing front and Poisson, judged the
# same way. Prints a markdown table on stdout. Work files go to $SCANS_DIR (default /tmp/ef-scans).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:-$ROOT/build}
SEEDS=${2:-3}
WORK=${SCANS_DIR:-/tmp/ef-scans}
APPS=$BUILD/apps
SCAN=$ROOT/data/models/hippo1.ply
[[ -f $SCAN ]] || { echo "missing $SCAN (run data/fetch-models.sh)" >&2; exit 1; }
mkdir -p "$WORK"

row() {  # LABEL MESH SECONDS
  "$APPS/gcs-eval" "$2" "$SCAN" > "$2.eval" 2>/dev/null
  awk -v label="$1" -v took="$3" '
    /^chamfer-L1:/ { c = $3; gsub(/[()]/, "", c) }
    /^hausdorff 95%:/ { h = $4; gsub(/[()]/, "", h) }
    /^F-score @ 1.00%:/ { f = $4 }
    /^orientation consistency:/ { o = $3 }
    /^components:/ { k = $2; l = $5; gsub(/,/, "", k); gsub(/,/, "", l) }
    END { printf "| %s | %s / %s | %s | %s | %s | %s | %s |\n", label, k, l, c, h, f, o, took }' "$2.eval"
}

echo "| run | components / border loops | Chamfer-L1 | Hausdorff 95% | F-score @ 1% | orientation consistency | time |"
echo "|---|---|---|---|---|---|---|"
for flag in "" --ignore-normals; do
  what=normals
  [[ -n $flag ]] && what="points only"
  for seed in $(seq 1 "$SEEDS"); do
    out=$WORK/hippo1-$seed-${what// /-}.ply
    start=$(date +%s.%N)
    "$APPS/gcs-reconstruct" "$SCAN" -o "$out" --vertices 5000 --seed "$seed" -q $flag > /dev/null
    row "ours, $what, seed $seed" "$out" "$(printf '%.1f s' "$(echo "$(date +%s.%N) - $start" | bc)")"
  done
done
if [[ -x $BUILD/bench/cgal_reconstruct_reference ]]; then
  "$BUILD/bench/cgal_reconstruct_reference" "$SCAN" -o "$WORK" > "$WORK/cgal.log"
  row "CGAL advancing front" "$WORK/hippo1-advancing-front.off" "-"
  row "CGAL Poisson" "$WORK/hippo1-poisson.off" "-"
fi
