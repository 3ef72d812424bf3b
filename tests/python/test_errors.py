"""Bad input gets the right exception with the library's message; nothing crashes."""

import os

import numpy as np
import pytest

import edgefront as ef
from conftest import DATA_DIR, grid


@pytest.fixture
def mesh():
    return grid(6)


def test_wrong_dtypes(mesh):
    V, F = mesh
    with pytest.raises(ValueError, match="V must be float32 or float64, got dtype int64"):
        ef.geodesic_distance(V.astype(np.int64), F, 0)
    with pytest.raises(ValueError, match="F must be int32 or int64, got dtype float64"):
        ef.geodesic_distance(V, F.astype(np.float64), 0)
    with pytest.raises(ValueError, match="F must be int32 or int64, got dtype uint32"):
        ef.geodesic_distance(V, F.astype(np.uint32), 0)
    with pytest.raises(ValueError, match="V must be float32 or float64, got dtype float16"):
        ef.geodesic_distance(V.astype(np.float16), F, 0)
    with pytest.raises(ValueError, match="sources must be integer vertex indices"):
        ef.geodesic_distance(V, F, [0.5])
    with pytest.raises(ValueError, match="no source vertex given"):
        ef.geodesic_distance(V, F, [])


def test_wrong_shapes(mesh):
    V, F = mesh
    with pytest.raises(ValueError, match=r"V must have shape \(n, 3\), got shape \(36, 2\)"):
        ef.geodesic_distance(V[:, :2], F, 0)
    with pytest.raises(ValueError, match=r"F must have shape \(n, 3\), got shape \(150,\)"):
        ef.geodesic_distance(V, F.ravel(), 0)
    with pytest.raises(ValueError, match="V is empty"):
        ef.geodesic_distance(np.zeros((0, 3)), F, 0)
    with pytest.raises(ValueError, match="write_mesh|scalars must have 36 values"):
        ef.write_mesh("never.ply", V, F, scalars=np.zeros(5))
    assert not os.path.exists("never.ply")


def test_non_finite_coordinates(mesh):
    V, F = mesh
    V = V.copy()
    V[7, 1] = np.nan
    with pytest.raises(ValueError, match="row 7"):
        ef.geodesic_distance(V, F, 0)
    V[7, 1] = np.inf
    with pytest.raises(ValueError, match="row 7"):
        ef.GeodesicSolver(V, F)
    with pytest.raises(ValueError, match="row 7"):
        ef.reconstruct(V, None, vertices=10)


def test_out_of_range_indices(mesh):
    V, F = mesh
    bad = F.copy()
    bad[3, 2] = len(V)
    with pytest.raises(ValueError, match="row 3"):
        ef.geodesic_distance(V, bad, 0)
    bad[3, 2] = -1
    with pytest.raises(ValueError, match="row 3"):
        ef.detect_twists(V, bad)
    with pytest.raises(ValueError):
        ef.geodesic_distance(V, F, len(V))
    with pytest.raises(ValueError):
        ef.geodesic_distance(V, F, -1)
    with pytest.raises(ValueError, match="out of range"):
        ef.geodesic_distance(V, F, [2 ** 40])
    with pytest.raises(ValueError):
        ef.geodesic_distance(V, F, ([len(F)], [[1.0, 0.0, 0.0]]))
    with pytest.raises(ValueError):
        ef.geodesic_distance(V, F, ([0], [[0.5, 0.6, 0.0]]))  # does not sum to 1
    solver = ef.GeodesicSolver(V, F)
    with pytest.raises(ValueError, match=str(len(V))):
        solver.path_sources(0, len(V))
    with pytest.raises(ValueError):
        solver.path_sources(-1, 3)


def test_bad_options(mesh):
    V, F = mesh
    with pytest.raises(ValueError, match="heat"):
        ef.geodesic_distance(V, F, 0, method="heat")
    with pytest.raises(ValueError):
        ef.geodesic_distance(V, F, 0, max_distance=-1.0)
    with pytest.raises(ValueError):
        ef.geodesic_distance(V, F, 0, max_distance=float("nan"))
    with pytest.raises(ValueError, match="points and normals go together"):
        ef.repair_twists(V, F, points=V)
    with pytest.raises(ValueError):
        ef.reconstruct(V, None, vertices=len(V) + 1)
    with pytest.raises(ValueError, match="vertices must be a positive count"):
        ef.reconstruct(V, None, vertices=-5)
    with pytest.raises(TypeError):
        ef.reconstruct(V, None, vertices=20.5)
    with pytest.raises(ValueError, match="normals: 5 rows for 36 points"):
        ef.reconstruct(V, V[:5], vertices=10)
    with pytest.raises(ValueError):
        ef.render_png(V, F, width=0)


def test_files(tmp_path, mesh):
    V, F = mesh
    with pytest.raises(OSError, match="no-such-file.off"):
        ef.read_mesh(tmp_path / "no-such-file.off")
    with pytest.raises(OSError):
        ef.read_points(tmp_path / "no-such-file.xyz")
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n")
    with pytest.raises(OSError, match="bad.off"):
        ef.read_mesh(bad)
    with pytest.raises(OSError):
        ef.write_mesh(tmp_path / "missing-dir" / "m.ply", V, F)
    with pytest.raises(ValueError):
        ef.write_mesh(tmp_path / "m.xyz", V, F)  # not a mesh format
    with pytest.raises(ValueError):
        ef.write_mesh(tmp_path / "m.off", V, F, scalars=np.zeros(len(V)))  # scalars need PLY
    with pytest.raises(OSError):
        ef.render_png(V, F, path=tmp_path / "missing-dir" / "m.png")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.off"]  # nothing half-written


def test_nonmanifold_faces_are_refused_by_write_mesh(tmp_path, mesh):
    V, F = mesh
    F2 = np.concatenate([F, F[:1]])  # a repeated face
    with pytest.raises(ValueError, match="row 50"):
        ef.write_mesh(tmp_path / "m.ply", V, F2)
    solver = ef.GeodesicSolver(V, F2)  # the distance functions drop it and say so
    assert solver.dropped_faces == 1


def points_on_sphere(n=400, seed=3):
    rng = np.random.default_rng(seed)
    P = rng.normal(size=(n, 3))
    P /= np.linalg.norm(P, axis=1, keepdims=True)
    return P


def test_progress_false_cancels_and_returns_a_valid_mesh():
    P = points_on_sphere()
    calls = []

    def stop_early(p):
        calls.append(p)
        return False

    V, F, info = ef.reconstruct(P, P, vertices=300, progress=stop_early, return_info=True)
    assert info["cancelled"] and info["stop_reason"] == "cancelled"
    assert len(calls) == 1 and calls[0]["target_vertices"] == 300
    assert 4 <= len(V) < 300 and F.min() >= 0 and F.max() < len(V)
    full, _ = ef.reconstruct(P, P, vertices=300, progress=lambda p: None)  # None continues
    assert len(full) == 300


def test_progress_exception_propagates_with_the_partial_mesh():
    P = points_on_sphere()

    class Stop(Exception):
        pass

    def boom(p):
        raise Stop(f"at {p['vertices']}")

    with pytest.raises(Stop) as e:
        ef.reconstruct(P, P, vertices=300, progress=boom)
    V, F = e.value.partial_result
    assert 4 <= len(V) < 300 and F.max() < len(V)
    with pytest.raises(TypeError):
        ef.reconstruct(P, P, vertices=300, progress=lambda: True)  # wrong signature: TypeError


def test_evaluate_bad_ground_truth(mesh):
    V, F = mesh
    with pytest.raises(ValueError):
        ef.evaluate(V, F, np.zeros((3, 3)))  # zero bounding-box diagonal
    with pytest.raises(ValueError, match="not both"):
        ef.evaluate(V, F, V, V, gt_faces=F)
