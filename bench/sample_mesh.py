#!/usr/bin/python3
"""bench/sample_mesh.py: an oriented point cloud sampled from a triangle mesh (scripts/bench-closed.sh).

    bench/sample_mesh.py MESH.off OUT.xyz [--points N] [--seed S]

Area-uniform samples of the mesh's triangles (polygons are fanned), each with its triangle's unit
normal (the mesh's orientation: outward for CGAL's closed models). Writes `x y z nx ny nz` lines;
the same seed gives the same file. Only OFF input (CGAL's sample models). numpy only.
"""
import argparse
import os
import sys

import numpy as np


def read_off(path):
    """Vertices and fanned triangles of a plain OFF or COFF file (colours after the numbers are skipped)."""
    with open(path, "r", encoding="utf-8", errors="replace") as f:
        lines = [l.split("#", 1)[0].split() for l in f]
    lines = [l for l in lines if l]
    head = lines[0]
    if not head[0].upper().endswith("OFF"):
        raise ValueError(f"{path}: not an OFF file")
    rest = lines[1:]
    counts = head[1:] if len(head) > 1 else rest.pop(0)
    nv, nf = int(counts[0]), int(counts[1])
    verts = np.array([[float(x) for x in l[:3]] for l in rest[:nv]], dtype=np.float64)
    tris = []
    for l in rest[nv:nv + nf]:
        k = int(l[0])
        ids = [int(x) for x in l[1:1 + k]]
        for j in range(1, k - 1):
            tris.append((ids[0], ids[j], ids[j + 1]))
    return verts, np.array(tris, dtype=np.int64)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("out")
    ap.add_argument("--points", type=int, default=20000)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    if a.points < 1:
        sys.exit("sample_mesh: --points must be >= 1")
    v, t = read_off(a.mesh)
    p0, p1, p2 = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    cross = np.cross(p1 - p0, p2 - p0)
    area2 = np.linalg.norm(cross, axis=1)
    keep = area2 > 0
    p0, p1, p2, cross, area2 = p0[keep], p1[keep], p2[keep], cross[keep], area2[keep]
    if len(area2) == 0:
        sys.exit(f"sample_mesh: {a.mesh} has no triangle of positive area")
    rng = np.random.default_rng(a.seed)
    face = rng.choice(len(area2), size=a.points, p=area2 / area2.sum())
    r1 = np.sqrt(rng.random(a.points))
    r2 = rng.random(a.points)
    w0, w1, w2 = 1 - r1, r1 * (1 - r2), r1 * r2
    pts = w0[:, None] * p0[face] + w1[:, None] * p1[face] + w2[:, None] * p2[face]
    nrm = cross[face] / area2[face][:, None]
    tmp = a.out + ".tmp"
    np.savetxt(tmp, np.hstack([pts, nrm]), fmt="%.9g")
    os.replace(tmp, a.out)


if __name__ == "__main__":
    main()
