#!/usr/bin/env python3
"""Our reconstruction beside Open3D's screened Poisson and ball pivoting, on the same clouds, from
Python: wall and CPU time (the process's, all threads), Chamfer-L1 and Hausdorff-95 (edgefront.evaluate: the figures of gcs-eval, in %
of the ground truth's bounding-box diagonal), closedness (border loops) and components.

    PYTHONPATH=build/python /usr/bin/python3 bench/python/peers.py [--cgal-data /work/cgal-data/data]
        [--vertices 5000] [--points 20000] [--threads 1]

Needs Debian's python3-open3d (scripts/setup.sh --with-peers) and CGAL's sample data
(data/fetch-models.sh, or --cgal-data). Clouds: kitten.xyz (oriented points of points_3) judged
against itself, and clouds sampled area-uniformly (seed 1, with their face normals) from a few
meshes of meshes/, judged against the mesh. Ours: edgefront.reconstruct(P, N, vertices=V, seed=1)
(growing cell structures with the twist repair). Poisson: depth 8, untrimmed (Open3D's default
output; the density trim is a per-cloud choice). Ball pivoting: radii 1, 2 and 4 x the mean
nearest-neighbour spacing. Open3D runs with --threads threads (its default uses every core; 1 for
a like-for-like time with our single-threaded loop).
Prints a Markdown table.
"""

import argparse
import os
import pathlib
import time

import numpy as np

import edgefront as ef


def sample_mesh(V, F, n, seed=1):
    """n area-uniform points on the mesh with their face normals."""
    rng = np.random.default_rng(seed)
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    cross = np.cross(b - a, c - a)
    area = np.linalg.norm(cross, axis=1)
    keep = area > 0
    F, a, b, c, cross, area = F[keep], a[keep], b[keep], c[keep], cross[keep], area[keep]
    face = rng.choice(len(F), size=n, p=area / area.sum())
    u, v = rng.random(n), rng.random(n)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    P = a[face] + u[:, None] * (b[face] - a[face]) + v[:, None] * (c[face] - a[face])
    N = cross[face] / area[face][:, None]
    return P, N


def run_open3d(P, N, which):
    import open3d as o3d
    pcd = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(P))
    pcd.normals = o3d.utility.Vector3dVector(N)
    t0, c0 = time.perf_counter(), time.process_time()
    if which == "poisson":
        mesh, _ = o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(pcd, depth=8)
    else:
        spacing = float(np.mean(pcd.compute_nearest_neighbor_distance()))
        radii = o3d.utility.DoubleVector([spacing, 2 * spacing, 4 * spacing])
        mesh = o3d.geometry.TriangleMesh.create_from_point_cloud_ball_pivoting(pcd, radii)
    seconds = (time.perf_counter() - t0, time.process_time() - c0)
    return np.asarray(mesh.vertices), np.asarray(mesh.triangles).astype(np.int64), seconds


def row(cloud, method, V, F, seconds, gt):
    if len(F) == 0:
        return f"| {cloud} | {method} | {seconds[0]:.2f} | {seconds[1]:.2f} | 0 | - | - | - | - | no faces |"
    e = ef.evaluate(V, F, *gt[0], **gt[1], samples=100000, self_intersections=False)
    m = e["mesh"]
    return (f"| {cloud} | {method} | {seconds[0]:.2f} | {seconds[1]:.2f} | {m['vertices']} | {e['chamfer_l1_percent']:.3f} | "
            f"{e['hausdorff_p95_percent']:.3f} | {m['border_loops']} | {m['components']} | "
            + (f"{m['faces_dropped_when_read']} non-manifold face(s) dropped for the evaluation"
               if m["faces_dropped_when_read"] else "") + " |")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cgal-data", default=os.environ.get("CGAL_DATA", "/work/cgal-data/data"))
    ap.add_argument("--vertices", type=int, default=5000)
    ap.add_argument("--points", type=int, default=20000)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--meshes", default="bunny00.off,elephant.off,armadillo.off")
    args = ap.parse_args()
    if args.threads > 0:
        os.environ["OMP_NUM_THREADS"] = str(args.threads)  # Open3D's OpenMP loops (read at import)
    import open3d as o3d
    o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)
    root = pathlib.Path(args.cgal_data)
    clouds = []
    P, N = ef.read_points(root / "points_3" / "kitten.xyz")
    clouds.append(("kitten.xyz", P, N, ((P, N), {})))
    for name in args.meshes.split(","):
        Vm, Fm = ef.read_mesh(root / "meshes" / name)
        P, N = sample_mesh(Vm, Fm, args.points)
        clouds.append((f"{name} ({args.points} samples)", P, N, ((Vm,), {"gt_faces": Fm})))
    print(f"Open3D {o3d.__version__}, OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}; "
          f"ours at {args.vertices} vertices; {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}")
    print()
    print("| cloud | method | wall (s) | CPU (s) | vertices | Chamfer-L1 (%) | Hausdorff-95 (%) | border loops | components | notes |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for cloud, P, N, gt in clouds:
        t0, c0 = time.perf_counter(), time.process_time()
        V, F = ef.reconstruct(P, N, vertices=min(args.vertices, len(P)), seed=1)
        seconds = (time.perf_counter() - t0, time.process_time() - c0)
        print(row(cloud, "edgefront GCS", V, F, seconds, gt), flush=True)
        for which in ["poisson", "ball-pivoting"]:
            V, F, seconds = run_open3d(P, N, which)
            print(row(cloud, f"Open3D {which}", V, F, seconds, gt), flush=True)


if __name__ == "__main__":
    main()
