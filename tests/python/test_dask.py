"""The Dask examples (examples/dask/): sources of a distance matrix and a folder of scans sharded
over a dask.distributed.LocalCluster with 2 worker processes give the same bytes as the serial
run; finished items are files a rerun skips."""

import os
import pathlib
import sys

import numpy as np
import pytest

pytest.importorskip("dask", reason="dask is not importable (Debian: python3-dask)")
pytest.importorskip("distributed", reason="dask.distributed is not importable (Debian: python3-distributed)")

import edgefront as ef  # noqa: E402
from conftest import DATA_DIR, PY_DATA_DIR, SOURCE_DIR  # noqa: E402

sys.path.insert(0, str(SOURCE_DIR / "examples" / "dask"))
import distance_matrix as dm  # noqa: E402
import reconstruct_folder as rf  # noqa: E402


@pytest.fixture(scope="module")
def client():
    from dask.distributed import Client, LocalCluster
    # The worker processes import edgefront from where this process found it.
    package_root = str(pathlib.Path(ef.__file__).resolve().parents[1])
    os.environ["PYTHONPATH"] = os.pathsep.join([package_root] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


def test_distance_matrix_sharded_equals_serial(tmp_path, client):
    V, F = ef.read_mesh(DATA_DIR / "bumpy-sphere.off")
    sources = np.arange(0, 640, 16)  # 40 sources, 7 tasks of 6
    serial, computed = dm.distance_matrix(V, F, sources, tmp_path / "serial", None, chunk=6)
    assert len(computed) == 7 and serial.shape == (40, len(V))
    for i in [0, 17, 39]:
        assert np.array_equal(serial[i], ef.geodesic_distance(V, F, int(sources[i])))
    sharded, computed = dm.distance_matrix(V, F, sources, tmp_path / "dask", client, chunk=6)
    assert len(computed) == 7
    assert np.array_equal(sharded, serial)
    assert np.load(tmp_path / "dask" / "matrix.npy").tobytes() == serial.tobytes()
    # a rerun skips finished chunks; a lost one is recomputed, with the same bytes
    lost = dm.chunk_file(tmp_path / "dask", 12, 6)
    lost.unlink()
    again, computed = dm.distance_matrix(V, F, sources, tmp_path / "dask", client, chunk=6)
    assert [pathlib.Path(p).name for p in computed] == [lost.name]
    assert np.array_equal(again, serial)
    assert not list((tmp_path / "dask").glob("*.tmp"))  # no temporary file left


def test_folder_of_scans_one_task_per_scan(tmp_path, client):
    P, N = ef.read_points(PY_DATA_DIR / "bumpy-sphere-2k.xyz")
    scans = tmp_path / "scans"
    scans.mkdir()
    ef.write_points(scans / "a.xyz", P, N)
    ef.write_points(scans / "b.xyz", P[::2], N[::2])
    ef.write_points(scans / "c.ply", P * [1.0, 2.0, 0.5], None)  # an ellipsoid without normals
    written = rf.reconstruct_folder(scans, tmp_path / "serial", None, vertices=150)
    assert len(written) == 3
    written = rf.reconstruct_folder(scans, tmp_path / "dask", client, vertices=150)
    assert sorted(pathlib.Path(p).name for p in written) == ["a.ply", "b.ply", "c.ply"]
    for name in ["a.ply", "b.ply", "c.ply"]:
        assert (tmp_path / "dask" / name).read_bytes() == (tmp_path / "serial" / name).read_bytes(), name
    V, F = ef.read_mesh(tmp_path / "dask" / "a.ply")
    assert len(V) == 150
    # a rerun skips finished scans; a lost one is redone, with the same bytes
    before = (tmp_path / "dask" / "a.ply").stat().st_mtime_ns
    (tmp_path / "dask" / "b.ply").unlink()
    written = rf.reconstruct_folder(scans, tmp_path / "dask", client, vertices=150)
    assert [pathlib.Path(p).name for p in written] == ["b.ply"]
    assert (tmp_path / "dask" / "b.ply").read_bytes() == (tmp_path / "serial" / "b.ply").read_bytes()
    assert (tmp_path / "dask" / "a.ply").stat().st_mtime_ns == before
