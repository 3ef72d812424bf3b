#!/usr/bin/env bash
# scripts/bench-twist-heal.sh: issue 26, goal 1 - repairing finished twisted meshes with an oriented
# reference cloud, as a user would: sample a vault (ef-shapes), reconstruct it with the published
# loop's plain winners and no twist repair (gcs-reconstruct --no-orient-winners --no-twist), then
# `ef-twist MESH --points CLOUD -o FIXED`. One table row per run: consistency with the cloud
# before -> after, area removed (net: (area before - after) / before), components before -> after,
# regions flipped, twist lines cut, cut edges, what mending the small rejected patches did, and
# recall at 1% of the diagonal against the scan before -> after (gcs-eval: surface the repair lost).
#
#   scripts/bench-twist-heal.sh [SEEDS...]          (default seeds: 1 2 3)
#   CASES="vault-shell:0.2:1500 ..." scripts/bench-twist-heal.sh 1 2
#
# CASES: shape:thickness:vertices ('-' for no thickness). Points: POINTS (default 20000).
# EXTRA: more ef-twist options (e.g. "--cut-cost 2" or "--detector"). Runs under nice -n 5.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
B=${EDGEFRONT_BUILD_DIR:-$ROOT/build}
OUT=${OUT:-/tmp/bench-twist-heal}
POINTS=${POINTS:-20000}
CASES=${CASES:-"vault-shell:0.3:1500 vault-shell:0.2:1500 vault-shell:0.2:3000 vault-shell:0.1:1650 vault-sheet:-:1500 pointed-vault:-:1500 groin-vault:-:1500"}
EXTRA=${EXTRA:-}
SEEDS=("$@")
[[ ${#SEEDS[@]} -gt 0 ]] || SEEDS=(1 2 3)
for app in ef-shapes gcs-reconstruct ef-twist gcs-eval; do
  [[ -x $B/apps/$app ]] || { echo "bench-twist-heal: $B/apps/$app is not built" >&2; exit 1; }
done
mkdir -p "$OUT"
echo "| shape | vertices | seed | consistency before -> after | area removed | components before -> after | regions flipped | twist lines | cut edges | mended: swaps / moves / cut out | recall @1% before -> after | ef-twist s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for c in $CASES; do
  IFS=: read -r shape t verts <<<"$c"
  thick=()
  name=$shape
  if [[ $t != - ]]; then
    thick=(--thickness "$t")
    name="$shape t/R $t"
  fi
  for seed in "${SEEDS[@]}"; do
    base="$OUT/$shape-${t}-${verts}-s$seed"
    [[ -s $base.xyz ]] || nice -n 5 "$B/apps/ef-shapes" "$shape" "${thick[@]}" --points "$POINTS" --seed "$seed" -o "$base.xyz" >/dev/null
    [[ -s $base-raw.ply ]] || nice -n 5 "$B/apps/gcs-reconstruct" "$base.xyz" -o "$base-raw.ply" --vertices "$verts" --seed "$seed" \
      --no-orient-winners --no-twist -q >/dev/null
    start=$(date +%s.%N)
    # shellcheck disable=SC2086
    nice -n 5 "$B/apps/ef-twist" "$base-raw.ply" --points "$base.xyz" -o "$base-fixed.ply" $EXTRA >"$base-report.txt"
    secs=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
    cons=$(sed -n 's/^consistency: *\([0-9.e-]*\) -> \([0-9.e-]*\).*/\1 -> \2/p' "$base-report.txt")
    removed=$(sed -n 's/^faces removed: *[0-9]* (\([-0-9.e]*\)% .*/\1%/p' "$base-report.txt")
    comps=$(sed -n 's/^components: *//p' "$base-report.txt")
    regions=$(sed -n 's/^repairs: *//p' "$base-report.txt")
    lines=$(sed -n 's/^twist lines cut: *//p' "$base-report.txt")
    mended=$(sed -n 's/^mended: *\([0-9]*\) edges swapped, \([0-9]*\) vertices moved, \([0-9]*\) faces cut out.*/\1 \/ \2 \/ \3/p' "$base-report.txt")
    # Surface lost, as the scan sees it: the share of the scan within 1% of the diagonal of the mesh.
    recall() { "$B/apps/gcs-eval" "$1" "$base.xyz" --samples 20000 --no-self-intersections --threads 1 |
      sed -n 's/^F-score @ 1.00%:.*recall \([0-9.]*\),.*/\1/p'; }
    rec="$(recall "$base-raw.ply") -> $(recall "$base-fixed.ply")"
    cut=$(awk 'match($0, /cut (along )?[0-9]+ edges/) { t = substr($0, RSTART, RLENGTH); gsub(/[^0-9]/, "", t); s += t } END { print s + 0 }' "$base-report.txt")
    printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %.2f |\n' "$name" "$verts" "$seed" "$cons" "$removed" "$comps" "$regions" "${lines:--}" \
      "${cut:-0}" "${mended:--}" "$rec" "$secs"
  done
done
