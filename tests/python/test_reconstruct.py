"""Reconstruction of a bundled cloud (closed, oriented), bit for bit with gcs-reconstruct, and
evaluation bit for bit with gcs-eval --json."""

import json

import numpy as np
import pytest

import edgefront as ef
from conftest import PY_DATA_DIR, app

# tests/python/data/bumpy-sphere-2k.xyz was written by
#   build/apps/ef-shapes bumpy-sphere --points 2000 --seed 1 --decimals 4 -o tests/python/data/bumpy-sphere-2k.xyz
CLOUD = PY_DATA_DIR / "bumpy-sphere-2k.xyz"
TARGET = 400


@pytest.fixture(scope="module")
def cloud():
    return ef.read_points(CLOUD)


@pytest.fixture(scope="module")
def result(cloud):
    P, N = cloud
    return ef.reconstruct(P, N, vertices=TARGET, seed=1, return_info=True)


def test_closed_and_oriented(cloud, result):
    P, N = cloud
    V, F, info = result
    assert info["stop_reason"] == "target reached" and not info["cancelled"]
    assert V.shape == (TARGET, 3) and F.dtype == np.int32
    e = ef.evaluate(V, F, P, N, samples=20000)
    assert e["mesh"]["closed"] and e["mesh"]["border_loops"] == 0
    assert e["mesh"]["components"] == 1 and e["mesh"]["genus"] == 0
    assert e["mesh"]["edge_manifold"] and e["mesh"]["vertex_manifold"]
    assert e["orientation_consistency"]["raw"] > 0.99  # faces outward, as the normals
    assert e["chamfer_l1_percent"] < 1.0


def test_bit_for_bit_with_gcs_reconstruct(tmp_path, cloud, result):
    V, F, _ = result
    out = tmp_path / "r.ply"
    app("gcs-reconstruct", CLOUD, "-o", out, "--vertices", TARGET, "--seed", 1, "-q")
    V2, F2 = ef.read_mesh(out)
    assert np.array_equal(V, V2) and np.array_equal(F, F2)


def test_another_seed_gives_another_mesh(cloud, result):
    P, N = cloud
    V, F, _ = result
    V3, F3 = ef.reconstruct(P, N, vertices=TARGET, seed=2)
    assert len(V3) == TARGET and not np.array_equal(V, V3)


def test_preset_bit_for_bit_with_gcs_reconstruct_and_not_the_defaults(tmp_path, cloud):
    # Without normals open_sheet fits quadric normals (InputOptions::quadric_normals): another mesh
    # than the defaults, and the same bytes as gcs-reconstruct --preset open_sheet.
    P, _ = cloud
    V, F = ef.reconstruct(P, vertices=TARGET, preset="open_sheet")
    out = tmp_path / "r.ply"
    app("gcs-reconstruct", CLOUD, "-o", out, "--vertices", TARGET, "--ignore-normals", "--preset", "open_sheet", "-q")
    V2, F2 = ef.read_mesh(out)
    assert np.array_equal(V, V2) and np.array_equal(F, F2)
    V0, _ = ef.reconstruct(P, vertices=TARGET)
    assert not np.array_equal(V, V0)
    with pytest.raises(ValueError, match="thin_shell"):
        ef.reconstruct(P, vertices=TARGET, preset="thin-shell")


def test_evaluate_bit_for_bit_with_gcs_eval(tmp_path, cloud, result):
    P, N = cloud
    V, F, _ = result
    ef.write_mesh(tmp_path / "r.ply", V, F)
    ref = json.loads(app("gcs-eval", tmp_path / "r.ply", CLOUD, "--json", "--samples", 20000))
    e = ef.evaluate(V, F, P, N, samples=20000)
    assert e == ref


def test_evaluate_against_a_mesh(result):
    V, F, _ = result
    e = ef.evaluate(V, F, V, gt_faces=F, samples=5000, self_intersections=False)
    assert e["ground_truth"]["kind"] == "mesh"
    assert e["chamfer_l1_percent"] < 0.1  # the mesh against itself: only the sampling gap
    assert e["mesh"]["self_intersecting_pairs"] is None
