"""Shared fixtures and mesh makers for the Python package's tests (run by ctest as python.*)."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("EDGEFRONT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
APP_DIR = pathlib.Path(os.environ.get("EDGEFRONT_APP_DIR", SOURCE_DIR / "build" / "apps"))
DATA_DIR = SOURCE_DIR / "data"
TEST_DATA_DIR = SOURCE_DIR / "tests" / "data"
# The Python tests' own inputs (kept out of tests/data, which seeds the fuzzers' corpus: an 88 KB
# cloud there would raise libFuzzer's input size limit).
PY_DATA_DIR = SOURCE_DIR / "tests" / "python" / "data"


def app(name, *args, cwd=None):
    """Runs build/apps/<name> with args; returns its stdout (fails the test on a non-zero exit)."""
    exe = APP_DIR / name
    if not exe.exists():
        pytest.fail(f"{exe} is not built (the Python tests compare with the apps; build them first)")
    r = subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True, cwd=cwd)
    assert r.returncode == 0, f"{name} {' '.join(map(str, args))} exited {r.returncode}: {r.stderr}"
    return r.stdout


def grid(n=21, size=2.0, jitter=0.0, seed=1):
    """A planar n x n grid in z = 0 over [-size/2, size/2]^2, each quad split along an alternating
    diagonal (an irregular triangulation); interior vertices jittered by `jitter` cell sizes."""
    t = np.linspace(-size / 2, size / 2, n)
    x, y = np.meshgrid(t, t, indexing="ij")
    V = np.stack([x.ravel(), y.ravel(), np.zeros(n * n)], axis=1)
    if jitter:
        rng = np.random.default_rng(seed)
        inner = (np.abs(V[:, 0]) < size / 2 - 1e-12) & (np.abs(V[:, 1]) < size / 2 - 1e-12)
        V[inner, :2] += rng.uniform(-jitter, jitter, (inner.sum(), 2)) * (size / (n - 1))
    F = []
    for i in range(n - 1):
        for j in range(n - 1):
            a, b, c, d = i * n + j, (i + 1) * n + j, (i + 1) * n + j + 1, i * n + j + 1
            if (i + j) % 2:
                F += [(a, b, c), (a, c, d)]
            else:
                F += [(a, b, d), (b, c, d)]
    return V, np.array(F, dtype=np.int64)


def icosphere(levels=4, radius=1.0):
    """A subdivided icosahedron projected on the sphere (outward), (V, F)."""
    p = (1 + 5 ** 0.5) / 2
    V = [(-1, p, 0), (1, p, 0), (-1, -p, 0), (1, -p, 0), (0, -1, p), (0, 1, p), (0, -1, -p), (0, 1, -p),
         (p, 0, -1), (p, 0, 1), (-p, 0, -1), (-p, 0, 1)]
    F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
         (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    V = [np.array(v, float) / np.linalg.norm(v) for v in V]
    for _ in range(levels):
        mid = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                m = V[a] + V[b]
                V.append(m / np.linalg.norm(m))
                mid[key] = len(V) - 1
            return mid[key]

        G = []
        for a, b, c in F:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            G += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        F = G
    return np.array(V) * radius, np.array(F, dtype=np.int64)


def twisted_tube(along=40, around=24, length=2.0, width=0.5, thickness=0.1, twisted=True):
    """A flattened closed tube along x whose cross-section is mirrored (z -> -z) beyond the middle
    segment: the two layers cross there and everything beyond is inside out (the geometry of
    twist::twisted_tube). Returns (V, F, outward) where outward(c) is the intended outward normal
    at a face centre c (None on the crossing segment). twisted=False: the same tube, not mirrored."""
    twist = along // 2 if twisted else along
    h, half, dx = thickness / 2, length / 2, length / along
    V = []
    for i in range(along + 1):
        x, sign = -half + i * dx, (1.0 if i <= twist else -1.0)
        for j in range(around):
            phi = 2 * np.pi * j / around
            V.append((x, width * np.cos(phi), sign * h * np.sin(phi)))
    c0, c1 = len(V), len(V) + 1
    V += [(-half, 0, 0), (half, 0, 0)]

    def at(i, j):
        return i * around + (j + around) % around

    F = []
    for i in range(along):
        for j in range(around):
            F += [(at(i, j), at(i, j + 1), at(i + 1, j + 1)), (at(i, j), at(i + 1, j + 1), at(i + 1, j))]
    for j in range(around):
        F += [(c0, at(0, j + 1), at(0, j)), (c1, at(along, j), at(along, j + 1))]
    x_lo = -half + twist * dx

    def outward(c):
        if x_lo < c[0] < x_lo + dx:
            return None
        if abs(c[0] + half) < 1e-9:
            return np.array([-1.0, 0, 0])
        if abs(c[0] - half) < 1e-9:
            return np.array([1.0, 0, 0])
        n = np.array([0.0, c[1] / width ** 2, c[2] / h ** 2])
        return n / np.linalg.norm(n)

    return np.array(V), np.array(F, dtype=np.int64), outward


def face_normals(V, F):
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    return n / np.linalg.norm(n, axis=1, keepdims=True)


def border_edges(F):
    """Directed edges without their reverse (border edges of an oriented mesh)."""
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    s = set(map(tuple, e))
    return [x for x in s if (x[1], x[0]) not in s]


@pytest.fixture
def bumpy():
    import edgefront as ef
    return ef.read_mesh(DATA_DIR / "bumpy-sphere.off")
