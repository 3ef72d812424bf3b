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
# Peers (optional, default none): CLOSED_PEERS="cgal-poisson cgal-af open3d-poisson" runs each named
# reconstructor on the same cloud (with its normals) per model and seed, writes its mesh to
# $CLOSED_DIR/MODEL-SEED-PEER.off, judges it by the same gcs-eval against the model and adds a row to
# $CLOSED_DIR/peers.tsv (column "method" for "normals"; time = the peer's own reconstruction time);
# the summary then lists the peers per model and, per run, whether our Chamfer-L1 is <= Poisson's.
# cgal-poisson / cgal-af: BUILD_DIR/bench/cgal_reconstruct_reference (configure with
# -DEDGEFRONT_BUILD_BENCH=ON and CGAL installed), CGAL's defaults; open3d-poisson:
# bench/open3d_poisson.py (Debian's python3-open3d; depth CLOSED_O3D_DEPTH, default 8, untrimmed,
# one thread).
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

judged() {  # MESH JSON: gcs-eval of MESH against the model ($mesh) into JSON; prints the row's judged fields
  "$BUILD/apps/gcs-eval" "$1" "$mesh" --json --samples 50000 --no-self-intersections > "$2" || return 1
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s' \
    "$(field "$2" 'e["mesh"]["border_loops"]')" "$(field "$2" 'e["mesh"]["genus"]')" \
    "$(field "$2" 'e["mesh"]["components"]')" "$mg" "$mc" \
    "$(field "$2" 'e["chamfer_l1_percent"]')" "$(field "$2" 'e["hausdorff_p95_percent"]')" \
    "$(field "$2" '[f["fscore"] for f in e["fscores"] if abs(f["threshold_fraction"] - 0.01) < 1e-9][0]')"
}

# ---- Peers (CLOSED_PEERS): the other reconstructors on the same clouds, rows in peers.tsv ----
PEERS=${CLOSED_PEERS:-}
PEERS_TSV=$WORK/peers.tsv
O3D_DEPTH=${CLOSED_O3D_DEPTH:-8}
peers_start() {  # checks the peers' names and programs, writes peers.tsv's header
  local peer
  for peer in $PEERS; do
    case $peer in
      cgal-poisson|cgal-af)
        [[ -x $BUILD/bench/cgal_reconstruct_reference ]] || { echo "bench-closed: CLOSED_PEERS has $peer but" \
          "$BUILD/bench/cgal_reconstruct_reference is not built (configure with -DEDGEFRONT_BUILD_BENCH=ON; needs CGAL)" >&2; exit 2; } ;;
      open3d-poisson)
        "$PY" -c "import open3d" 2>/dev/null || { echo "bench-closed: CLOSED_PEERS has open3d-poisson but" \
          "$PY cannot import open3d (scripts/setup.sh --with-peers)" >&2; exit 2; }
        [[ $O3D_DEPTH =~ ^[1-9][0-9]?$ ]] && (( O3D_DEPTH <= 12 )) || {
          echo "bench-closed: CLOSED_O3D_DEPTH must be 1-12, got '$O3D_DEPTH'" >&2; exit 2; } ;;
      *) echo "bench-closed: CLOSED_PEERS: unknown peer '$peer' (cgal-poisson, cgal-af, open3d-poisson)" >&2; exit 2 ;;
    esac
  done
  printf 'model\tmethod\tseed\tseconds\tborder_loops\tgenus\tcomponents\tmodel_genus\tmodel_components\tchamfer_pct\th95_pct\tf1\tfaces_dropped\n' \
    > "$PEERS_TSV"
}
run_peers() {  # MODEL SEED CLOUD: every peer on the cloud, judged against the model like ours
  local model=$1 seed=$2 cloud=$3 peer out took fields
  for peer in $PEERS; do
    out=$WORK/$model-$seed-$peer.off
    took=
    case $peer in
      cgal-poisson|cgal-af)
        local method=poisson label="CGAL Poisson"
        [[ $peer == cgal-af ]] && method=advancing-front label="CGAL advancing front"
        if "$BUILD/bench/cgal_reconstruct_reference" "$cloud" -o "$WORK/cgal-$peer" --only "$method" --no-eval \
            > "$out.log" 2>&1 && mv "$WORK/cgal-$peer/$model-$seed-$method.off" "$out"; then
          took=$(sed -n "s/^== $label: \([0-9.e+-]*\) s,.*/\1/p" "$out.log")
        fi ;;
      open3d-poisson)
        if "$PY" "$ROOT/bench/open3d_poisson.py" "$cloud" "$out" --depth "$O3D_DEPTH" > "$out.log" 2>&1; then
          took=$(sed -n 's/^seconds: //p' "$out.log")
        fi ;;
    esac
    if [[ -z $took ]]; then
      echo "bench-closed: $model seed $seed $peer failed: $(tail -1 "$out.log")" >&2
      printf '%s\t%s\t%s\tfailed\t\t\t\t%s\t%s\t\t\t\t\n' "$model" "$peer" "$seed" "$mg" "$mc" >> "$PEERS_TSV"
      continue
    fi
    fields=$(judged "$out" "$out.json")
    printf '%s\t%s\t%s\t%.1f\t%s\t%s\n' "$model" "$peer" "$seed" "$took" "$fields" \
      "$(field "$out.json" 'e["mesh"]["faces_dropped_when_read"]')" >> "$PEERS_TSV"
  done
}
[[ -n $PEERS ]] && peers_start
# ---- end of the peers ----

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
      fields=$(judged "$out" "$out.json")  # an assignment, so that a failed gcs-eval stops the script
      printf '%s\t%s\t%s\t%.1f\t%s\n' "$model" "$what" "$seed" "$took" "$fields" >> "$TSV"
    done
    [[ -z $PEERS ]] || run_peers "$model" "$seed" "$cloud"
  done
done
if [[ -n $PEERS ]]; then
  "$PY" "$ROOT/bench/closed_summary.py" "$TSV" --peers "$PEERS_TSV"
else
  "$PY" "$ROOT/bench/closed_summary.py" "$TSV"
fi
