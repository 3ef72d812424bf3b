#!/usr/bin/python3
"""bench/closed_summary.py: the markdown summary of scripts/bench-closed.sh's runs.tsv.

    bench/closed_summary.py RUNS.tsv [RUNS_BASELINE.tsv] [--peers PEERS.tsv]

Per model and normals/points: runs, closed runs (0 border loops), runs with the model's genus,
runs with the model's component count, all three, and Chamfer-L1 / Hausdorff-95 (% of the
diagonal) / F-score at 1% as median [min-max]; then the totals. With a second file (an earlier
run of the same set) the totals of both are printed side by side.
With --peers (scripts/bench-closed.sh's peers.tsv: the other reconstructors on the same clouds)
the per-model table also lists each peer under its model, and two more tables follow: per run
(model and seed) our Chamfer-L1 with and without normals beside each Poisson's and whether ours
is <= Poisson's (issue 25's test), and the count of such runs per model and in all.
"""
import argparse
import csv
import statistics
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


def table(rows, peers=()):
    groups = OrderedDict()
    for r in rows:
        groups.setdefault((r["model"], r["normals"]), []).append(r)
    for r in peers:  # after our rows of the same model
        groups.setdefault((r["model"], r["method"]), []).append(dict(r, normals=r["method"]))
    if peers:
        models = list(OrderedDict.fromkeys(r["model"] for r in list(rows) + list(peers)))
        groups = OrderedDict(sorted(groups.items(), key=lambda kv: models.index(kv[0][0])))
    out = [f"| model | {'input or peer' if peers else 'input'} | runs | closed | genus | components | all three | border loops | "
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


def totals(rows, inputs=("normals", "points")):
    res = {}
    for what in inputs:
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


POISSONS = ("cgal-poisson", "open3d-poisson")


def chamfer(r):
    """A row's Chamfer-L1 in %; None for a failed run, "-" for no run."""
    if r is None:
        return "-"
    return None if r["seconds"] == "failed" else float(r["chamfer_pct"])


def peer_comparison(rows, peers):
    """Per run, ours (normals, points) against each Poisson of the peers on the same cloud:
    the per-run table and the per-model counts of runs where ours is <= Poisson's."""
    ours = {(r["model"], r["seed"], r["normals"]): r for r in rows}
    theirs = {(r["model"], r["seed"], r["method"]): r for r in peers}
    poissons = [p for p in POISSONS if any(k[2] == p for k in theirs)]
    inputs = [w for w in ("normals", "points") if any(k[2] == w for k in ours)]
    models = list(OrderedDict.fromkeys(r["model"] for r in list(rows) + list(peers)))
    runs = sorted(OrderedDict.fromkeys((r["model"], r["seed"]) for r in peers),
                  key=lambda run: (models.index(run[0]), int(run[1])))
    if not poissons or not inputs:
        return []
    fmt = lambda v: "failed" if v is None else v if v == "-" else f"{v:.3f}"
    head = ([f"ours {w}" for w in inputs] + poissons
            + [f"{w} <= {p}" for p in poissons for w in inputs])
    out = ["Per run: Chamfer-L1 % (ours and Poisson on the same cloud; a failed run of ours is not <=, "
           "a failed Poisson is left out of the count)", "",
           "| model | seed | " + " | ".join(head) + " |", "|---|---|" + "---|" * len(head)]
    counts = OrderedDict()
    for model, seed in runs:
        c = {w: chamfer(ours.get((model, seed, w))) for w in inputs}
        c.update({p: chamfer(theirs.get((model, seed, p))) for p in poissons})
        cells = [fmt(c[w]) for w in inputs] + [fmt(c[p]) for p in poissons]
        per = counts.setdefault(model, OrderedDict())
        for p in poissons:
            for w in inputs:
                n, k = per.get((w, p), (0, 0))
                if c[p] is None or c[p] == "-":
                    cells.append("-")
                    per[(w, p)] = (n, k)
                    continue
                ok = c[w] not in (None, "-") and c[w] <= c[p]
                cells.append("yes" if ok else "no")
                per[(w, p)] = (n + 1, k + ok)
        out.append(f"| {model} | {seed} | " + " | ".join(cells) + " |")
    keys = [(w, p) for p in poissons for w in inputs]
    out += ["", "Runs where our Chamfer-L1 <= Poisson's (of the runs where that Poisson gave a mesh)", "",
            "| model | " + " | ".join(f"{w} <= {p}" for w, p in keys) + " |", "|---|" + "---|" * len(keys)]
    total = {key: (0, 0) for key in keys}
    for model, per in counts.items():
        out.append(f"| {model} | " + " | ".join(f"{per[key][1]}/{per[key][0]}" for key in keys) + " |")
        for key in keys:
            total[key] = (total[key][0] + per[key][0], total[key][1] + per[key][1])
    out.append("| all | " + " | ".join(f"**{total[key][1]}/{total[key][0]}**" for key in keys) + " |")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs")
    ap.add_argument("baseline", nargs="?")
    ap.add_argument("--peers")
    a = ap.parse_args()
    rows = load(a.runs)
    peers = load(a.peers) if a.peers else []
    print("\n".join(table(rows, peers)))
    print()
    print("| set | input | runs | failed | closed | genus | components | all three | border loops (sum) | "
          "Chamfer-L1 % median | Hausdorff-95 <= 1% | F-score >= 0.99 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    if a.baseline:
        print("\n".join(totals_lines("baseline", totals(load(a.baseline)))))
    print("\n".join(totals_lines("this run", totals(rows))))
    if peers:
        methods = list(OrderedDict.fromkeys(r["method"] for r in peers))
        print("\n".join(totals_lines("peers", totals([dict(r, normals=r["method"]) for r in peers], methods))))
    comparison = peer_comparison(rows, peers)
    if comparison:
        print()
        print("\n".join(comparison))


if __name__ == "__main__":
    main()
