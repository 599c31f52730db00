"""Contact layers of BCD with an O(dt) error: elastic exchange ("reflect") and the Brownian-bridge push ("bridge").

BCD's own layer ("merge", fricgen.rods.bcd) stops colliding rods in contact: on the gap g = x_{i+1} - x_i - sigma
of a pair it is the projection g_1 = max(g_0 + Delta, 0), which leaves an atom of exact contacts and biases
everything by O(sqrt(dt)). The layers here move each rod by its trial displacement
d_i = mu F_i dt (the same forces and noise as BCD, B-11) and then restore the hard core:

* reflect: elastic collisions of equal rods. A pair whose gap ended negative is exchanged,
  x_i, x_{i+1} <- x_{i+1} - sigma, x_i + sigma, which maps g -> -g and keeps the pair's centre; exchanges are
  repeated around the ring until no gap is negative (a sort of y_i = x_i - i sigma, with the ring's seam).
  For rods without forces this is the exact law at any dt (reflection principle); with forces it is the
  symmetrised Euler scheme of reflected diffusions, weak order 1 (Bossy, Gobet & Talay 2004).
* bridge: the Skorokhod reflection of the gap's Brownian bridge. The gap of a pair is a Brownian motion of
  variance v = 4 D dt per step (D_rel = 2 D) and its drift; reflected at 0 it is g_t = Z_t - min(0, min Z)
  with Z the free path. Given g_0 = a and the free end g_0 + d_{i+1} - d_i = b, the bridge's minimum m has
  P(m <= z) = exp(-2 (a - z)(b - z) / v) (z <= min(a, b)) whatever the drift; sampled by inversion with
  E = -ln(1 - u), m = [a + b - sqrt((a - b)^2 + 2 v E)] / 2, the pair is pushed apart by p = max(0, -m),
  half on each rod (its centre stays), so g_1 = b + p. Exact for a pair with a constant relative drift;
  the pair touched during the step (a contact that the end points may miss) iff m < 0, with probability
  exp(-2 a b / v) = exp(-g_0 g_1 / (D_rel dt)) for b > 0. Only pairs with 2 a b / v < BRIDGE_CUT draw.
  Chains: a pair's free end moves with its neighbours' pushes, p_i = max(0, -m(a_i, b_i - (p_{i-1} +
  p_{i+1}) / 2)), solved by Gauss-Seidel sweeps (for E -> 0, BCD's projection of linear paths); not
  exact when three rods meet within a step; overlaps it leaves are removed by exchanges as in reflect.
  The contact density comes from the gaps' local time at contact (tally_local_time).

Derivation, tests and measurements: docs/physics-bcd-contact-layer.md.
"""

from __future__ import annotations

import math

import numba

from ..rng import fold_key, uniform

MERGE, REFLECT, BRIDGE = 0, 1, 2  # the positions of their names in fricgen.rods.config.CONTACT_LAYERS
BRIDGE_CUT = 20.0  # pairs with 2 a b / v above it touch with probability < exp(-20) = 2e-9: no draw
_BRIDGE_STREAM = 0x6272696467650001  # the bridge's uniforms: a sub-stream of the step's BCD key
_SWEEPS = 200  # at most this many solves per candidate in the chains' Gauss-Seidel (they need a few)
_ROUNDING = 8.0 * 2.0**-52  # relative rounding of an exchange, x_i + sigma - L + L != x_i + sigma


@numba.njit(inline="always", cache=True)
def _next(i, n):
    return i + 1 if i + 1 < n else 0


@numba.njit(cache=True)
def exchange(x, length, sigma, tolerance):
    """Exchange neighbours whose gap is below -tolerance until none is (elastic collisions of equal rods):
    x_i, x_{i+1} <- x_{i+1} - sigma, x_i + sigma (plus or minus L at the ring's seam, so the sum of x is kept).
    Every exchange removes one inversion of the periodic sequence y_i = x_i - i sigma, so this ends.
    Returns the number of exchanges."""
    n = x.size
    count = 0
    swapped = True
    while swapped:
        swapped = False
        for i in range(n):
            j = _next(i, n)
            offset = length if j == 0 else 0.0
            if j == 0 and not math.isfinite(length):
                continue  # an open line has no seam
            gap = x[j] + offset - x[i] - sigma
            if gap < -(tolerance + _ROUNDING * (abs(x[i]) + abs(x[j]) + offset)):
                left = x[i]
                x[i] = x[j] + offset - sigma
                x[j] = left + sigma - offset
                swapped = True
                count += 1
    return count


@numba.njit(inline="always", cache=True)
def bridge_minimum(a, b, variance, e):
    """The minimum of a Brownian bridge from a to b with increment variance ``variance``, for the
    exponential variate e = -ln(1 - u): m = [a + b - sqrt((a - b)^2 + 2 variance e)] / 2."""
    return 0.5 * (a + b - math.sqrt((a - b) ** 2 + 2.0 * variance * e))


@numba.njit(inline="always", cache=True)
def _push(a, b, variance, u):
    """max(0, -m) for the bridge from a to b with E = -ln(1 - u): zero unless the bridge touched, m < 0,
    i.e. b <= 0 or E > t = 2 a b / v. u <= t / (1 + t) implies E <= u / (1 - u) <= t, which spares the
    logarithm of most pairs that do not touch."""
    if b > 0.0:
        t = 2.0 * a * b / variance
        if u <= t / (1.0 + t):
            return 0.0
        e = -math.log1p(-u)
        if e <= t:
            return 0.0
    else:
        e = -math.log1p(-u)
    return -bridge_minimum(a, b, variance, e)


@numba.njit(inline="always", cache=True)
def _enqueue(neighbour, work, top):
    """Put the candidate of pair ``neighbour`` (if it is one and not queued) on the stack; returns the new top."""
    values, slots, stack = work[2], work[3], work[4]
    k = slots[neighbour]
    if k >= 0 and values[k, 4] == 0.0:
        values[k, 4] = 1.0
        stack[top] = k
        top += 1
    return top


@numba.njit(cache=True)
def _pushes(x, d, length, sigma, variance, bridge_key, work):
    """The bridge pushes p_i >= 0 of the pairs (i, i + 1) whose bridge may touch, solved for chains:
    p_i = max(0, -m_i), m_i the minimum of the bridge from a_i to b_i - (p_{i-1} + p_{i+1}) / 2 (the free end
    shifted by the neighbours' pushes, each pair with its own variate E_i). The candidates
    (2 a_i b_i < BRIDGE_CUT variance) get p_i from their own bridge; then a pair whose push changed by
    more than 1e-10 sqrt(v) puts its neighbouring candidates on a stack to be solved again (Gauss-Seidel
    on the chains only). work = (push, candidates, values: (a, b, u, x_i + a / 2, queued) per candidate,
    slots: the candidate of each pair or -1 (all -1 between steps), stack). Returns the number of candidates."""
    push, candidates, values, slots, stack = work
    n = x.size
    count = 0
    for i in range(n):
        push[i] = 0.0
        j = _next(i, n)
        if j == 0 and not math.isfinite(length):
            continue
        a = (x[j] + length if j == 0 else x[j]) - x[i] - sigma
        b = a + d[j] - d[i]
        if 2.0 * a * b < BRIDGE_CUT * variance:
            u = uniform(bridge_key, i)
            candidates[count], slots[i] = i, count
            values[count, 0], values[count, 1], values[count, 2], values[count, 3], values[count, 4] = a, b, u, x[i] + 0.5 * a, 0.0
            push[i] = _push(a, b, variance, u)
            count += 1
    top = 0
    for k in range(count):
        i = candidates[k]
        if push[i] > 0.0:
            top = _enqueue(i - 1 if i > 0 else n - 1, work, top)
            top = _enqueue(_next(i, n), work, top)
    for _ in range(_SWEEPS * count):  # chains: a pair's end moves with its neighbours' pushes
        if top == 0:
            break
        top -= 1
        k = stack[top]
        values[k, 4] = 0.0
        i = candidates[k]
        before, after = i - 1 if i > 0 else n - 1, _next(i, n)
        p = _push(values[k, 0], values[k, 1] - 0.5 * (push[before] + push[after]), variance, values[k, 2])
        if abs(p - push[i]) > 1e-10 * math.sqrt(variance):
            top = _enqueue(before, work, top)
            top = _enqueue(after, work, top)
        push[i] = p
    for k in range(count):
        slots[candidates[k]] = -1
    return count


@numba.njit(cache=True)
def propagate(x, d, length, sigma, variance, key, layer, work):
    """Move rods by their trial displacements d and restore the hard core by the layer REFLECT or BRIDGE
    (module docstring); variance = 4 D dt of a gap's increment, key = this step's key of the replica,
    work = (push, candidates, values, slots, stack): work arrays of n, n x 5 for values, slots all -1 (see
    _pushes); after the step,
    push[i] > 0 if and only if pair (i, i + 1) touched (bridge). Returns the number of bridge candidates."""
    n = x.size
    count = 0
    if layer == BRIDGE:
        push = work[0]
        count = _pushes(x, d, length, sigma, variance, fold_key(key, _BRIDGE_STREAM), work)
        for i in range(n):
            p = push[i]
            if p > 0.0:  # half on each rod of the pair
                d[i] -= 0.5 * p
                d[_next(i, n)] += 0.5 * p
    for i in range(n):
        x[i] += d[i]
    exchange(x, length, sigma, 1e-12 * sigma)
    return count


@numba.njit(cache=True)
def tally_local_time(work, count, variance, weight, wavelength, tally):
    """tally[bin of x_i + a / 2, 0] += weight p_i for each pushed pair of the step: the push is the gap's
    local time at contact (the Skorokhod term), whose rate is E[dL] = (v / (2 dt)) p(0) dt = 2 D rho_2(x, sigma+) dt
    per pair density, so that with weight 2 w / v the tally counts like a gap bin of width w at the
    contact density. x_i + a / 2 is where the
    left rod touches if the pair's centre stays (the centre moves independently of the gap, by O(dt)
    on average); the start x_i would shift rho_2(x) by O(sqrt(dt))."""
    push, candidates, values = work[0], work[1], work[2]
    bins = tally.shape[0]
    for k in range(count):
        p = push[candidates[k]]
        if p == 0.0:
            continue
        phase = values[k, 3] / wavelength
        b = int((phase - math.floor(phase)) * bins)
        tally[b if b < bins else 0, 0] += weight * p
