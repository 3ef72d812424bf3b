#!/usr/bin/env bash
# scripts/bench-twist-coverage.sh: issue 26, goal 3 - does the twist repair in the default loop lower
# coverage? The same runs (gcs-reconstruct defaults) with and without the repair (--no-twist),
# measured by gcs-eval against the shape's fine mesh: coverage = recall at 1% of the diagonal (the
# share of the shape within 1% of the diagonal of the result), Hausdorff-95 in % of the diagonal.
#
#   scripts/bench-twist-coverage.sh [SEEDS...]       (default seeds: 1 2 3 4 5)
#   CASES="vault-shell:0.08:1500 ..." scripts/bench-twist-coverage.sh 1 2
#
# CASES: shape:thickness:vertices ('-' for no thickness); POINTS (default 20000). Runs under nice -n 5.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
B=${EDGEFRONT_BUILD_DIR:-$ROOT/build}
OUT=${OUT:-/tmp/bench-twist-coverage}
POINTS=${POINTS:-20000}
CASES=${CASES:-"vault-shell:0.08:1500"}
SEEDS=("$@")
[[ ${#SEEDS[@]} -gt 0 ]] || SEEDS=(1 2 3 4 5)
for app in ef-shapes gcs-reconstruct gcs-eval; do
  [[ -x $B/apps/$app ]] || { echo "bench-twist-coverage: $B/apps/$app is not built" >&2; exit 1; }
done
mkdir -p "$OUT"
field() { /usr/bin/python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))' "$@"; }
echo "| shape | vertices | seed | coverage without / with repair | Hausdorff-95 % without / with | components without / with | twist summary |"
echo "|---|---|---|---|---|---|---|"
for c in $CASES; do
  IFS=: read -r shape t verts <<<"$c"
  thick=()
  name=$shape
  if [[ $t != - ]]; then
    thick=(--thickness "$t")
    name="$shape t/R $t"
  fi
  gt="$OUT/$shape-$t-gt.off"
  [[ -s $gt ]] || nice -n 5 "$B/apps/ef-shapes" "$shape" "${thick[@]}" --mesh --resolution 128 -o "$gt" >/dev/null
  for seed in "${SEEDS[@]}"; do
    base="$OUT/$shape-$t-$verts-s$seed"
    [[ -s $base.xyz ]] || nice -n 5 "$B/apps/ef-shapes" "$shape" "${thick[@]}" --points "$POINTS" --seed "$seed" -o "$base.xyz" >/dev/null
    for mode in plain twist; do
      flags=()
      [[ $mode == plain ]] && flags=(--no-twist)
      [[ -s $base-$mode.ply ]] || nice -n 5 "$B/apps/gcs-reconstruct" "$base.xyz" -o "$base-$mode.ply" --vertices "$verts" --seed "$seed" \
        "${flags[@]}" -q >"$base-$mode.log"
      [[ -s $base-$mode.json ]] || nice -n 5 "$B/apps/gcs-eval" "$base-$mode.ply" "$gt" --json --no-self-intersections >"$base-$mode.json"
    done
    cov() { field "$1" "'%.4f' % d['fscores'][1]['recall']"; }
    h95() { field "$1" "'%.2f' % d['hausdorff_p95_percent']"; }
    comps() { field "$1" "len(d['orientation_consistency']['components'])"; }
    summary=$(sed -n 's/.*twist-repair: \([^,]*found\), \([^)]*)\).*/\1, \2/p' "$base-twist.log")
    printf '| %s | %s | %s | %s / %s | %s / %s | %s / %s | %s |\n' "$name" "$verts" "$seed" \
      "$(cov "$base-plain.json")" "$(cov "$base-twist.json")" "$(h95 "$base-plain.json")" "$(h95 "$base-twist.json")" \
      "$(comps "$base-plain.json")" "$(comps "$base-twist.json")" "$summary"
  done
done
