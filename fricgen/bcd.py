"""Brownian cluster dynamics (BCD) of hard rods on a ring (Antonov et al. 2022, B-1..19).

Overdamped rods of length sigma, dx_i/dt = mu F_i + sqrt(2D) xi_i (B-1, B-27), on a periodic line
of length L. Per step dt:

1. trial forces F_i = f(x_i) + F_drive + sum_j f_int(x_i, x_j) + sqrt(2D/dt)/mu N_i (B-11, B-28),
   with N_i keyed on (seed, step, replica, i) (counter-based, reproducible);
2. cluster analysis: each run of rods in contact is split recursively at the cut with the largest
   positive difference of mean forces (right minus left); pieces that cannot split move with
   mu times their mean force (B-4, B-5, B-12);
3. event-driven propagation: the earliest collision inside the step merges the two clusters
   perfectly inelastically, velocity (m v_left + n v_right)/(m + n) (B-13..18), until t + dt (B-19).

Continuous pair forces act between neighbours (f_int of range sigma + eps < 2 sigma, e.g. the
sticky force B-32). Positions are kept unwrapped and ordered (x_0 < ... < x_{N-1} < x_0 + L): rods
never pass each other. Sampling after each step adds the rods of every period to histograms over
one wavelength (B-24, B-25) and histograms the gaps r - sigma of neighbours at the left rod's bin:
exact contacts (left by merging) apart, positive gaps in bins of width w (B-26; see rods.py for the
estimate of the contact density).
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types

from .langevin import SCALAR_KERNEL
from .rng import normal_pair_at, stream_key

BCD_STREAM = 4
CONTACT_TOLERANCE = 1e-12  # relative to sigma: gaps below it are contacts
OK, PASSED, ALL_IN_CONTACT = 0, 1, 2

_F, _I, _B = types.float64, types.int64, types.boolean
_V, _M, _T = types.Array(_F, 1, "C"), types.Array(_F, 2, "C"), types.Array(_F, 3, "C")


@numba.njit(inline="always", cache=True)
def _gap(x, i, length):
    """x_{i+1} - x_i around the ring."""
    j = i + 1
    return x[j] - x[i] if j < x.size else x[0] + length - x[i]


@numba.njit(cache=True)
def _cluster_velocities(forces, members, count, mu, v, stack, prefix):
    """Split the contact cluster members[0:count] recursively (B-4, B-5) and set v = mu <F>."""
    prefix[0] = 0.0
    for k in range(count):
        prefix[k + 1] = prefix[k] + forces[members[k]]
    stack[0, 0], stack[0, 1] = 0, count
    top = 1
    while top > 0:
        top -= 1
        a, b = stack[top, 0], stack[top, 1]
        best, cut = 0.0, -1
        for j in range(a + 1, b):
            difference = (prefix[b] - prefix[j]) / (b - j) - (prefix[j] - prefix[a]) / (j - a)
            if difference > best:
                best, cut = difference, j
        if cut < 0:
            velocity = mu * (prefix[b] - prefix[a]) / (b - a)
            for k in range(a, b):
                v[members[k]] = velocity
        else:
            stack[top, 0], stack[top, 1] = a, cut
            stack[top + 1, 0], stack[top + 1, 1] = cut, b
            top += 2


@numba.njit(cache=True)
def _step(x, forces, v, length, sigma, mu, dt, members, stack, prefix):
    """Cluster analysis, then event-driven propagation over dt; returns a status."""
    n = x.size
    tolerance = CONTACT_TOLERANCE * sigma
    start = -1
    for i in range(n):
        if _gap(x, i, length) - sigma > tolerance:
            start = i
            break
    if start < 0:
        return ALL_IN_CONTACT
    count = 0
    for offset in range(1, n + 1):
        i = (start + offset) % n
        members[count] = i
        count += 1
        if _gap(x, i, length) - sigma > tolerance:  # i is the right end of its cluster
            _cluster_velocities(forces, members, count, mu, v, stack, prefix)
            count = 0
    elapsed = 0.0
    while True:
        first, when = -1, dt - elapsed
        for i in range(n):
            j = i + 1 if i + 1 < n else 0
            if v[i] > v[j]:
                t = (_gap(x, i, length) - sigma) / (v[i] - v[j])
                if t < when:
                    first, when = i, max(t, 0.0)
        for i in range(n):
            x[i] += v[i] * when
        elapsed += when
        if first < 0:
            break
        # merge the cluster ending at `first` with the one starting at first + 1 (B-17)
        left, right = first, (first + 1) % n
        m, k = 1, 1
        while m < n and v[(left - m) % n] == v[left] and _gap(x, (left - m) % n, length) - sigma <= tolerance:
            m += 1
        while k < n and v[(right + k) % n] == v[right] and _gap(x, (right + k - 1) % n, length) - sigma <= tolerance:
            k += 1
        merged = (m * v[left] + k * v[right]) / (m + k)
        for q in range(m):
            v[(left - q) % n] = merged
        for q in range(k):
            v[(right + q) % n] = merged
    for i in range(n):
        if _gap(x, i, length) < sigma * (1.0 - 1e-9):
            return PASSED
    return OK


@numba.njit(
    _I(_M, _F, _F, _F, _F, _F, _I, _I, _I, SCALAR_KERNEL, _V, _F, SCALAR_KERNEL, _V, _F, _B, _F, _F, _M, _T),
    parallel=True,
    cache=True,
)  # fmt: skip
def advance_rods(positions, length, sigma, mu, diffusion, dt, steps, first_step, seed, external, external_params, drive,
                 pair_force, pair_params, pair_range, pair_on, wavelength, gap_width, rho_counts, gap_counts):  # fmt: skip
    """Advance every replica (row of positions) by ``steps`` BCD steps, sampling after each step.

    rho_counts[r, b] accumulates rods per bin of one wavelength; gap_counts[r, b, k] the left rods
    of pairs in exact contact (k = 0) and with gap r - sigma in [(k - 1) w, k w) (k >= 1), w = gap_width. Returns OK or a
    failure status (PASSED: rods overlapped; ALL_IN_CONTACT: no gap left on the ring).
    """
    replicas, n = positions.shape
    bins, gap_bins = gap_counts.shape[1], gap_counts.shape[2]
    status = np.zeros(replicas, dtype=np.int64)
    noise = math.sqrt(2.0 * diffusion / dt) / mu
    for r in numba.prange(replicas):
        x = positions[r]
        forces, v, prefix = np.empty(n), np.empty(n), np.empty(n + 1)
        members = np.empty(n, dtype=np.int64)
        stack = np.empty((2 * n + 2, 2), dtype=np.int64)
        for s in range(steps):
            key = stream_key(seed, first_step + s, BCD_STREAM)
            for i in range(n):
                z = normal_pair_at(key, r, i >> 1, 0)
                forces[i] = external(x[i], external_params) + drive + noise * (z[0] if i & 1 == 0 else z[1])
            if pair_on:
                for i in range(n):
                    gap = _gap(x, i, length)
                    if gap < sigma + pair_range:
                        f = pair_force(gap, pair_params)  # on the right rod, from the left one (B-32)
                        forces[(i + 1) % n] += f
                        forces[i] -= f
            status[r] = _step(x, forces, v, length, sigma, mu, dt, members, stack, prefix)
            if status[r] != OK:
                break
            for i in range(n):
                b = int((x[i] / wavelength - math.floor(x[i] / wavelength)) * bins) % bins
                rho_counts[r, b] += 1.0
                gap = _gap(x, i, length) - sigma
                k = 0 if gap <= CONTACT_TOLERANCE * sigma else 1 + int(gap / gap_width)
                if k < gap_bins:
                    gap_counts[r, b, k] += 1.0
    return status.max()
