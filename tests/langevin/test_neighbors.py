"""The Verlet list against brute force: every pair closer than the cutoff, sorted, with its reverse slot;
when a list kept between calls is still valid."""

import numpy as np
import pytest

from fricgen.langevin.neighbors import SHORT, build_neighbors, neighbor_list, still_valid
from fricgen.langevin.records import NeighborList

CASES = [  # (dimension, particles, box, lists longer than SHORT): many cells, boxes of one or two cells along a direction
    (2, 500, [20.0, 20.0, 0.0], False),
    (3, 400, [8.0, 9.0, 7.0], False),
    (2, 50, [2.5, 3.0, 0.0], True),
    (3, 30, [2.0, 2.9, 5.0], False),
    (3, 300, [4.0, 4.0, 4.0], True),
]


@pytest.mark.parametrize(("dims", "n", "box", "long"), CASES)
def test_the_list_holds_exactly_the_pairs_within_the_cutoff(dims, n, box, long):
    rng = np.random.default_rng(3)
    box = np.array(box)
    pos = rng.uniform(0, 1, (n, 3)) * box
    cutoff = 1.3
    start, neighbors, reverse = build_neighbors(pos, box, dims, cutoff)
    assert (np.diff(start).max() > SHORT) == long  # insertion sort, and the general sort beyond SHORT
    for i in range(n):
        d = pos[:, :dims] - pos[i, :dims]
        d -= box[:dims] * np.rint(d / box[:dims])
        within = [k for k in np.flatnonzero((d**2).sum(1) < cutoff**2) if k != i]
        assert list(neighbors[start[i] : start[i + 1]]) == within, i
        for slot in range(start[i], start[i + 1]):
            k = neighbors[slot]
            assert start[k] <= reverse[slot] < start[k + 1] and neighbors[reverse[slot]] == i


def test_a_kept_list_is_valid_only_for_what_it_was_built_for():
    """still_valid: the same particles, box and cutoff, and no particle moved more than skin/2 since
    the build (minimum image, so a move across the boundary counts by its true length)."""
    rng = np.random.default_rng(5)
    box, inv_box, cutoff, skin = np.array([10.0, 10.0, 0.0]), np.array([0.1, 0.1, 0.0]), 1.5, 0.4
    pos = np.zeros((100, 3))
    pos[:, :2] = rng.uniform(0, 10, (100, 2))
    pos[3, 0] = 0.05
    listed = neighbor_list(pos, box, 2, cutoff)
    assert still_valid(listed, pos, box, inv_box, 2, cutoff, skin)
    moved = pos.copy()
    moved[7, 0] += 0.19
    assert still_valid(listed, moved, box, inv_box, 2, cutoff, skin)
    moved[7, 0] += 0.02
    assert not still_valid(listed, moved, box, inv_box, 2, cutoff, skin)
    moved[7, 0] = np.nan
    assert not still_valid(listed, moved, box, inv_box, 2, cutoff, skin)
    wrapped = pos.copy()
    wrapped[3, 0] = 9.95  # a move by 0.1 across the boundary
    assert still_valid(listed, wrapped, box, inv_box, 2, cutoff, skin)
    assert not still_valid(listed, pos, box, inv_box, 2, cutoff + 0.1, skin)
    assert not still_valid(listed, pos[:99], box, inv_box, 2, cutoff, skin)
    box[0] = 11.0  # the list keeps its own copy of the box it was built for
    assert not still_valid(listed, pos, box, np.array([1 / 11, 0.1, 0.0]), 2, cutoff, skin)
    assert not still_valid(NeighborList.unbuilt(), pos, box, inv_box, 2, cutoff, skin)
