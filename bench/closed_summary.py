#!/usr/bin/python3
"""bench/closed_summary.py: the markdown summary of scripts/bench-closed.sh's runs.tsv.

    bench/closed_summary.py RUNS.tsv [RUNS_BASELINE.tsv]

Per model and normals/points: runs, closed runs (0 border loops), runs with the model's genus,
runs with the model's component count, all three, and Chamfer-L1 / Hausdorff-95 (% of the
diagonal) / F-score at 1% as median [min-max]; then the totals. With a second file (an earlier
run of the same set) the totals of both are printed side by side.
"""
import csv
import statistics
import sys
from collections import OrderedDict


def load(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f, delimiter="\t"))


def spread(values, fmt):
    if not values:
        return "-"
    return f"{fmt(statistics.median(values))} [{fmt(min(values))}-{fmt(max(values))}]"


def judge(r):
    ok = r["seconds"] != "failed"
    closed = ok and int(r["border_loops"]) == 0
    genus = ok and abs(float(r["genus"]) - float(r["model_genus"])) < 1e-9
    comps = ok and int(r["components"]) == int(r["model_components"])
    return ok, closed, genus, comps


def table(rows):
    groups = OrderedDict()
    for r in rows:
        groups.setdefault((r["model"], r["normals"]), []).append(r)
    out = ["| model | input | runs | closed | genus | components | all three | border loops | "
           "Chamfer-L1 % | Hausdorff-95 % | F-score @1% | time s |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for (model, what), rs in groups.items():
        j = [judge(r) for r in rs]
        good = [r for r, (ok, *_rest) in zip(rs, j) if ok]
        fl = lambda k: [float(r[k]) for r in good]
        out.append(
            f"| {model} (genus {float(rs[0]['model_genus']):g}, {rs[0]['model_components']} part) | {what} | {len(rs)} | "
            f"{sum(x[1] for x in j)} | {sum(x[2] for x in j)} | {sum(x[3] for x in j)} | "
            f"{sum(x[1] and x[2] and x[3] for x in j)} | "
            f"{spread([int(r['border_loops']) for r in good], lambda v: f'{v:g}')} | "
            f"{spread(fl('chamfer_pct'), lambda v: f'{v:.3f}')} | {spread(fl('h95_pct'), lambda v: f'{v:.2f}')} | "
            f"{spread(fl('f1'), lambda v: f'{v:.3f}')} | {spread(fl('seconds'), lambda v: f'{v:.1f}')} |")
    return out


def totals(rows):
    res = {}
    for what in ("normals", "points"):
        rs = [r for r in rows if r["normals"] == what]
        if not rs:
            continue
        j = [judge(r) for r in rs]
        good = [r for r, (ok, *_rest) in zip(rs, j) if ok]
        n = len(rs)
        res[what] = {
            "runs": n,
            "failed": n - len(good),
            "closed": sum(x[1] for x in j),
            "genus": sum(x[2] for x in j),
            "components": sum(x[3] for x in j),
            "all": sum(x[1] and x[2] and x[3] for x in j),
            "f1_ge_099": sum(float(r["f1"]) >= 0.99 for r in good),
            "h95_le_1": sum(float(r["h95_pct"]) <= 1.0 for r in good),
            "chamfer_median": statistics.median([float(r["chamfer_pct"]) for r in good]) if good else float("nan"),
            "loops_total": sum(int(r["border_loops"]) for r in good),
        }
    return res


def totals_lines(label, t):
    out = []
    for what, v in t.items():
        out.append(f"| {label} | {what} | {v['runs']} | {v['failed']} | {v['closed']} | {v['genus']} | "
                   f"{v['components']} | {v['all']} | {v['loops_total']} | {v['chamfer_median']:.3f} | "
                   f"{v['h95_le_1']} | {v['f1_ge_099']} |")
    return out


def main():
    rows = load(sys.argv[1])
    print("\n".join(table(rows)))
    print()
    print("| set | input | runs | failed | closed | genus | components | all three | border loops (sum) | "
          "Chamfer-L1 % median | Hausdorff-95 <= 1% | F-score >= 0.99 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    if len(sys.argv) > 2:
        print("\n".join(totals_lines("baseline", totals(load(sys.argv[2])))))
    print("\n".join(totals_lines("this run", totals(rows))))


if __name__ == "__main__":
    main()
