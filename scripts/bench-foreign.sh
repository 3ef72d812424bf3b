#!/usr/bin/env bash
# scripts/bench-foreign.sh: the foreign GCS host (examples/foreign_gcs) on closed vault shells,
# without and with EdgeFront's twist repair (issue 23's measurement).
#
#   scripts/bench-foreign.sh [--first S] [--seeds N] [--vertices V] [--points P] [--thickness T] [--modes "M ..."] [--build DIR] [--out DIR]
#
# Defaults: seeds 1-10 (--first S --seeds N: seeds S .. S+N-1), 3000 vertices, 20000 oriented points, t/R 0.2 (R = 1). Per seed: a cloud
# from ef-shapes (seed S), foreign-gcs in each mode (seed S): plain (--no-twist), repair, heal
# (the repair with the session's border heal, --heal), heal2 (the heal zipping within 2 mean edges,
# --heal --heal-gap 2), grow (the heal with 2 rows of border growth per repair, repairs from 600
# vertices on, pieces under 1% of the largest dropped at the end: --grow 2 --repair-from 600
# --min-piece 0.01), heal600 (the heal alone, repairs from 600 vertices on: --heal --repair-from 600);
# default modes "plain repair heal". Each result
# judged by gcs-eval against a denser sample of the same shape (200000 points, seed 1000 + S):
# orientation consistency "raw" (share of the area whose normal agrees with the nearest
# ground-truth normal, no sign forgiven), "per component" (each component with its better sign),
# components and border loops. Needs a build with the targets foreign-gcs, ef-shapes and gcs-eval.
# Prints a Markdown table (one row per run) and a summary; the meshes stay in --out.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
MODES="plain repair heal" FIRST=1 SEEDS=10 VERTICES=3000 POINTS=20000 THICKNESS=0.2 BUILD=$ROOT/build OUT=${TMPDIR:-/tmp}/bench-foreign
while (($#)); do
  case $1 in
    --first) FIRST=$2; shift 2 ;;
    --seeds) SEEDS=$2; shift 2 ;;
    --vertices) VERTICES=$2; shift 2 ;;
    --points) POINTS=$2; shift 2 ;;
    --thickness) THICKNESS=$2; shift 2 ;;
    --modes) MODES=$2; shift 2 ;;
    --build) BUILD=$2; shift 2 ;;
    --out) OUT=$2; shift 2 ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    *) echo "bench-foreign.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
for mode in $MODES; do
  case $mode in plain|repair|heal|heal2|grow|heal600) ;; *) echo "bench-foreign.sh: unknown mode $mode (plain, repair, heal, heal2, grow, heal600)" >&2; exit 2 ;; esac
done
FOREIGN=$BUILD/examples/foreign_gcs/foreign-gcs
SHAPES=$BUILD/apps/ef-shapes
EVAL=$BUILD/apps/gcs-eval
for b in "$FOREIGN" "$SHAPES" "$EVAL"; do
  [[ -x $b ]] || { echo "bench-foreign.sh: $b missing (cmake --build $BUILD --target foreign-gcs ef-shapes gcs-eval)" >&2; exit 1; }
done
mkdir -p "$OUT"
PY=/usr/bin/python3
echo "# foreign-gcs on vault-shell t/R $THICKNESS, $VERTICES vertices, $POINTS points; $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%FT%TZ)"
echo
echo "| seed | repair | raw | per component | components | border loops | vertices | faces | far probes | step cap | wall s | session s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for ((s = FIRST; s < FIRST + SEEDS; ++s)); do
  cloud=$OUT/cloud-$s.xyz gt=$OUT/gt-$s.xyz
  [[ -s $cloud ]] || "$SHAPES" vault-shell --points "$POINTS" --thickness "$THICKNESS" --seed "$s" -o "$cloud" 2>/dev/null
  [[ -s $gt ]] || "$SHAPES" vault-shell --points 200000 --thickness "$THICKNESS" --seed $((1000 + s)) -o "$gt" 2>/dev/null
  for mode in $MODES; do
    mesh=$OUT/$mode-$s.off
    flags=()
    case $mode in
      plain) flags=(--no-twist) ;;
      repair) ;;
      heal) flags=(--heal) ;;
      heal2) flags=(--heal --heal-gap 2) ;;
      grow) flags=(--grow 2 --repair-from 600 --min-piece 0.01) ;;
      heal600) flags=(--heal --repair-from 600) ;;
    esac
    start=$(date +%s.%N)
    log=$("$FOREIGN" "$cloud" -o "$mesh" --vertices "$VERTICES" --seed "$s" ${flags[@]+"${flags[@]}"} 2>&1)
    wall=$(echo "$(date +%s.%N) - $start" | bc)
    "$EVAL" "$mesh" "$gt" --json --no-self-intersections >"$OUT/$mode-$s.json"
    echo "$log" >"$OUT/$mode-$s.log"
    "$PY" - "$s" "$mode" "$wall" "$log" "$OUT/$mode-$s.json" <<'PY'
import json, re, sys
seed, mode, wall, log, path = sys.argv[1:6]
e = json.load(open(path))
o, m = e["orientation_consistency"], e["mesh"]
far = re.search(r"far probes (\d+) of (\d+)", log)
sess = re.search(r"session ([0-9.]+) s", log)
print(f"| {seed} | {mode} | {o['raw']:.4f} | {o['per_component']:.4f} | {m['components']} | {m['border_loops']} | "
      f"{m['vertices']} | {m['faces']} | {far.group(1)}/{far.group(2)} | {'yes' if 'step limit' in log else ''} | "
      f"{float(wall):.1f} | {float(sess.group(1)):.1f} |")
PY
  done
done | tee "$OUT/table.md"
"$PY" - "$OUT/table.md" <<'PY'
import sys
rows = [l.split("|")[1:-1] for l in open(sys.argv[1]) if l.startswith("| ") and not l.startswith("| seed")]
for mode in ("plain", "repair", "heal", "heal2", "heal600", "grow"):
    r = [[c.strip() for c in x] for x in rows if x[1].strip() == mode]
    if not r: continue
    raw = [float(x[2]) for x in r]; comp = [int(x[4]) for x in r]; cap = sum(x[9] == "yes" for x in r)
    print(f"\n{mode}: raw {min(raw):.4f}-{max(raw):.4f} (median {sorted(raw)[len(raw)//2]:.4f}); "
          f">= 0.99 in {sum(v >= 0.99 for v in raw)}/{len(r)}; < 0.9 in {sum(v < 0.9 for v in raw)}/{len(r)}; "
          f"one piece in {sum(c == 1 for c in comp)}/{len(r)} (components {min(comp)}-{max(comp)}); step cap in {cap}/{len(r)}")
PY
