#!/usr/bin/env python3
"""A geodesic distance field: a PNG and a PLY (MeshLab shows its per-vertex quality and colors).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/distance_field.py [MESH] [OUT_DIR]
"""
import pathlib
import sys

import edgefront as ef

mesh = sys.argv[1] if len(sys.argv) > 1 else "data/bumpy-sphere.off"
out = pathlib.Path(sys.argv[2] if len(sys.argv) > 2 else "out")
out.mkdir(parents=True, exist_ok=True)

V, F = ef.read_mesh(mesh)
d = ef.geodesic_distance(V, F, [0])                      # method="mdf" | "windows" | "fast" | "dijkstra"
ef.write_mesh(out / "distance.ply", V, F, scalars=d)
ef.render_png(V, F, scalars=d, path=out / "distance.png", color_bar=True)
print(f"{len(V)} vertices, farthest at {d.max():.4f} -> {out}/distance.ply, {out}/distance.png")
