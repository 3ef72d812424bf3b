#!/usr/bin/env bash
# scripts/bench-closed.sh: the reconstructor on clouds sampled from closed models (issue 25).
#
#   scripts/bench-closed.sh [BUILD_DIR] [SEEDS] [MODELS...]
#       defaults: build, 5, and the closed CGAL sample models below that are on this machine
#
# For every model and seed: a 20,000-point cloud sampled area-uniformly from the model's triangles
# with their normals (bench/sample_mesh.py, the seed also seeds the sampling), reconstructed at
# 5,000 vertices with its normals and without them (--ignore-normals), each judged by gcs-eval
# against the model mesh (exact point-to-triangle distances both ways): border loops (closed = 0),
# genus and components against the model's, Chamfer-L1, Hausdorff-95 and the F-score at 1%
# (distances in % of the model's bounding-box diagonal).
# Models: $CLOSED_MODELS_DIR (default /work/cgal-data/data/meshes, else data/models); work files in
# $CLOSED_DIR (default /tmp/ef-closed). Set CLOSED_VERTICES / CLOSED_POINTS to change 5000 / 20000,
# CLOSED_INPUTS="normals" or "points" to run one half only, CLOSED_FLAGS to pass more options to
# gcs-reconstruct (e.g. "--no-orient-winners").
# Writes the raw rows to $CLOSED_DIR/runs.tsv and prints a markdown summary
# (bench/closed_summary.py) on stdout.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:-$ROOT/build}
SEEDS=${2:-5}
shift $(( $# >= 2 ? 2 : $# ))
WORK=${CLOSED_DIR:-/tmp/ef-closed}
VERTICES=${CLOSED_VERTICES:-5000}
POINTS=${CLOSED_POINTS:-20000}
INPUTS=${CLOSED_INPUTS:-normals points}
EXTRA=${CLOSED_FLAGS:-}
PY=/usr/bin/python3
MODELS_DIR=${CLOSED_MODELS_DIR:-}
if [[ -z $MODELS_DIR ]]; then
  if [[ -d /work/cgal-data/data/meshes ]]; then MODELS_DIR=/work/cgal-data/data/meshes; else MODELS_DIR=$ROOT/data/models; fi
fi
MODELS=("$@")
if [[ ${#MODELS[@]} -eq 0 ]]; then
  MODELS=(bull camel cow dino elk hand horse femur elephant man 3torus double-torus-example eight knot1)
fi
for app in gcs-reconstruct gcs-eval; do
  [[ -x $BUILD/apps/$app ]] || { echo "bench-closed: $BUILD/apps/$app is not built" >&2; exit 1; }
done
mkdir -p "$WORK"
TSV=$WORK/runs.tsv
printf 'model\tnormals\tseed\tseconds\tborder_loops\tgenus\tcomponents\tmodel_genus\tmodel_components\tchamfer_pct\th95_pct\tf1\n' > "$TSV"

field() {  # JSON_FILE EXPR: one value from gcs-eval --json
  "$PY" -c "import json,sys; e=json.load(open(sys.argv[1])); print($2)" "$1"
}

for model in "${MODELS[@]}"; do
  mesh=$MODELS_DIR/$model.off
  if [[ ! -f $mesh ]]; then
    echo "bench-closed: skipping $model (no $mesh)" >&2
    continue
  fi
  # The model's own genus and components, counted the way the results are.
  "$BUILD/apps/gcs-eval" "$mesh" "$mesh" --json --samples 1000 --no-self-intersections > "$WORK/$model-model.json"
  mg=$(field "$WORK/$model-model.json" 'e["mesh"]["genus"]')
  mc=$(field "$WORK/$model-model.json" 'e["mesh"]["components"]')
  for seed in $(seq 1 "$SEEDS"); do
    cloud=$WORK/$model-$seed.xyz
    [[ -f $cloud ]] || "$PY" "$ROOT/bench/sample_mesh.py" "$mesh" "$cloud" --points "$POINTS" --seed "$seed"
    for what in $INPUTS; do
      flag=
      [[ $what == points ]] && flag=--ignore-normals
      out=$WORK/$model-$seed-$what.ply
      start=$(date +%s.%N)
      if ! "$BUILD/apps/gcs-reconstruct" "$cloud" -o "$out" --vertices "$VERTICES" --seed "$seed" -q $flag $EXTRA \
          > "$out.log" 2>&1; then
        echo "bench-closed: $model seed $seed $what failed: $(tail -1 "$out.log")" >&2
        printf '%s\t%s\t%s\tfailed\t\t\t\t%s\t%s\t\t\t\n' "$model" "$what" "$seed" "$mg" "$mc" >> "$TSV"
        continue
      fi
      took=$(echo "$(date +%s.%N) - $start" | bc)
      "$BUILD/apps/gcs-eval" "$out" "$mesh" --json --samples 50000 --no-self-intersections > "$out.json"
      printf '%s\t%s\t%s\t%.1f\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$model" "$what" "$seed" "$took" \
        "$(field "$out.json" 'e["mesh"]["border_loops"]')" "$(field "$out.json" 'e["mesh"]["genus"]')" \
        "$(field "$out.json" 'e["mesh"]["components"]')" "$mg" "$mc" \
        "$(field "$out.json" 'e["chamfer_l1_percent"]')" "$(field "$out.json" 'e["hausdorff_p95_percent"]')" \
        "$(field "$out.json" '[f["fscore"] for f in e["fscores"] if abs(f["threshold_fraction"] - 0.01) < 1e-9][0]')" \
        >> "$TSV"
    done
  done
done
"$PY" "$ROOT/bench/closed_summary.py" "$TSV"
