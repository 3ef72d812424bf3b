#!/usr/bin/env bash
# scripts/bench-models.sh: the reconstructor on the vertex sets of CGAL's six sample meshes (issue 6).
#
#   scripts/bench-models.sh [BUILD_DIR] [SEEDS]      (default: build, 3; needs data/fetch-models.sh)
#
# Each model's vertices, without normals, are the cloud (a clean scan, sampled unevenly and coarsely
# for its detail); gcs-reconstruct (default app) rebuilds a mesh at about 70% of the vertex count
# (at most 5,000), and gcs-eval measures it against the model's own mesh. Prints a markdown table
# on stdout: the model's components / border loops / genus, then per seed the result's.
# Work files go to $MODELS_DIR (default /tmp/ef-models).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:-$ROOT/build}
SEEDS=${2:-3}
WORK=${MODELS_DIR:-/tmp/ef-models}
APPS=$BUILD/apps
mkdir -p "$WORK"

topology() {  # MESH -> "components / loops / genus"
  "$APPS/ef-info" "$1" 2>/dev/null | awk '
    /^components:/ { c = $2 } /^border loops:/ { l = $3 }
    /genus/ { for (i = 1; i <= NF; ++i) if ($i == "genus") g = g (g == "" ? "" : "+") $(i + 1); sub(/;$/, "", g) }
    END { print c " / " l " / " g }'
}

echo "| model (vertices) | model: components / loops / genus | target | seed | result: components / loops / genus | Chamfer-L1 (% diag.) | orientation consistency | self-intersecting pairs | time |"
echo "|---|---|---|---|---|---|---|---|---|"
for m in elephant homer ChineseDragon-10kv man armadillo bunny00; do
  model=$ROOT/data/models/$m.off
  [[ -f $model ]] || { echo "missing $model (run data/fetch-models.sh)" >&2; exit 1; }
  n=$(awk 'NR == 2 { print $1; exit }' "$model")
  target=$(( n * 7 / 10 )); (( target > 5000 )) && target=5000
  truth=$(topology "$model")
  for seed in $(seq 1 "$SEEDS"); do
    out=$WORK/$m-$seed.ply
    start=$(date +%s.%N)
    "$APPS/gcs-reconstruct" "$model" -o "$out" --vertices "$target" --seed "$seed" -q > /dev/null
    took=$(echo "$(date +%s.%N) - $start" | bc)
    "$APPS/gcs-eval" "$out" "$model" > "$WORK/$m-$seed.eval" 2>/dev/null
    chamfer=$(awk '/^chamfer-L1:/ { gsub(/[()]/, "", $3); print $3; exit }' "$WORK/$m-$seed.eval")
    orient=$(awk '/^orientation consistency:/ { print $3; exit }' "$WORK/$m-$seed.eval")
    selfint=$(awk '/^self-intersecting pairs:/ { print $3; exit }' "$WORK/$m-$seed.eval")
    printf '| %s (%s) | %s | %s | %s | %s | %s | %s | %s | %.1f s wall |\n' "$m" "$n" "$truth" "$target" "$seed" \
      "$(topology "$out")" "$chamfer" "$orient" "$selfint" "$took"
  done
done
