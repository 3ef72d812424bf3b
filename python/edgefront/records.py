"""Replaying an edit record (what repair_twists returns) on plain numpy arrays."""

import numpy as np


def apply_record(V, F, record, compact=True):
    """apply_record(V, F, record, compact=True) -> (V2, F2)

    Replays the edit record of edgefront.repair_twists on the host's own arrays, in numpy, in the
    record's order (twist/edit_record.h): 1. append the added vertices; 2. move the moved ones;
    3. flip faces (a b c -> a c b); 4. replace corners (in face f the corner holding vertex
    `from` takes `to`; the replacements of one face apply together); 5. remove faces (their rows
    become -1 -1 -1); 6. append the added faces. With compact=True the removed rows are dropped
    (keeping the order of the rest), which gives the F that repair_twists returns.

    V must have record["vertices_before"] rows and F record["faces_before"] rows. Raises
    ValueError when the record does not fit the arrays (a corner that does not hold `from`, an
    index out of range); V and F are never modified.
    """
    V = np.asarray(V, dtype=np.float64)
    F = np.array(F, dtype=np.int64)  # a copy: the caller's array stays as it is
    n0, m0 = int(record["vertices_before"]), int(record["faces_before"])
    if V.shape != (n0, 3) or F.shape != (m0, 3):
        raise ValueError(f"apply_record: the record is for {n0} vertices and {m0} faces, "
                         f"got V {V.shape} and F {F.shape}")
    added = np.asarray(record["vertices_added_position"], dtype=np.float64).reshape(-1, 3)
    V = np.concatenate([V, added])  # 1.
    moved = np.asarray(record["vertices_moved"], dtype=np.int64)
    if moved.size:
        if moved.min() < 0 or moved.max() >= len(V):
            raise ValueError("apply_record: a moved vertex is out of range")
        V[moved] = np.asarray(record["vertices_moved_position"], dtype=np.float64).reshape(-1, 3)  # 2.
    flipped = np.asarray(record["faces_flipped"], dtype=np.int64)
    if flipped.size:
        if flipped.min() < 0 or flipped.max() >= m0:
            raise ValueError("apply_record: a flipped face is out of range")
        F[flipped] = F[flipped][:, [0, 2, 1]]  # 3.
    corners = np.asarray(record["corners_replaced"], dtype=np.int64).reshape(-1, 3)
    if corners.size:  # 4.: each replacement to the corner that held `from` before any of this face's
        faces = corners[:, 0]
        if faces.min() < 0 or faces.max() >= m0:
            raise ValueError("apply_record: a replaced corner's face is out of range")
        before = F[faces]                                  # the rows as they were before step 4
        hit = before == corners[:, 1:2]                    # which corner holds `from`
        if not np.all(hit.sum(axis=1) == 1):
            bad = int(np.flatnonzero(hit.sum(axis=1) != 1)[0])
            raise ValueError(f"apply_record: face {int(faces[bad])} does not hold vertex {int(corners[bad, 1])} once")
        rows, cols = np.nonzero(hit)
        F[faces[rows], cols] = corners[rows, 2]
    removed = np.asarray(record["faces_removed"], dtype=np.int64)
    if removed.size:
        if removed.min() < 0 or removed.max() >= m0:
            raise ValueError("apply_record: a removed face is out of range")
        F[removed] = -1  # 5.
    F = np.concatenate([F, np.asarray(record["faces_added"], dtype=np.int64).reshape(-1, 3)])  # 6.
    if F.size and F.max() >= len(V):
        raise ValueError("apply_record: a face refers to a vertex beyond the record's vertices")
    if compact:
        F = F[F[:, 0] >= 0]
    return V, F.astype(np.int32)
