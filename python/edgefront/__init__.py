"""EdgeFront: geodesics with edge fronts, twist repair and surface reconstruction on numpy arrays.

Meshes are numpy arrays: V, float64 or float32 of shape (n, 3), and F, int32 or int64 of shape
(m, 3) (0-based rows of V). Arrays are read in place when C-contiguous (a non-contiguous array is
copied once); results are new numpy arrays (V float64, F int32). Long calls release the GIL.
Library errors become ValueError (bad input), OSError (files) or RuntimeError, with the library's
message.

    import edgefront as ef
    V, F = ef.read_mesh("data/bumpy-sphere.off")
    d = ef.geodesic_distance(V, F, [0])                 # method="mdf" | "windows" | "fast" | "dijkstra"
    ef.write_mesh("dist.ply", V, F, scalars=d)          # PLY with per-vertex quality and colors
    ef.render_png(V, F, scalars=d, path="dist.png")

    P, N = ef.read_points("data/vault-sheet.xyz")
    V, F = ef.reconstruct(P, N, vertices=2000)          # growing cell structures + twist repair
    print(ef.evaluate(V, F, P, N)["chamfer_l1"])

Functions: read_mesh, write_mesh, read_points, write_points, render_png, geodesic_distance,
GeodesicSolver, geodesic_path, edge_front_levels, detect_twists, repair_twists, apply_record,
reconstruct, evaluate. See help(edgefront.<name>) and docs/python.md.
"""

from ._edgefront import (
    GeodesicSolver,
    detect_twists,
    edge_front_levels,
    evaluate,
    geodesic_distance,
    geodesic_path,
    read_mesh,
    read_points,
    reconstruct,
    render_png,
    repair_twists,
    write_mesh,
    write_points,
)
from .records import apply_record

__all__ = [
    "GeodesicSolver",
    "apply_record",
    "detect_twists",
    "edge_front_levels",
    "evaluate",
    "geodesic_distance",
    "geodesic_path",
    "read_mesh",
    "read_points",
    "reconstruct",
    "render_png",
    "repair_twists",
    "write_mesh",
    "write_points",
]
