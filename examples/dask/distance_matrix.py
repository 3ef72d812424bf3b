#!/usr/bin/env python3
"""A geodesic distance matrix, its sources sharded over a Dask cluster.

    PYTHONPATH=build/python /usr/bin/python3 examples/dask/distance_matrix.py data/bumpy-sphere.off \\
        --sources 0:642:10 --out out/dmatrix                      # a LocalCluster with 2 worker processes
    ... --scheduler tcp://scheduler:8786                           # the same on a real cluster

Each task computes the rows of one chunk of sources (edgefront.GeodesicSolver on the mesh, which
the cluster holds once) and writes them to OUT/rows-<first>-<count>.npy atomically (a temporary
file in the same folder, then os.replace), so a worker that dies loses nothing finished, and a
rerun skips every chunk whose file exists. The matrix (sources x vertices, float64, inf where
unreached) is then assembled into OUT/matrix.npy, also atomically. The result is the same, byte
for byte, as the serial run (--serial), for any number of workers and any chunk size.
"""

import argparse
import os
import pathlib
import sys
import tempfile

import numpy as np


def save_atomically(path, array):
    """np.save to a temporary file next to `path`, then os.replace: readers and reruns see the
    old file or the complete new one, never a partial one."""
    path = pathlib.Path(path)
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            np.save(f, array)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def chunk_file(out_dir, first, count):
    return pathlib.Path(out_dir) / f"rows-{first:08d}-{count:06d}.npy"


def compute_rows(mesh, sources, method, max_distance, out_path):
    """One task: the distance fields of `sources` (one row each) written to out_path."""
    import edgefront as ef
    V, F = mesh
    solver = ef.GeodesicSolver(V, F)
    rows = np.stack([solver.distance(int(s), method=method, max_distance=max_distance) for s in sources])
    save_atomically(out_path, rows)
    return str(out_path)


def distance_matrix(V, F, sources, out_dir, client=None, chunk=8, method="mdf", max_distance=np.inf):
    """Rows of the distance matrix for `sources` (vertex indices), one task per `chunk` sources,
    on `client` (a dask.distributed.Client) or, with client=None, serially in this process.
    Returns (matrix, computed) where computed lists the chunk files this call wrote (the others
    existed already)."""
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    sources = np.asarray(sources, dtype=np.int64)
    chunks = [(i, sources[i:i + chunk]) for i in range(0, len(sources), chunk)]
    todo = [(first, s) for first, s in chunks if not chunk_file(out_dir, first, len(s)).exists()]
    computed = []
    if todo and client is None:
        computed = [compute_rows((V, F), s, method, max_distance, chunk_file(out_dir, first, len(s)))
                    for first, s in todo]
    elif todo:
        if __name__ != "__main__":
            client.upload_file(__file__)  # the workers import this module to run compute_rows
        mesh = client.scatter((V, F), broadcast=True)  # sent once to every worker, not per task
        futures = [client.submit(compute_rows, mesh, s, method, max_distance, chunk_file(out_dir, first, len(s)),
                                 pure=False)
                   for first, s in todo]
        computed = client.gather(futures)
    matrix = np.concatenate([np.load(chunk_file(out_dir, first, len(s))) for first, s in chunks])
    save_atomically(out_dir / "matrix.npy", matrix)
    return matrix, computed


def parse_range(text):
    """"a:b:step" or "a,b,c" -> vertex indices."""
    if ":" in text:
        return np.arange(*[int(x) for x in text.split(":")])
    return np.array([int(x) for x in text.split(",")])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("--sources", default="0:64", help="a:b[:step] or a,b,c (default 0:64)")
    ap.add_argument("--out", default="out/dmatrix", help="output folder (default out/dmatrix)")
    ap.add_argument("--chunk", type=int, default=8, help="sources per task (default 8)")
    ap.add_argument("--method", default="mdf")
    ap.add_argument("--scheduler", help="address of a running scheduler, e.g. tcp://scheduler:8786")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (default 2)")
    ap.add_argument("--serial", action="store_true", help="no Dask: every chunk in this process")
    args = ap.parse_args(argv)
    import edgefront as ef
    V, F = ef.read_mesh(args.mesh)
    sources = parse_range(args.sources)
    if args.serial:
        matrix, computed = distance_matrix(V, F, sources, args.out, None, args.chunk, args.method)
    else:
        from dask.distributed import Client, LocalCluster
        if args.scheduler:
            with Client(args.scheduler) as client:
                matrix, computed = distance_matrix(V, F, sources, args.out, client, args.chunk, args.method)
        else:
            with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                              dashboard_address=None) as cluster, Client(cluster) as client:
                matrix, computed = distance_matrix(V, F, sources, args.out, client, args.chunk, args.method)
    print(f"distance matrix {matrix.shape[0]} x {matrix.shape[1]} -> {args.out}/matrix.npy "
          f"({len(computed)} chunk(s) computed, the rest were done already)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
