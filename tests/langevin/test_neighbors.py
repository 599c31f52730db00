"""The Verlet list against brute force: every pair closer than the cutoff, sorted, with its reverse slot."""

import numpy as np
import pytest

from fricgen.langevin.neighbors import build_neighbors

CASES = [  # (dimension, particles, box): many cells, and boxes of one or two cells along a direction
    (2, 500, [20.0, 20.0, 0.0]),
    (3, 400, [8.0, 9.0, 7.0]),
    (2, 50, [2.5, 3.0, 0.0]),
    (3, 30, [2.0, 2.9, 5.0]),
]


@pytest.mark.parametrize(("dims", "n", "box"), CASES)
def test_the_list_holds_exactly_the_pairs_within_the_cutoff(dims, n, box):
    rng = np.random.default_rng(3)
    box = np.array(box)
    pos = rng.uniform(0, 1, (n, 3)) * box
    cutoff = 1.3
    start, neighbors, reverse = build_neighbors(pos, box, dims, cutoff)
    for i in range(n):
        d = pos[:, :dims] - pos[i, :dims]
        d -= box[:dims] * np.rint(d / box[:dims])
        within = [k for k in np.flatnonzero((d**2).sum(1) < cutoff**2) if k != i]
        assert list(neighbors[start[i] : start[i + 1]]) == within, i
        for slot in range(start[i], start[i + 1]):
            assert neighbors[reverse[slot]] == i
