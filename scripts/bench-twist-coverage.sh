#!/usr/bin/env bash
# scripts/bench-twist-coverage.sh: issue 26, goal 3 - does the twist repair in the default loop lower
# coverage? The same runs (gcs-reconstruct defaults) with and without the repair (--no-twist),
# measured by gcs-eval against the shape's fine mesh: coverage = recall at 1% of the diagonal (the
# share of the shape within 1% of the diagonal of the result), Hausdorff-95 in % of the diagonal.
#
#   scripts/bench-twist-coverage.sh [SEEDS...]       (default seeds: 1 2 3 4 5)
#   CASES="vault-shell:0.08:1500 ..." scripts/bench-twist-coverage.sh 1 2
#   TAG=new EXTRA="--some-flag" scripts/bench-twist-coverage.sh 1 2   (the runs with repair of a variant)
#
# CASES: shape:thickness:vertices ('-' for no thickness; default: every vault shape, see below);
# POINTS (default 20000). Runs under nice -n 5. Outputs in OUT (default /tmp/bench-twist-coverage),
# reused when present (the runs are deterministic per seed). TAG names the runs with repair (default
# "twist"), EXTRA adds gcs-reconstruct flags to them. After the per-run table, a summary per case:
# mean and worst difference with - without (coverage points) and how often with < without.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
B=${EDGEFRONT_BUILD_DIR:-$ROOT/build}
OUT=${OUT:-/tmp/bench-twist-coverage}
POINTS=${POINTS:-20000}
# The vault shells at 1500 vertices (t/R 0.3-0.08; at t/R 0.1 the mean edge is about t) and at
# t/R 0.05 at edge = t (6191 vertices, as bench_twist --edge-per-thickness 1); the other vaults at 1500.
CASES=${CASES:-"vault-shell:0.3:1500 vault-shell:0.2:1500 vault-shell:0.1:1500 vault-shell:0.08:1500 vault-shell:0.05:6191 vault-sheet:-:1500 pointed-vault:-:1500 groin-vault:-:1500"}
TAG=${TAG:-twist}
read -r -a EXTRA_FLAGS <<<"${EXTRA:-}"
SEEDS=("$@")
[[ ${#SEEDS[@]} -gt 0 ]] || SEEDS=(1 2 3 4 5)
for app in ef-shapes gcs-reconstruct gcs-eval; do
  [[ -x $B/apps/$app ]] || { echo "bench-twist-coverage: $B/apps/$app is not built" >&2; exit 1; }
done
mkdir -p "$OUT"
field() { /usr/bin/python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))' "$@"; }
echo "| shape | vertices | seed | coverage without / with repair | Hausdorff-95 % without / with | consistency without / with | components without / with | twist summary |"
echo "|---|---|---|---|---|---|---|---|"
summary_rows=()
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
    for mode in plain "$TAG"; do
      flags=()
      if [[ $mode == plain ]]; then flags=(--no-twist); else flags=("${EXTRA_FLAGS[@]}"); fi
      [[ -s $base-$mode.ply ]] || nice -n 5 "$B/apps/gcs-reconstruct" "$base.xyz" -o "$base-$mode.ply" --vertices "$verts" --seed "$seed" \
        "${flags[@]}" -q >"$base-$mode.log"
      [[ -s $base-$mode.json ]] || nice -n 5 "$B/apps/gcs-eval" "$base-$mode.ply" "$gt" --json --no-self-intersections >"$base-$mode.json"
    done
    cov() { field "$1" "'%.4f' % d['fscores'][1]['recall']"; }
    h95() { field "$1" "'%.2f' % d['hausdorff_p95_percent']"; }
    comps() { field "$1" "len(d['orientation_consistency']['components'])"; }
    cons() { field "$1" "'%.4f' % d['orientation_consistency']['raw']"; }
    summary=$(sed -n 's/.*twist-repair: \([^,]*found\), \([^)]*)\).*/\1, \2/p' "$base-$TAG.log")
    c0=$(cov "$base-plain.json")
    c1=$(cov "$base-$TAG.json")
    printf '| %s | %s | %s | %s / %s | %s / %s | %s / %s | %s / %s | %s |\n' "$name" "$verts" "$seed" "$c0" "$c1" \
      "$(h95 "$base-plain.json")" "$(h95 "$base-$TAG.json")" "$(cons "$base-plain.json")" "$(cons "$base-$TAG.json")" \
      "$(comps "$base-plain.json")" "$(comps "$base-$TAG.json")" "$summary"
    summary_rows+=("$name|$verts|$c0|$c1|$(cons "$base-$TAG.json")")
  done
done
echo
echo "| shape | vertices | runs | coverage with - without: mean / worst (points) | runs with < without | consistency with: min |"
echo "|---|---|---|---|---|---|"
printf '%s\n' "${summary_rows[@]}" | /usr/bin/python3 -c '
import sys
cases = {}
for line in sys.stdin:
    name, verts, c0, c1, k1 = line.strip().split("|")
    cases.setdefault((name, verts), []).append((float(c0), float(c1), float(k1)))
for (name, verts), runs in cases.items():
    d = [100 * (c1 - c0) for c0, c1, _ in runs]
    print("| %s | %s | %d | %+.2f / %+.2f | %d | %.4f |" % (name, verts, len(runs), sum(d) / len(d), min(d),
          sum(1 for c0, c1, _ in runs if c1 < c0), min(k for _, _, k in runs)))
'
