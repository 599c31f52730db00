"""Cell list plus Verlet list with a skin, for periodic boxes of any density.

The list is *full* (each pair appears in the lists of both particles) and each particle's list is
sorted by index, so force sums run in a fixed order: trajectories are bit-identical for any
thread count and any cell traversal order. Stored in CSR form: the neighbours of i are
``neighbors[start[i]:start[i + 1]]``. Positions are wrapped into [0, L) in every periodic
direction; in 2-D the z coordinate is 0 and not periodic.
"""

from __future__ import annotations

import numba
import numpy as np


@numba.njit(inline="always", cache=True)
def minimum_image(d, length, inverse):
    """d - L rint(d / L) with inverse = 1/L: exact negation symmetry (rint rounds half to even)."""
    return d - length * np.rint(d * inverse)


@numba.njit(cache=True)
def _offsets(n):
    """Distinct neighbour-cell offsets along one direction with n cells."""
    if n >= 3:
        return np.array([-1, 0, 1])
    if n == 2:
        return np.array([0, 1])
    return np.array([0])


@numba.njit(cache=True)
def _cells(pos, box, dims, cutoff):
    n = np.ones(3, dtype=np.int64)
    for a in range(dims):
        n[a] = max(1, int(box[a] / cutoff))
    cell = np.empty(pos.shape[0], dtype=np.int64)
    for i in range(pos.shape[0]):
        index = 0
        for a in range(dims):
            c = int(pos[i, a] / box[a] * n[a])
            c = min(max(c, 0), n[a] - 1)
            index = index * n[a] + c
        cell[i] = index
    order = np.argsort(cell, kind="mergesort")
    first = np.zeros(n[0] * n[1] * n[2] + 1, dtype=np.int64)
    for i in range(pos.shape[0]):
        first[cell[i] + 1] += 1
    for c in range(first.size - 1):
        first[c + 1] += first[c]
    return n, cell, order, first


@numba.njit(cache=True)
def _visit(i, pos, box, dims, cutoff2, cells, out, fill):
    """Count (fill=False) or write (fill=True) the neighbours of i; returns the count.
    ``cells`` = (cells per direction, cell of each particle, particles sorted by cell, first of each cell)."""
    n, cell, order, first = cells
    c = cell[i]
    coords = np.zeros(3, dtype=np.int64)
    rest = c
    for a in range(dims - 1, -1, -1):
        coords[a] = rest % n[a]
        rest //= n[a]
    count = 0
    ox, oy, oz = _offsets(n[0]), _offsets(n[1]), _offsets(n[2]) if dims == 3 else np.array([0])
    for dx in ox:
        for dy in oy:
            for dz in oz:
                shift = (dx, dy, dz)
                index = 0
                for a in range(dims):
                    index = index * n[a] + (coords[a] + shift[a]) % n[a]
                for slot in range(first[index], first[index + 1]):
                    k = order[slot]
                    if k == i:
                        continue
                    r2 = 0.0
                    for a in range(dims):
                        d = minimum_image(pos[k, a] - pos[i, a], box[a], 1.0 / box[a])
                        r2 += d * d
                    if r2 < cutoff2:
                        if fill:
                            out[count] = k
                        count += 1
    return count


@numba.njit(parallel=True, cache=True)
def build_neighbors(pos, box, dims, cutoff):
    """Full Verlet list of all pairs closer than ``cutoff``: CSR (start, neighbors) and ``reverse``,
    the slot of (k, i) for the slot of (i, k)."""
    size = pos.shape[0]
    cells = _cells(pos, box, dims, cutoff)
    counts = np.empty(size, dtype=np.int64)
    dummy = np.empty(0, dtype=np.int64)
    for i in numba.prange(size):
        counts[i] = _visit(i, pos, box, dims, cutoff * cutoff, cells, dummy, False)
    start = np.zeros(size + 1, dtype=np.int64)
    for i in range(size):
        start[i + 1] = start[i] + counts[i]
    neighbors = np.empty(start[size], dtype=np.int64)
    for i in numba.prange(size):
        segment = neighbors[start[i] : start[i + 1]]
        _visit(i, pos, box, dims, cutoff * cutoff, cells, segment, True)
        segment.sort()
    reverse = np.empty_like(neighbors)
    for i in numba.prange(size):
        for slot in range(start[i], start[i + 1]):
            k = neighbors[slot]
            reverse[slot] = start[k] + np.searchsorted(neighbors[start[k] : start[k + 1]], i)
    return start, neighbors, reverse
