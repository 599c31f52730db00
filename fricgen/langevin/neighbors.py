"""Cell list plus Verlet list with a skin, for periodic boxes of any density.

The list is *full* (each pair appears in the lists of both particles) and each particle's list is
sorted by index, so force sums run in a fixed order: trajectories are bit-identical for any
thread count and any cell traversal order. Stored in CSR form: the neighbours of i are
``neighbors[start[i]:start[i + 1]]``. Positions are wrapped into [0, L) in every periodic
direction; in 2-D the z coordinate is 0 and not periodic.

A list built with cutoff r_c = reach + skin holds every pair closer than the reach for as long as no
particle has moved more than skin/2 since the build. The engine keeps it from one call to the next
(:class:`fricgen.langevin.records.NeighborList`) and builds a new one only when that fails: which
valid list a step uses does not change its result.
"""

from __future__ import annotations

import numba
import numpy as np

from .records import NeighborList

#: Neighbour counts up to which a list is sorted by insertion (fricgen.langevin.neighbors._sort_short).
SHORT = 32


@numba.njit(inline="always", cache=True)
def minimum_image(d, length, inverse):
    """d - L rint(d / L) with inverse = 1/L: exact negation symmetry (rint rounds half to even)."""
    return d - length * np.rint(d * inverse)


@numba.njit(inline="always", cache=True)
def separation(pos, i, k, box, inv_box, dims):
    """The minimum-image vector r_k - r_i as (dx, dy, dz); dz = 0 in 2-D."""
    dx = minimum_image(pos[k, 0] - pos[i, 0], box[0], inv_box[0])
    dy = minimum_image(pos[k, 1] - pos[i, 1], box[1], inv_box[1])
    dz = minimum_image(pos[k, 2] - pos[i, 2], box[2], inv_box[2]) if dims == 3 else 0.0
    return dx, dy, dz


@numba.njit(inline="always", cache=True)
def squared_displacement(pos, reference, i, box, inv_box, dims):
    """|r_i - reference_i|^2, minimum image."""
    d2 = 0.0
    for a in range(dims):
        d = minimum_image(pos[i, a] - reference[i, a], box[a], inv_box[a])
        d2 += d * d
    return d2


@numba.njit(inline="always", cache=True)
def _offsets(n):
    """The distinct neighbour-cell offsets along a direction with n cells: range(first, last + 1)."""
    return (-1, 1) if n >= 3 else (0, min(n - 1, 1))


@numba.njit(cache=True)
def offsets(counts):
    """CSR offsets of consecutive groups of sizes ``counts``: [0, counts[0], counts[0] + counts[1], ...]."""
    out = np.zeros(counts.size + 1, dtype=np.int64)
    for i in range(counts.size):
        out[i + 1] = out[i] + counts[i]
    return out


@numba.njit(cache=True)
def sort_by_key(keys, first):
    """The indices of ``keys`` sorted by key, stably (the filling pass of a counting sort), given the
    offsets ``first`` of the keys' counts: those of key g land in order[first[g]:first[g + 1]]."""
    order, filled = np.empty(keys.size, dtype=np.int64), first[:-1].copy()
    for j in range(keys.size):
        order[filled[keys[j]]] = j
        filled[keys[j]] += 1
    return order


@numba.njit(cache=True)
def _cells(pos, box, dims, cutoff):
    """(cells per direction, cell of each particle, particles sorted by cell (stable), first of each
    cell in that order, positions in that order): the positions are copied in cell order so that a
    cell's particles are read from consecutive memory."""
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
    counts = np.zeros(n[0] * n[1] * n[2], dtype=np.int64)
    for i in range(pos.shape[0]):
        counts[cell[i]] += 1
    first = offsets(counts)
    order = sort_by_key(cell, first)
    return n, cell, order, first, pos[order]


@numba.njit(inline="always", cache=True)
def _wrap(c, n):
    """c modulo n for -n <= c < 2n, without an integer division (which would cost more than a
    distance check, 27 times per particle in 3-D)."""
    return c + n if c < 0 else (c - n if c >= n else c)


@numba.njit(inline="always", cache=True)
def _sort_short(segment):
    """Sort a particle's neighbours in place: insertion sort for the few of a contact list (a call
    of the general sort costs more than sorting them), the general sort beyond SHORT."""
    if segment.size > SHORT:
        segment.sort()
        return
    for j in range(1, segment.size):
        value, m = segment[j], j - 1
        while m >= 0 and segment[m] > value:
            segment[m + 1] = segment[m]
            m -= 1
        segment[m + 1] = value


@numba.njit(cache=True)
def _visit(i, pos, box, dims, cutoff2, cells, out, fill):
    """fill=False: the number of particles in i's cell and the cells around it (i included), a bound
    on its neighbours that needs no distance; fill=True: write the neighbours of i into ``out`` (as
    long as that bound), returns their count. ``cells``: as _cells returns them."""
    n, cell, order, first, packed = cells
    nx, ny, nz = n[0], n[1], n[2]
    cx, cy, cz = (cell[i] // (ny * nz), (cell[i] // nz) % ny, cell[i] % nz) if dims == 3 else (cell[i] // ny, cell[i] % ny, 0)
    (x0, x1), (y0, y1), (z0, z1) = _offsets(nx), _offsets(ny), _offsets(nz) if dims == 3 else (0, 0)
    inv_x, inv_y, inv_z = 1.0 / box[0], 1.0 / box[1], 1.0 / box[2] if dims == 3 else 0.0
    count = 0
    for dx in range(x0, x1 + 1):
        column = _wrap(cx + dx, nx) * ny
        for dy in range(y0, y1 + 1):
            row = (column + _wrap(cy + dy, ny)) * nz
            for dz in range(z0, z1 + 1):
                index = row + _wrap(cz + dz, nz)
                if not fill:
                    count += first[index + 1] - first[index]
                    continue
                for slot in range(first[index], first[index + 1]):
                    k = order[slot]
                    d = minimum_image(packed[slot, 0] - pos[i, 0], box[0], inv_x)
                    r2 = d * d
                    d = minimum_image(packed[slot, 1] - pos[i, 1], box[1], inv_y)
                    r2 += d * d
                    if dims == 3:
                        d = minimum_image(packed[slot, 2] - pos[i, 2], box[2], inv_z)
                        r2 += d * d
                    out[count] = k  # written always and kept if near (out has room for every candidate): no branch to mispredict
                    count += (r2 < cutoff2) & (k != i)
    return count


@numba.njit(cache=True)
def _reverse_slots(start, neighbors):
    """reverse[slot of (i, k)] = slot of (k, i) in a full, sorted list. Walks the particles in order:
    the partners k < i lead i's list, and i is the next partner above k in k's list that no earlier
    particle took (cursor[k]), since the particles that took them came before i."""
    reverse, cursor = np.empty_like(neighbors), np.empty(start.size - 1, dtype=np.int64)
    for i in range(start.size - 1):
        slot = start[i]
        while slot < start[i + 1] and neighbors[slot] < i:
            back = cursor[neighbors[slot]]
            cursor[neighbors[slot]] += 1
            reverse[slot], reverse[back] = back, slot
            slot += 1
        cursor[i] = slot
    return reverse


@numba.njit(parallel=True, cache=True)
def build_neighbors(pos, box, dims, cutoff):
    """Full Verlet list of all pairs closer than ``cutoff``: CSR (start, neighbors) and ``reverse``,
    the slot of (k, i) for the slot of (i, k). One pass over the distances: each particle writes its
    neighbours, sorted, into room for its candidates (``_visit``), then the lists are packed."""
    size = pos.shape[0]
    cells = _cells(pos, box, dims, cutoff)
    counts = np.empty(size, dtype=np.int64)
    none = np.empty(0, dtype=np.int64)
    for i in numba.prange(size):
        counts[i] = _visit(i, pos, box, dims, cutoff * cutoff, cells, none, False)
    room = offsets(counts)
    scratch = np.empty(room[size], dtype=np.int64)
    for i in numba.prange(size):
        counts[i] = _visit(i, pos, box, dims, cutoff * cutoff, cells, scratch[room[i] : room[i + 1]], True)
        _sort_short(scratch[room[i] : room[i] + counts[i]])
    start = offsets(counts)
    neighbors = np.empty(start[size], dtype=np.int64)
    for i in numba.prange(size):
        neighbors[start[i] : start[i + 1]] = scratch[room[i] : room[i] + counts[i]]
    return start, neighbors, _reverse_slots(start, neighbors)


@numba.njit(cache=True)
def neighbor_list(pos, box, dims, cutoff):
    """The :class:`NeighborList` of all pairs closer than ``cutoff`` at positions ``pos``."""
    start, neighbors, reverse = build_neighbors(pos, box, dims, cutoff)
    return NeighborList(start, neighbors, reverse, pos.copy(), box.copy(), cutoff)


@numba.njit(cache=True)
def still_valid(listed, pos, box, inv_box, dims, cutoff, skin):
    """Whether ``listed`` holds every pair closer than cutoff - skin at ``pos``: built for as many
    particles, the same box and cutoff, and no particle moved more than skin/2 (nor to NaN) since."""
    if listed.start.size != pos.shape[0] + 1 or listed.cutoff != cutoff:
        return False
    for a in range(3):
        if listed.box[a] != box[a]:
            return False
    limit = 0.25 * skin * skin
    for i in range(pos.shape[0]):
        if not squared_displacement(pos, listed.reference, i, box, inv_box, dims) <= limit:  # also NaN
            return False
    return True
