"""Files and pictures: round trips, PLY scalars, PNG output."""

import numpy as np

import edgefront as ef
from conftest import DATA_DIR, TEST_DATA_DIR, app


def test_read_mesh_matches_the_file(bumpy):
    V, F = bumpy
    assert V.dtype == np.float64 and V.shape == (642, 3)
    assert F.dtype == np.int32 and F.shape == (1280, 3)
    lines = (DATA_DIR / "bumpy-sphere.off").read_text().split("\n")
    assert np.array_equal(V[0], [float(x) for x in lines[2].split()])
    assert F[0].tolist() == [int(x) for x in lines[2 + 642].split()[1:]]


def test_write_read_round_trip(tmp_path, bumpy):
    V, F = bumpy
    for ext in ["off", "obj", "ply"]:
        ef.write_mesh(tmp_path / f"m.{ext}", V, F)
        V2, F2 = ef.read_mesh(tmp_path / f"m.{ext}")
        assert np.array_equal(V2, V) and np.array_equal(F2, F), ext
    V32 = V.astype(np.float32)
    ef.write_mesh(str(tmp_path / "f.ply"), V32, F.astype(np.int64))
    V2, _ = ef.read_mesh(tmp_path / "f.ply")
    assert np.array_equal(V2, V32.astype(np.float64))


def test_ply_scalars_and_colors(tmp_path, bumpy):
    V, F = bumpy
    d = ef.geodesic_distance(V, F, 0, max_distance=1.0)
    ef.write_mesh(tmp_path / "d.ply", V, F, scalars=d, binary=False)
    text = (tmp_path / "d.ply").read_text()
    header = text.split("end_header")[0]
    assert "property double quality" in header and "property uchar red" in header
    first = text.split("end_header\n")[1].split("\n")[0].split()
    assert float(first[3]) == 0.0  # vertex 0: distance 0
    ef.write_mesh(tmp_path / "n.ply", V, F, scalars={"distance": d, "height": V[:, 2]})
    assert b"property double height" in (tmp_path / "n.ply").read_bytes()[:400]
    # what the app reads back is the same mesh
    info = app("ef-info", tmp_path / "n.ply")
    assert "642" in info


def test_read_points(tmp_path):
    P, N = ef.read_points(DATA_DIR / "vault-sheet.xyz")
    assert P.shape == (3000, 3) and N.shape == (3000, 3)
    np.testing.assert_allclose(np.linalg.norm(N, axis=1), 1, atol=1e-12)
    ef.write_points(tmp_path / "p.xyz", P[:10])
    P2, N2 = ef.read_points(tmp_path / "p.xyz")
    assert N2 is None and np.array_equal(P2, P[:10])
    P3, N3 = ef.read_points(TEST_DATA_DIR / "points_normals.ply")
    assert N3 is not None and len(P3) == len(N3)


def test_render_png(tmp_path, bumpy):
    V, F = bumpy
    d = ef.geodesic_distance(V, F, 0)
    ef.render_png(V, F, scalars=d, path=tmp_path / "d.png", width=200, height=150)
    data = (tmp_path / "d.png").read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 1000
    img = ef.render_png(V, F, width=64, height=48)
    assert img.dtype == np.uint8 and img.shape == (48, 64, 3)
    assert (img != 255).any() and (img == 255).all(axis=2).any()  # the mesh and some background
    colored = ef.render_png(V, F, scalars=d, width=64, height=48)
    assert not np.array_equal(colored, img)
