#!/usr/bin/env python3
"""A surface from a point cloud (growing cell structures with the twist repair): a PNG and a PLY.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/reconstruct.py [CLOUD] [VERTICES] [OUT_DIR]

With the defaults this is the main job (scripts/main.sh): the same mesh, byte for byte, as
`gcs-reconstruct data/vault-sheet.xyz --vertices 2000`.
"""
import pathlib
import sys

import edgefront as ef

cloud = sys.argv[1] if len(sys.argv) > 1 else "data/vault-sheet.xyz"
vertices = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
out = pathlib.Path(sys.argv[3] if len(sys.argv) > 3 else "out")
out.mkdir(parents=True, exist_ok=True)

P, N = ef.read_points(cloud)                             # N is None for a cloud without normals
V, F = ef.reconstruct(P, N, vertices=vertices, seed=1,
                      progress=lambda p: print(f"\r{p['vertices']}/{p['target_vertices']} vertices", end=""))
ef.write_mesh(out / "reconstruction.ply", V, F)
ef.render_png(V, F, path=out / "reconstruction.png")
e = ef.evaluate(V, F, P, N)
print(f"\n{len(V)} vertices, {len(F)} faces, Chamfer-L1 {e['chamfer_l1_percent']:.3f}% of the diagonal, "
      f"{e['mesh']['border_loops']} border loop(s) -> {out}/reconstruction.ply, {out}/reconstruction.png")
