"""Twist detection and repair on a twisted tube, with the edit record replayed in numpy."""

import numpy as np

import edgefront as ef
from conftest import face_normals, twisted_tube


def outward_share(V, F, outward):
    """Area-free share of faces with an intended normal whose normal agrees with it."""
    n = face_normals(V, F)
    c = V[F].mean(axis=1)
    agree = total = 0
    for ni, ci in zip(n, c):
        t = outward(ci)
        if t is None:
            continue
        total += 1
        agree += float(ni @ t) > 0
    return agree / total


def test_detect_finds_the_twisted_half():
    V, F, outward = twisted_tube()
    labels = ef.detect_twists(V, F)
    assert labels.dtype == np.int32 and labels.shape == (len(F),)
    assert labels.max() >= 0, "no twisted region found"
    assert np.all(labels >= -1)
    twisted = labels >= 0
    c = V[F].mean(axis=1)
    assert np.mean(c[twisted, 0] > 0) > 0.5  # mostly in the mirrored half (x > 0) or along its twist line
    V_ok, F_ok, _ = twisted_tube(twisted=False)  # the same tube without the twist: nothing found
    assert ef.detect_twists(V_ok, F_ok).max() == -1


def test_repair_and_replay_the_record():
    V, F, outward = twisted_tube()
    before = outward_share(V, F, outward)
    assert before < 0.6  # about half of the tube is inside out
    V2, F2, rec = ef.repair_twists(V, F)
    assert rec["vertices_before"] == len(V) and rec["faces_before"] == len(F)
    assert V2.dtype == np.float64 and F2.dtype == np.int32
    assert len(rec["faces_flipped"]) + len(rec["faces_removed"]) > 0
    # the record replayed in numpy on our own copy gives the same mesh
    V3, F3 = ef.apply_record(V, F, rec)
    assert np.array_equal(V3, V2) and np.array_equal(F3, F2)
    # the repaired mesh faces outward where the truth says so, and has no twisted region left
    assert outward_share(V2, F2, outward) > 0.95
    used = np.unique(F2)
    assert ef.detect_twists(V2, F2).max() == -1 or len(used) < len(V2)


def test_repair_with_reference_normals():
    V, F, outward = twisted_tube()
    c = V[F].mean(axis=1)
    keep = [i for i in range(len(F)) if outward(c[i]) is not None]
    P = c[keep]
    N = np.array([outward(c[i]) for i in keep])
    V2, F2, rec = ef.repair_twists(V, F, points=P, normals=N)
    assert outward_share(V2, F2, outward) > 0.95
    V3, F3 = ef.apply_record(V, F, rec)
    assert np.array_equal(F3, F2)


def test_nothing_to_repair_gives_an_empty_record():
    from conftest import icosphere
    V, F = icosphere(2)
    V2, F2, rec = ef.repair_twists(V, F)
    assert np.array_equal(V2, V) and np.array_equal(F2, F)
    assert all(len(rec[k]) == 0 for k in rec if k not in ("vertices_before", "faces_before"))
