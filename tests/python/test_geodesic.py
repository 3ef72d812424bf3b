"""Geodesic distances, paths and levels: analytic answers and bit-for-bit agreement with ef-distance."""

import concurrent.futures

import numpy as np
import pytest

import edgefront as ef
from conftest import DATA_DIR, app, grid, icosphere


@pytest.mark.parametrize("method", ["mdf", "windows"])
def test_planar_grid_distances_are_euclidean(method):
    V, F = grid(21)
    src = 10 * 21 + 10  # the centre
    d = ef.geodesic_distance(V, F, src, method=method)
    exact = np.linalg.norm(V - V[src], axis=1)
    assert d.dtype == np.float64 and d.shape == (len(V),)
    assert d[src] == 0
    np.testing.assert_allclose(d, exact, rtol=0, atol=1e-9)


@pytest.mark.parametrize("seed", [1, 2])
def test_jittered_planar_grid(seed):
    # Interior vertices moved by up to 0.3 cells: obtuse triangles. The windows are exact; the MDF
    # is exact at all but a few vertices (measured: 2-3 of 441, too long by at most 1.8% there;
    # ef-distance gives the same numbers), not "under any triangulation" as the README says.
    V, F = grid(21, jitter=0.3, seed=seed)
    src = 10 * 21 + 10
    exact = np.linalg.norm(V - V[src], axis=1)
    np.testing.assert_allclose(ef.geodesic_distance(V, F, src, method="windows"), exact, rtol=0, atol=1e-9)
    d = ef.geodesic_distance(V, F, src, method="mdf")
    err = np.abs(d - exact)
    assert np.count_nonzero(err > 1e-9) <= 5
    assert np.all(err <= 0.02 * exact + 1e-9)


def test_dijkstra_overestimates_and_fast_is_close():
    V, F = grid(21, jitter=0.3)
    exact = np.linalg.norm(V - V[0], axis=1)
    dij = ef.geodesic_distance(V, F, [0], method="dijkstra")
    assert np.all(dij >= exact - 1e-12)
    assert np.mean(dij - exact) > 1e-3  # along edges: clearly longer on a jittered grid
    fast = ef.geodesic_distance(V, F, [0], method="fast")
    assert np.max(np.abs(fast - exact)) < 0.05 * exact.max()


def test_sphere_antipode_is_pi_r():
    R = 2.0
    V, F = icosphere(4, R)  # 2562 vertices, inscribed in the sphere
    anti = int(np.argmin(np.linalg.norm(V + V[0], axis=1)))
    assert np.allclose(V[anti], -V[0])
    for method in ["mdf", "windows"]:
        d = ef.geodesic_distance(V, F, 0, method=method)
        assert abs(d[anti] - np.pi * R) < 0.01 * np.pi * R, (method, d[anti])
        assert d[anti] == pytest.approx(d.max(), rel=2e-3)  # the farthest point


def parse_app_field(text):
    return np.array([float(x) for x in text.split()])


@pytest.mark.parametrize("method", ["mdf", "windows", "fast", "dijkstra"])
def test_bit_for_bit_with_ef_distance(bumpy, method):
    V, F = bumpy
    d = ef.geodesic_distance(V, F, [0, 100], method=method)
    ref = parse_app_field(app("ef-distance", DATA_DIR / "bumpy-sphere.off", "--source", "0,100", "--method", method))
    assert ref.shape == d.shape
    assert np.array_equal(d, ref), f"{np.count_nonzero(d != ref)} of {len(d)} values differ"


def test_surface_point_sources_bit_for_bit(bumpy):
    V, F = bumpy
    d = ef.geodesic_distance(V, F, ([7, 300], [[0.2, 0.3, 0.5], [1 / 3, 1 / 3, 1 / 3]]))
    ref = parse_app_field(app("ef-distance", DATA_DIR / "bumpy-sphere.off", "--point", "7:0.2,0.3,0.5",
                              "--point", f"300:{1 / 3!r},{1 / 3!r},{1 / 3!r}"))
    assert np.array_equal(d, ref)
    one = ef.geodesic_distance(V, F, (7, [0.2, 0.3, 0.5]))
    assert np.all(one >= 0) and one.min() < 0.1


def test_max_distance_bit_for_bit(bumpy):
    V, F = bumpy
    d = ef.geodesic_distance(V, F, 5, max_distance=0.5)
    ref = parse_app_field(app("ef-distance", DATA_DIR / "bumpy-sphere.off", "--source", "5", "--max-distance", "0.5"))
    assert np.array_equal(d, ref)
    assert np.isinf(d).any() and np.all(d[np.isfinite(d)] <= 0.5)


def test_dtypes_and_layouts_give_the_same_bytes(bumpy):
    V, F = bumpy
    V32 = V.astype(np.float32)
    ref = ef.geodesic_distance(V32.astype(np.float64), F.astype(np.int64), 3)
    assert np.array_equal(ef.geodesic_distance(V32, F.astype(np.int32), 3), ref)
    Vf = np.asfortranarray(V32.astype(np.float64))  # not C-contiguous: copied once
    assert not Vf.flags.c_contiguous
    assert np.array_equal(ef.geodesic_distance(Vf, F[:, :], 3), ref)
    wide = np.zeros((len(V), 6))
    wide[:, ::2] = V32
    assert np.array_equal(ef.geodesic_distance(wide[:, ::2], F, 3), ref)  # a strided view
    assert np.array_equal(ef.geodesic_distance(V32.tolist(), F.tolist(), [3]), ref)  # plain lists


def test_solver_queries_agree_with_the_field(bumpy):
    V, F = bumpy
    solver = ef.GeodesicSolver(V, F)
    assert solver.n_vertices == len(V) and solver.n_faces == len(F) and solver.dropped_faces == 0
    field = solver.distance([4])
    assert np.array_equal(field, ef.geodesic_distance(V, F, [4]))
    vs, ds = solver.distances_within([4], 0.4)
    assert vs.dtype == np.int32 and np.all(np.diff(ds) >= 0)
    assert set(vs.tolist()) == set(np.flatnonzero(field <= 0.4).tolist())
    np.testing.assert_allclose(ds, field[vs], rtol=0, atol=1e-12)
    assert solver.distance_between(4, int(vs[-1]), 0.4) == pytest.approx(ds[-1], abs=1e-12)
    far = int(np.argmax(field))
    assert solver.distance_between(4, far, 0.4) is None
    for method in ["windows", "fast", "dijkstra"]:
        assert np.array_equal(solver.distance(4, method=method), ef.geodesic_distance(V, F, 4, method=method))


@pytest.mark.parametrize("method", ["mdf", "fast"])
def test_solver_from_threads_matches_serial(bumpy, method):
    V, F = bumpy
    sources = list(range(0, 640, 40))
    serial = [ef.geodesic_distance(V, F, s, method=method) for s in sources]
    solver = ef.GeodesicSolver(V, F)  # fresh: the fast mode's table is built by the first threads
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        threaded = list(pool.map(lambda s: solver.distance(s, method=method), sources))
    for a, b in zip(serial, threaded):
        assert np.array_equal(a, b)


def test_planar_path_is_straight():
    V, F = grid(21, jitter=0.3)
    a, b = 0, len(V) - 1
    pts, length = ef.geodesic_path(V, F, a, b)
    assert pts.shape[1] == 3 and len(pts) >= 2
    np.testing.assert_allclose(pts[0], V[a], atol=1e-12)
    np.testing.assert_allclose(pts[-1], V[b], atol=1e-12)
    exact = np.linalg.norm(V[b] - V[a])
    assert length == pytest.approx(exact, rel=1e-9)
    assert np.sum(np.linalg.norm(np.diff(pts, axis=0), axis=1)) == pytest.approx(exact, rel=1e-9)
    chain, chain_length = ef.geodesic_path(V, F, a, b, polyline=False)
    assert np.all(np.min(np.linalg.norm(chain[:, None, :] - V[None, :, :], axis=2), axis=1) == 0)  # at vertices
    assert chain_length >= exact - 1e-9


def test_polyline_points_are_geodesic_sources():
    # On a plane the polyline is the straight segment; each of its points, as (face, barycentric),
    # reproduces its position, and as a source gives Euclidean distances (MDF: exact on a plane).
    V, F = grid(21)
    solver = ef.GeodesicSolver(V, F)
    a, b = 3, len(V) - 5
    pts, _ = solver.path(a, b)
    faces, bary = solver.path_sources(a, b)
    assert faces.shape == (len(pts),) and bary.shape == (len(pts), 3)
    np.testing.assert_allclose(np.einsum("ki,kij->kj", bary, V[F[faces]]), pts, atol=1e-12)
    mid = len(pts) // 2
    d = solver.distance((faces[mid:mid + 1], bary[mid:mid + 1]))
    np.testing.assert_allclose(d, np.linalg.norm(V - pts[mid], axis=1), atol=1e-9)


def test_path_between_components_is_empty():
    V, F = grid(5)
    V2 = np.concatenate([V, V + [10, 0, 0]])
    F2 = np.concatenate([F, F + len(V)])
    pts, length = ef.geodesic_path(V2, F2, 0, len(V))
    assert pts.shape == (0, 3) and np.isinf(length)


def test_edge_front_levels_on_a_grid():
    V, F = grid(9)
    levels = ef.edge_front_levels(V, F, 40)  # the centre of a 9 x 9 grid
    assert levels.dtype == np.int32 and levels[40] == 0
    neighbours = np.unique(F[np.any(F == 40, axis=1)])
    assert set(levels[neighbours[neighbours != 40]].tolist()) == {1}
    assert levels.max() >= 4
    capped = ef.edge_front_levels(V, F, 40, max_levels=2)
    assert np.all((capped == -1) | (capped == levels)) and (capped == -1).any()


@pytest.mark.parametrize("method", ["mdf", "fast", "windows", "dijkstra"])
def test_batch_rows_equal_single_fields_for_any_thread_count(method):
    V, F = icosphere(3)
    solver = ef.GeodesicSolver(V, F)
    sources = [0, 17, 40, 99, 300]
    one = solver.distances(sources, method=method, threads=1)
    assert one.shape == (len(sources), len(V)) and one.dtype == np.float64
    for threads in (2, 3):
        assert solver.distances(sources, method=method, threads=threads).tobytes() == one.tobytes()
    for i, s in enumerate(sources):
        assert one[i].tobytes() == solver.distance([s], method=method).tobytes()
    targets = [5, 6, 7, 200]
    matrix = solver.distances(sources, targets, method=method, threads=2)
    assert matrix.shape == (len(sources), len(targets))
    np.testing.assert_array_equal(matrix, one[:, targets])


def test_batch_progress_cancels_and_errors():
    V, F = icosphere(3)
    solver = ef.GeodesicSolver(V, F)
    calls = []
    partial = solver.distances(list(range(8)), threads=1, progress=lambda done, total: calls.append(done) or done < 3)
    assert calls == [1, 2, 3]
    assert np.isnan(partial[3:]).all() and not np.isnan(partial[:3]).any()

    def boom(done, total):
        raise KeyError("stop")

    with pytest.raises(KeyError):
        solver.distances([0, 1, 2], threads=2, progress=boom)
    with pytest.raises(ValueError):
        solver.distances([len(V)])
    with pytest.raises(ValueError):
        solver.distances([], threads=1)
    with pytest.raises(ValueError):
        solver.distances([0], method="nope")
