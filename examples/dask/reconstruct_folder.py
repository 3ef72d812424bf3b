#!/usr/bin/env python3
"""A folder of scans reconstructed over a Dask cluster, one task per scan.

    PYTHONPATH=build/python /usr/bin/python3 examples/dask/reconstruct_folder.py scans/ --out out/meshes \\
        --vertices 2000                                           # a LocalCluster with 2 worker processes
    ... --scheduler tcp://scheduler:8786                           # the same on a real cluster

Every point cloud in the folder (.xyz, .txt, .pts, .ply) is reconstructed by edgefront.reconstruct
(growing cell structures with the twist repair) and written to OUT/<name>.ply. The mesh is written
atomically (edgefront.write_mesh writes a temporary file and renames it), so a worker that dies
loses no finished scan, and a rerun skips every scan whose mesh exists. A reconstruction is
byte-identical per seed: the files are the same as the serial run's (--serial) for any number of
workers. One reconstruction is one task: it does not spread over workers.
"""

import argparse
import pathlib
import sys

CLOUD_SUFFIXES = {".xyz", ".txt", ".pts", ".ply"}


def reconstruct_one(cloud_path, mesh_path, vertices, seed):
    """One task: reconstruct one scan and write its mesh (atomically). Returns the mesh path."""
    import edgefront as ef
    P, N = ef.read_points(cloud_path)
    V, F = ef.reconstruct(P, N, vertices=min(vertices, len(P)), seed=seed)
    ef.write_mesh(mesh_path, V, F)
    return str(mesh_path)


def reconstruct_folder(in_dir, out_dir, client=None, vertices=2000, seed=1):
    """Reconstructs every cloud of in_dir into out_dir/<stem>.ply on `client` (a
    dask.distributed.Client) or serially (client=None). Returns the meshes this call wrote (the
    others existed already), in file-name order."""
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    scans = sorted(p for p in pathlib.Path(in_dir).iterdir() if p.suffix.lower() in CLOUD_SUFFIXES)
    todo = [(p, out_dir / (p.stem + ".ply")) for p in scans if not (out_dir / (p.stem + ".ply")).exists()]
    if client is None:
        return [reconstruct_one(p, m, vertices, seed) for p, m in todo]
    if todo and __name__ != "__main__":
        client.upload_file(__file__)  # the workers import this module to run reconstruct_one
    futures = [client.submit(reconstruct_one, str(p), str(m), vertices, seed, pure=False) for p, m in todo]
    return client.gather(futures)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder", help="folder of point clouds (.xyz, .txt, .pts, .ply)")
    ap.add_argument("--out", default="out/meshes", help="output folder (default out/meshes)")
    ap.add_argument("--vertices", type=int, default=2000, help="target vertices per mesh (default 2000)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--scheduler", help="address of a running scheduler, e.g. tcp://scheduler:8786")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (default 2)")
    ap.add_argument("--serial", action="store_true", help="no Dask: every scan in this process")
    args = ap.parse_args(argv)
    if args.serial:
        written = reconstruct_folder(args.folder, args.out, None, args.vertices, args.seed)
    else:
        from dask.distributed import Client, LocalCluster
        if args.scheduler:
            with Client(args.scheduler) as client:
                written = reconstruct_folder(args.folder, args.out, client, args.vertices, args.seed)
        else:
            with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                              dashboard_address=None) as cluster, Client(cluster) as client:
                written = reconstruct_folder(args.folder, args.out, client, args.vertices, args.seed)
    print(f"{len(written)} mesh(es) written to {args.out} (the others were done already)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
