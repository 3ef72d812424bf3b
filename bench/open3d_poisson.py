#!/usr/bin/python3
"""bench/open3d_poisson.py: Open3D's screened Poisson reconstruction of an oriented cloud (a peer in scripts/bench-closed.sh).

    bench/open3d_poisson.py POINTS.xyz OUT.off [--depth D] [--threads T]

POINTS.xyz: `x y z nx ny nz` lines (bench/sample_mesh.py's clouds); Poisson needs the normals, so
a cloud without them, or with a zero-length or non-finite normal or coordinate, is refused with
the first bad line named (exit 2), as are an empty cloud and options out of range.
Runs open3d.geometry.TriangleMesh.create_from_point_cloud_poisson with depth D (default 8,
Open3D's default and the depth bench/python/peers.py uses; the octree adapts to the samples, so
D is an upper bound: at 20,000 points the finest cells hold a few samples), scale 1.1, no linear
fit, and writes the mesh UNTRIMMED: no vertices are removed by the density quantile of Open3D's
tutorial. Poisson's isosurface of a closed, evenly sampled cloud is closed; a density trim cuts
holes where the samples are sparsest and would turn Poisson's closed result into an open one.
T threads (default 1: Open3D's default, every core, may sum in a different order from run to
run; one thread gives the same file for the same input, and a time comparable with our
single-threaded loop). Prints `seconds: S` (the reconstruction alone, without Open3D's import or
the file I/O), `vertices: V`, `faces: F`. Exit codes: 0 done, 1 error, 2 usage or bad input.
"""
import argparse
import math
import os
import sys
import time

import numpy as np


def fail(message):
    print(f"open3d_poisson: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_oriented_points(path):
    """The points and normals of an `x y z nx ny nz` file; refuses anything Poisson cannot use."""
    try:
        with open(path, "r", encoding="utf-8") as f:
            rows = [(i + 1, line.split()) for i, line in enumerate(f)]
    except OSError as e:
        fail(f"cannot read {path}: {e.strerror}")
    rows = [(n, r) for n, r in rows if r and not r[0].startswith("#")]
    if not rows:
        fail(f"{path}: no points")
    data = np.empty((len(rows), 6), dtype=np.float64)
    for k, (n, r) in enumerate(rows):
        if len(r) < 6:
            fail(f"{path}:{n}: {len(r)} numbers, need 6 (x y z nx ny nz): Poisson needs normals")
        try:
            data[k] = [float(x) for x in r[:6]]
        except ValueError:
            fail(f"{path}:{n}: not a number: {' '.join(r[:6])}")
    bad = np.flatnonzero(~np.isfinite(data).all(axis=1))
    if len(bad):
        fail(f"{path}:{rows[bad[0]][0]}: a non-finite coordinate or normal ({len(bad)} such lines)")
    length = np.linalg.norm(data[:, 3:], axis=1)
    bad = np.flatnonzero(length <= 0)
    if len(bad):
        fail(f"{path}:{rows[bad[0]][0]}: a zero-length normal ({len(bad)} such lines)")
    return data[:, :3], data[:, 3:] / length[:, None]


def write_off(path, vertices, triangles):
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(f"OFF\n{len(vertices)} {len(triangles)} 0\n")
        np.savetxt(f, vertices, fmt="%.17g")
        np.savetxt(f, np.hstack([np.full((len(triangles), 1), 3), triangles]), fmt="%d")
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("points")
    ap.add_argument("out")
    ap.add_argument("--depth", type=int, default=8, help="octree depth, 1-12 (default 8)")
    ap.add_argument("--threads", type=int, default=1, help="threads, >= 1 (default 1: deterministic)")
    a = ap.parse_args()
    if not 1 <= a.depth <= 12:
        ap.error(f"--depth must be in 1-12, got {a.depth}")
    if a.threads < 1:
        ap.error(f"--threads must be >= 1, got {a.threads}")
    if not a.out.lower().endswith(".off"):
        ap.error(f"the output must be an .off file, got {a.out}")
    points, normals = read_oriented_points(a.points)

    import open3d as o3d  # after the checks: the import takes about a second
    o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)
    pcd = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    pcd.normals = o3d.utility.Vector3dVector(normals)
    t0 = time.perf_counter()
    mesh, _densities = o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(
        pcd, depth=a.depth, width=0, scale=1.1, linear_fit=False, n_threads=a.threads)
    seconds = time.perf_counter() - t0
    vertices = np.asarray(mesh.vertices)
    triangles = np.asarray(mesh.triangles).astype(np.int64)
    if len(triangles) == 0 or not math.isfinite(float(np.abs(vertices).sum())):
        print(f"open3d_poisson: error: Poisson gave no usable mesh for {a.points}", file=sys.stderr)
        sys.exit(1)
    write_off(a.out, vertices, triangles)
    print(f"seconds: {seconds:.3f}\nvertices: {len(vertices)}\nfaces: {len(triangles)}")


if __name__ == "__main__":
    main()
