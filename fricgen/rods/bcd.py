"""Brownian cluster dynamics (BCD) of hard rods on a ring (Antonov et al. 2022, B-1..19).

Overdamped rods of length sigma, dx_i/dt = mu F_i + sqrt(2D) xi_i (B-1, B-27), on a periodic line
of length L, or on an open line for L = inf (the gap after the last rod is infinite). Per step dt:

1. trial forces F_i = f(x_i) + F_drive + sum_j f_int(x_i, x_j) + sqrt(2D/dt)/mu N_i (B-11, B-28),
   f from the external potential's force_field kernel (one call per step for all rods),
   with N_i a standard normal keyed on (seed, step, replica, i) (rng.ziggurat_normal: counter-based,
   so a run is bit-identical in any chunking and on any number of threads);
2. cluster analysis: each run of rods in contact is split recursively at the cut with the largest
   positive difference of mean forces (right minus left); pieces that cannot split move with
   mu times their mean force (B-4, B-5, B-12);
3. event-driven propagation: the earliest collision inside the step merges the two clusters
   perfectly inelastically, velocity (m v_left + n v_right)/(m + n) (B-13..18), until t + dt (B-19).
   Collisions wait in a heap and positions are extrapolated from t = 0, so an event costs
   O(cluster size + log N), not O(N).

Continuous pair forces act between neighbours (f_int of range sigma + eps < 2 sigma, e.g. the
sticky force B-32). Positions are kept unwrapped and ordered (x_0 < ... < x_{N-1} < x_0 + L): rods
never pass each other. Sampling after each step adds the rods of every period to histograms over
one wavelength (B-24, B-25) and histograms the gaps r - sigma of neighbours at the left rod's bin:
exact contacts (left by merging) apart, positive gaps in bins of width w (B-26; see fricgen.rods.simulation for the
estimate of the contact density); the same pass checks that no two rods overlap.

Steps 2 and 3 are BCD's own contact layer ("merge", O(sqrt(dt))); the layers "reflect" and "bridge"
(fricgen.rods.contact, O(dt)) replace them by trial displacements mu F_i dt and a restored hard core,
selected by Stepping.layer. Baxter's sticky rods in the limit eps = 0 (Ring.bond = gamma > 0) step by the
sticky boundary of fricgen.rods.sticky instead: bonded pairs (gaps <= CONTACT_TOLERANCE) are counted in
gap bin 0.

The field's drift (Stepping.drift): EULER evaluates the forces at x; LM (Leimkuhler-Matthews, with the bridge
layer, hard rods) at the midpoint of the step's noise, q = x + delta with delta = sqrt(2 D dt) N / 2, where the
hard core is not restored (each rod's law at q is its law at x convolved with a Gaussian, the LM correction of the
one-body profile), then moves x by mu F(q) dt + 2 delta with the bridge; the profile is sampled at q, the gaps and
the contacts at x (second order for the profile away from contacts). METROPOLIS (bridge layer, hard rods): Euler's
step, then accepted or rejected as a whole by the Metropolis test of fricgen.rods.adjusted, which makes the field's
Boltzmann distribution the chain's exact equilibrium at any dt (one test per replica per step).

The physics: docs/physics.md#brownian-cluster-dynamics, docs/physics-bcd-contact-layer.md,
docs/physics-bcd-field-drift.md.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types

from ..kernels import FIELD_KERNEL, SCALAR_KERNEL
from ..rng import BCD, fold_key, stream_key, uniform, ziggurat_normal
from .adjusted import log_proposal
from .contact import BRIDGE, MERGE, bridge_work, centre_distance, left_of, phase_bin, propagate, right_of, tally_local_time
from .records import COUNTS, REJECTED, RING, STEPPING
from .sticky import ALL_IN_CONTACT, OK, sticky_step

EULER, LM, METROPOLIS = 0, 1, 2  # the field's drift schemes, the positions of their names in fricgen.rods.config.DRIFT_SCHEMES
_ACCEPT_STREAM = 0x6163636570740001  # the Metropolis test's uniform: a sub-stream of the step's BCD key
CONTACT_TOLERANCE = 1e-12  # relative to sigma: gaps below it are contacts (with the sticky boundary: bonds)
PASSED = 1  # rods overlapped (the other statuses: fricgen.rods.sticky)


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


@numba.njit(inline="always", cache=True)
def _push(heap_t, heap_i, size, t, i):
    """Insert event (t, i) into the binary min-heap heap_t[0:size]; returns the new size."""
    k = size
    while k > 0:
        parent = (k - 1) >> 1
        if heap_t[parent] <= t:
            break
        heap_t[k], heap_i[k] = heap_t[parent], heap_i[parent]
        k = parent
    heap_t[k], heap_i[k] = t, i
    return size + 1


@numba.njit(inline="always", cache=True)
def _pop(heap_t, heap_i, size):
    """Remove the earliest event of the heap; returns (t, i, new size)."""
    t, i = heap_t[0], heap_i[0]
    size -= 1
    last_t, last_i = heap_t[size], heap_i[size]
    k = 0
    while True:
        child = 2 * k + 1
        if child >= size:
            break
        if child + 1 < size and heap_t[child + 1] < heap_t[child]:
            child += 1
        if heap_t[child] >= last_t:
            break
        heap_t[k], heap_i[k] = heap_t[child], heap_i[child]
        k = child
    heap_t[k], heap_i[k] = last_t, last_i
    return t, i, size


@numba.njit(cache=True)
def _rebuild(heap_t, heap_i, when):
    """A heap of the valid events only (time when[i] >= 0 for pair i); returns its size."""
    size = 0
    for i in range(when.size):
        if when[i] >= 0.0:
            size = _push(heap_t, heap_i, size, when[i], i)
    return size


@numba.njit(cache=True)
def _schedule(x, v, i, now, length, sigma, dt, events, size):
    """If rods i and i + 1 approach and touch before dt, at t = (x_{i+1} - x_i - sigma) / (v_i - v_{i+1})
    (B-14; x: positions extrapolated to t = 0, x_i(t) = x_i + v_i t), push the event at
    when[i] = max(t, now); else when[i] = -1. Returns the heap size; events = (heap_t, heap_i, when)."""
    heap_t, heap_i, when = events
    closing = v[i] - v[right_of(i, x.size)]
    gap = centre_distance(x, i, length) - sigma
    when[i] = -1.0
    if closing > 0.0 and gap < closing * dt:
        if size == heap_t.size:  # full of superseded events
            size = _rebuild(heap_t, heap_i, when)
        when[i] = max(gap / closing, now)
        size = _push(heap_t, heap_i, size, when[i], i)
    return size


@numba.njit(cache=True)
def _step(x, forces, v, length, sigma, mu, dt, clusters, events):
    """Cluster analysis, then event-driven propagation over dt; returns OK or ALL_IN_CONTACT.

    Work arrays: clusters = (members, stack, prefix), events = (heap_t, heap_i, when).
    During the step x holds the positions extrapolated to t = 0 (rod i is at x_i + v_i t), so that a
    merge moves only the rods of its two clusters. Collisions wait in a heap; when[i] is the valid
    time of pair i (-1: none), entries that disagree with it are superseded."""
    members, stack, prefix = clusters
    heap_t, heap_i, when = events
    n = x.size
    tolerance = CONTACT_TOLERANCE * sigma
    start = -1
    for i in range(n):
        if centre_distance(x, i, length) - sigma > tolerance:
            start = i
            break
    if start < 0:
        return ALL_IN_CONTACT
    count, i = 0, start
    for _ in range(n):
        i = right_of(i, n)
        members[count] = i
        count += 1
        if centre_distance(x, i, length) - sigma > tolerance:  # i ends the cluster members[0:count]
            if count == 1:
                v[i] = mu * forces[i]
            else:
                _cluster_velocities(forces, members, count, mu, v, stack, prefix)
            count = 0
    size = 0
    for i in range(n):
        when[i] = -1.0
        if centre_distance(x, i, length) - sigma < (v[i] - v[right_of(i, n)]) * dt:  # necessary; rarely true
            size = _schedule(x, v, i, 0.0, length, sigma, dt, events, size)
    while size > 0:
        now, left, size = _pop(heap_t, heap_i, size)
        if when[left] != now:  # superseded
            continue
        # merge the cluster ending at `left` with the one starting at `right` (B-17)
        right = right_of(left, n)
        a, b, m, k = left, right, 1, 1
        while m + k < n:
            c = left_of(a, n)
            if v[c] != v[left] or centre_distance(x, c, length) - sigma > tolerance:
                break
            a, m = c, m + 1
        while m + k < n:
            c = right_of(b, n)
            if v[c] != v[right] or centre_distance(x, b, length) - sigma > tolerance:
                break
            b, k = c, k + 1
        merged = (m * v[left] + k * v[right]) / (m + k)
        c = a
        for _ in range(m + k):
            x[c] += (v[c] - merged) * now  # the same x_c(now), now moving with `merged`
            v[c] = merged
            c = right_of(c, n)
        when[left] = -1.0
        if m + k < n:
            size = _schedule(x, v, left_of(a, n), now, length, sigma, dt, events, size)
            size = _schedule(x, v, b, now, length, sigma, dt, events, size)
    for i in range(n):
        x[i] += v[i] * dt
    return OK


@numba.njit(cache=True)
def _sample(x, at, ring, gap_width, rho_counts, gap_counts):
    """Add the rods at ``at`` to rho_counts[bin] and the gaps of x to gap_counts[bin, k] at the left rod's bin
    (see advance_rods); returns PASSED if two rods of x overlap, else OK."""
    length, sigma = ring.length, ring.sigma
    n, bins, gap_bins = x.size, rho_counts.size, gap_counts.shape[1]
    per_wavelength, per_gap, contact = 1.0 / ring.wavelength, 1.0 / gap_width, CONTACT_TOLERANCE * sigma
    status = OK
    for i in range(n):
        rho_counts[phase_bin(at[i] * per_wavelength, bins)] += 1.0
        gap = centre_distance(x, i, length) - sigma
        if gap < -1e-9 * sigma:
            status = PASSED
        k = 0 if gap <= contact else 1 + int(min(gap * per_gap, gap_bins))  # inf: after the last rod of an open line
        if k < gap_bins:
            gap_counts[phase_bin(x[i] * per_wavelength, bins), k] += 1.0
    return status


@numba.njit(cache=True)
def _metropolis(x, start, pushes, held, energy, ring, dt, external, field_energy, accept_key):
    """The Metropolis test of fricgen.rods.adjusted for the bridge step from ``start`` to x with ``pushes``: True if
    accepted. held[0] holds the field's forces at ``start`` and energy[0] its energy U(start); on acceptance both
    become those at x (held[1] and energy[1] are work)."""
    n, params = x.size, ring.field_params
    external(x, params, held[1])
    energy[1] = 0.0
    for i in range(n):
        energy[1] += field_energy(x[i], params)
    args = (ring.mu, dt, ring.diffusion, ring.length, ring.sigma)
    forward = log_proposal(start, x, pushes, held[0], *args)
    backward = log_proposal(x, start, pushes, held[1], *args)
    log_ratio = (energy[0] - energy[1]) / ring.kT + backward - forward
    accepted = log_ratio >= 0.0 or uniform(accept_key, 0) < math.exp(log_ratio)
    if accepted:
        held[0, :] = held[1]
        energy[0] = energy[1]
    return accepted


_SIGNATURE = types.int64(types.Array(types.float64, 2, "C"), RING, STEPPING, FIELD_KERNEL, SCALAR_KERNEL, SCALAR_KERNEL, COUNTS, REJECTED)


@numba.njit(_SIGNATURE, parallel=True, cache=True)
def advance_rods(positions, ring, stepping, external, field_energy, pair_force, counts, rejected):
    """Advance every replica (row of positions) by ``stepping.steps`` BCD steps, sampling after each.

    ``external`` is the field's force_field(xs, params, out), ``pair_force`` the neighbour force
    f(r, params) on the right rod. counts = (rho_counts, gap_counts): rho_counts[r, b] accumulates
    rods per bin of one wavelength; gap_counts[r, b, k] the left rods of pairs in exact contact
    (k = 0; with the bridge layer instead their local time at contact, fricgen.rods.contact.tally_local_time;
    with the sticky boundary the bonded pairs)
    and with gap r - sigma in [(k - 1) w, k w) (k >= 1), w = gap_width; with stepping.drift == LM the forces act
    and the profile is sampled at the noise's midpoint (the gaps at the step's end); with METROPOLIS ``field_energy``
    U(x, params) enters the test, rejected[r] counts the replica's rejected steps and no local time is tallied (the
    contact density comes from the gaps). Returns OK or a
    failure status (PASSED: rods overlapped; ALL_IN_CONTACT: no gap left on the ring; LONG_STEP: a bond's
    detach probability above 1).
    """
    rho_counts, gap_counts = counts
    length, sigma, mu, dt = ring.length, ring.sigma, ring.mu, stepping.dt
    replicas, n = positions.shape
    status = np.zeros(replicas, dtype=np.int64)
    noise = math.sqrt(2.0 * ring.diffusion / dt) / mu
    variance = 4.0 * ring.diffusion * dt  # of a gap's increment over a step
    for r in numba.prange(replicas):
        x = positions[r]
        forces, v, prefix, when = np.empty(n), np.empty(n), np.empty(n + 1), np.empty(n)
        members = np.empty(n, dtype=np.int64)
        stack = np.empty((2 * n + 2, 2), dtype=np.int64)
        heap_t, heap_i = np.empty(3 * n), np.empty(3 * n, dtype=np.int64)  # n, then 2 per merge (< n merges)
        d, drift, bridge = np.empty(n), np.empty(n), bridge_work(n)  # contact.propagate
        sticky = (np.empty(n), np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64), np.empty(n, dtype=np.bool_), np.empty(n + 1))
        normals, midpoint = np.empty(n), np.empty(n)
        start, held, energy = np.empty(n), np.empty((2, n)), np.zeros(2)  # METROPOLIS: the field at x is kept
        for s in range(stepping.steps):
            key = fold_key(stream_key(stepping.seed, stepping.first_step + s, BCD), r)
            for i in range(n):
                normals[i] = ziggurat_normal(key, i)
            at = x  # where the forces act and the profile is sampled
            if stepping.drift == LM:  # q = x + delta, the midpoint of the step's noise; rods may overlap there
                for i in range(n):
                    midpoint[i] = x[i] + 0.5 * noise * mu * dt * normals[i]
                at = midpoint
            if stepping.drift != METROPOLIS:
                external(at, ring.field_params, forces)
            else:  # the field's forces and energy at x are held from the step before
                if s == 0:
                    external(x, ring.field_params, held[0])
                    for i in range(n):
                        energy[0] += field_energy(x[i], ring.field_params)
                start[:] = x
                forces[:] = held[0]
            for i in range(n):
                if ring.bond > 0.0:
                    drift[i] = mu * dt * (forces[i] + ring.drive)  # the sticky boundary's drift
                forces[i] += ring.drive + noise * normals[i]
            if ring.pair_on:
                for i in range(n):
                    gap = centre_distance(at, i, length)
                    if gap < sigma + ring.pair_range:
                        f = pair_force(gap, ring.pair_params)  # on the right rod, from the left one (B-32)
                        forces[right_of(i, n)] += f
                        forces[i] -= f
            if ring.bond > 0.0:  # Baxter's limit: the sticky boundary (fricgen.rods.sticky)
                for i in range(n):
                    d[i] = mu * forces[i] * dt
                tolerance = CONTACT_TOLERANCE * sigma
                status[r] = sticky_step(x, d, drift, length, sigma, 2.0 * ring.diffusion * dt, ring.bond, key, tolerance, sticky)
            elif stepping.layer == MERGE:
                status[r] = _step(x, forces, v, length, sigma, mu, dt, (members, stack, prefix), (heap_t, heap_i, when))
            else:  # trial displacements mu F dt, then the hard core by exchanges (fricgen.rods.contact)
                for i in range(n):
                    d[i] = mu * forces[i] * dt
                count, exchanges = propagate(x, d, length, sigma, variance, key, stepping.layer, bridge)
                if stepping.layer == BRIDGE and stepping.drift != METROPOLIS:  # the contact density from the local time
                    tally_local_time(bridge, count, variance, 2.0 * stepping.gap_width / variance, ring.wavelength, gap_counts[r])
                if stepping.drift == METROPOLIS:
                    accept_key = fold_key(key, _ACCEPT_STREAM)  # a step with exchanges is not the layer's: rejected
                    if exchanges > 0 or not _metropolis(x, start, bridge[0], held, energy, ring, dt, external, field_energy, accept_key):
                        x[:] = start
                        rejected[r] += 1
            if status[r] == OK:
                status[r] = _sample(x, at, ring, stepping.gap_width, rho_counts[r], gap_counts[r])
            if status[r] != OK:
                break
    return status.max()
