#!/usr/bin/env bash
# scripts/bench-exact-vs-cgal.sh: one full distance field per model and source, computed by CGAL's
# exact Surface_mesh_shortest_path and by `ef-distance --method windows|mdf|dijkstra`, each in its
# own process, in the same run. Prints a markdown table on stdout: process CPU time (user + sys,
# mesh loading included for every method), peak resident memory, and the relative error of each
# method against CGAL's exact distances (mean and max over the reached vertices but the source).
#
#   scripts/bench-exact-vs-cgal.sh [--models "a b ..."] [--sources "17 4242"]
#
# Needs a build with CGAL and the bench tools (cmake -DEDGEFRONT_BUILD_BENCH=ON, the default when
# CGAL is found), the models in data/models (data/fetch-models.sh) and python3.
# Environment: EDGEFRONT_BUILD_DIR (default build), WORK_DIR (default a fresh temporary folder).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${EDGEFRONT_BUILD_DIR:-$ROOT/build}
MODELS="elephant homer ChineseDragon-10kv man armadillo bunny00"
SOURCES="17"
while [ $# -gt 0 ]; do
  case "$1" in
    --models) shift; MODELS="$1" ;;
    --sources) shift; SOURCES="$1" ;;
    *) echo "bench-exact-vs-cgal: unknown argument '$1'" >&2; exit 2 ;;
  esac
  shift
done
CGAL=$BUILD/bench/cgal_geodesic_reference
DIST=$BUILD/apps/ef-distance
for tool in "$CGAL" "$DIST"; do
  [ -x "$tool" ] || { echo "bench-exact-vs-cgal: $tool is missing (build with CGAL and the bench tools)" >&2; exit 1; }
done
WORK=${WORK_DIR:-$(mktemp -d)}
mkdir -p "$WORK"

echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), load $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| model | vertices | source | method | CPU s | peak RSS MiB | time / CGAL exact | mean rel. error | max rel. error |"
echo "|---|---|---|---|---|---|---|---|---|"
for model in $MODELS; do
  mesh=$ROOT/data/models/$model.off
  [ -f "$mesh" ] || { echo "bench-exact-vs-cgal: $mesh is missing (run data/fetch-models.sh)" >&2; exit 1; }
  for s in $SOURCES; do
    /usr/bin/time -f "%U %S %M" -o "$WORK/time.cgal" "$CGAL" "$mesh" --sources "$s" -o "$WORK/$model" >/dev/null 2>&1
    for method in windows mdf dijkstra; do
      /usr/bin/time -f "%U %S %M" -o "$WORK/time.$method" "$DIST" "$mesh" --source "$s" --method "$method" \
        -o "$WORK/$model.$s.$method.txt" 2>/dev/null
    done
    python3 - "$WORK" "$model" "$s" <<'EOF'
import math, struct, sys
work, model, s = sys.argv[1], sys.argv[2], int(sys.argv[3])
raw = open(f"{work}/{model}.exact.{s}.bin", "rb").read()
exact = struct.unpack(f"<{len(raw) // 8}d", raw)
def cpu(name):
    u, sy, kb = open(f"{work}/time.{name}").read().split()
    return float(u) + float(sy), int(kb) / 1024.0
base, base_rss = cpu("cgal")
print(f"| {model} | {len(exact)} | {s} | CGAL exact | {base:.2f} | {base_rss:.0f} | 1 | (reference) | |")
for method in ("windows", "mdf", "dijkstra"):
    got = [float(x) for x in open(f"{work}/{model}.{s}.{method}.txt")]
    errs = [abs(g - e) / e for g, e in zip(got, exact) if e > 0 and math.isfinite(e)]
    t, rss = cpu(method)
    ratio = t / base if base > 0 else float("nan")
    print(f"| {model} | {len(exact)} | {s} | {method} | {t:.2f} | {rss:.0f} | {ratio:.3f} | "
          f"{100 * sum(errs) / len(errs):.2g}% | {100 * max(errs):.2g}% |")
EOF
  done
done
