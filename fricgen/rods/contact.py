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
  p_{i+1}) / 2)), solved for each run of neighbouring pairs by Newton's method (for E -> 0, BCD's projection
  of linear paths); not exact when three rods meet within a step; overlaps it leaves are removed by
  exchanges as in reflect.
  The contact density comes from the gaps' local time at contact (tally_local_time).

Derivation, tests and measurements: docs/physics-bcd-contact-layer.md.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..rng import fold_key, uniform

MERGE, REFLECT, BRIDGE = 0, 1, 2  # the positions of their names in fricgen.rods.config.CONTACT_LAYERS
BRIDGE_CUT = 20.0  # pairs with 2 a b / v above it touch with probability < exp(-20) = 2e-9: no draw
_BRIDGE_STREAM = 0x6272696467650001  # the bridge's uniforms: a sub-stream of the step's BCD key
_TOLERANCE = 1e-12  # the chains' Newton solve stops at a residual below it times sqrt(v)
_ROUNDING = 8.0 * 2.0**-52  # relative rounding of an exchange, x_i + sigma - L + L != x_i + sigma


@numba.njit(inline="always", cache=True)
def centre_distance(x, i, length):
    """x_{i+1} - x_i around a ring of ``length`` (inf after the last rod of an open line, length = inf)."""
    j = i + 1
    return x[j] - x[i] if j < x.size else x[0] + length - x[i]


@numba.njit(inline="always", cache=True)
def right_of(i, n):
    """The rod to the right of rod i on a ring of n rods."""
    return i + 1 if i + 1 < n else 0


@numba.njit(inline="always", cache=True)
def left_of(i, n):
    """The rod to the left of rod i on a ring of n rods."""
    return i - 1 if i > 0 else n - 1


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
            j = right_of(i, n)
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
def _spread(a, b, variance, e):
    """R = sqrt((a - b)^2 + 2 variance e) of the bridge from a to b at the exponential variate e."""
    return math.sqrt((a - b) ** 2 + 2.0 * variance * e)


@numba.njit(inline="always", cache=True)
def bridge_minimum(a, b, variance, e):
    """The minimum of a Brownian bridge from a to b with increment variance ``variance``, for the
    exponential variate e = -ln(1 - u): m = [a + b - sqrt((a - b)^2 + 2 variance e)] / 2."""
    return 0.5 * (a + b - _spread(a, b, variance, e))


@numba.njit(inline="always", cache=True)
def _bridge(a, b, variance, u, e):
    """The push p = max(0, -m) of the bridge from a to b with E = -ln(1 - u), its slope dp/d(-b), which is
    (1 + (a - b) / R) / 2 in [0, 1] (R = _spread) where it pushes and 0 where it does not (p is convex in b),
    and E where it was needed. e: E if known, else negative. It pushes iff m < 0, i.e. b <= 0 or E > t = 2 a b / v;
    u <= t / (1 + t) implies E <= u / (1 - u) <= t, which spares the logarithm of most pairs that do not touch
    (e stays negative then)."""
    if b > 0.0:
        t = 2.0 * a * b / variance
        if e < 0.0:
            if u <= t / (1.0 + t):
                return 0.0, 0.0, e
            e = -math.log1p(-u)
        if e <= t:
            return 0.0, 0.0, e
    elif e < 0.0:
        e = -math.log1p(-u)
    spread = _spread(a, b, variance, e)
    return -bridge_minimum(a, b, variance, e), (0.5 + 0.5 * (a - b) / spread if spread > 0.0 else 0.5), e


@numba.njit(cache=True)
def bridge_work(n):
    """The bridge layer's work arrays for n rods: (push, candidates, values); values[k] holds (a, b, u,
    x_i + a / 2) of candidate k, three columns of the chains' Newton solve (_chain) and its E = -ln(1 - u) once
    computed (negative before), so that a chain's Newton iterations take no logarithm again."""
    return np.empty(n), np.empty(n, dtype=np.int64), np.empty((n, 8))


@numba.njit(inline="always", cache=True)
def _member(first, j, count):
    """The row of member j of the chain that starts at candidate ``first`` (candidates wrap at ``count``)."""
    k = first + j
    return k - count if k >= count else k


@numba.njit(cache=True)
def _chain(first, size, count, cyclic, variance, tolerance, work):
    """The pushes of one chain of ``size`` candidates of consecutive pairs (rows first, first + 1, ... modulo
    ``count`` of the values), whose neighbours outside the chain do not push; cyclic: the whole ring.
    They solve p_j = phi_j(s_j), s_j = (p_{j-1} + p_{j+1}) / 2, phi_j(s) = the push of the bridge from a_j to
    b_j - s (_bridge: increasing and convex in s, slope g_j in [0, 1]). Newton's method: p_j <- the solution of
    p_j - g_j (p_{j-1} + p_{j+1}) / 2 = phi_j - g_j s_j, tridiagonal (diagonally dominant; the last member
    borders it: p_j = y_j - z_j p_last, which closes a cyclic chain), until max_j |p_j - phi_j(s_j)| <= tolerance.
    As the map is convex and increasing, the iterates from the members' own pushes (p = phi(0), below the
    solution) increase monotonically to the solution, and the set of pushing members only grows.
    Columns 4-6 of the values hold the elimination's c'_j, y_j and z_j."""
    push, candidates, values = work
    n, last = push.size, size - 1
    for _ in range(size + 50):  # the pushing set grows at most size times, then Newton converges quadratically
        residual, c, y, z, h, r = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
        for j in range(size):
            k = _member(first, j, count)
            i = candidates[k]
            s = 0.5 * (push[left_of(i, n)] + push[right_of(i, n)])
            phi, g, values[k, 7] = _bridge(values[k, 0], values[k, 1] - s, variance, values[k, 2], values[k, 7])
            residual = max(residual, abs(phi - push[i]))
            h, r = -0.5 * g, phi - g * s
            if j < last:  # eliminate below the diagonal (Thomas), with the last member's column as a second right side
                lower = h if j > 0 else 0.0
                pivot = 1.0 - lower * c
                border = (h if j == last - 1 else 0.0) + (h if cyclic and j == 0 else 0.0)
                c = (h if j < last - 1 else 0.0) / pivot
                y, z = (r - lower * y) / pivot, (border - lower * z) / pivot
                values[k, 4], values[k, 5], values[k, 6] = c, y, z
        if residual <= tolerance:
            return
        for j in range(last - 2, -1, -1):
            k, above = _member(first, j, count), _member(first, j + 1, count)
            values[k, 5] -= values[k, 4] * values[above, 5]
            values[k, 6] -= values[k, 4] * values[above, 6]
        diagonal = 1.0  # the last row, p_last + h (p_{last-1} + [cyclic] p_0) = r, with p_j = y_j - z_j p_last
        for j in (last - 1, 0 if cyclic else -1):
            if j >= 0:
                k = _member(first, j, count)
                diagonal -= h * values[k, 6]
                r -= h * values[k, 5]
        p = r / diagonal
        push[candidates[_member(first, last, count)]] = p
        for j in range(last):
            k = _member(first, j, count)
            push[candidates[k]] = values[k, 5] - values[k, 6] * p


@numba.njit(cache=True)
def _pushes(x, d, length, sigma, variance, bridge_key, work):
    """The bridge pushes p_i >= 0 of the pairs (i, i + 1) whose bridge may touch, solved for chains:
    p_i = max(0, -m_i), m_i the minimum of the bridge from a_i to b_i - (p_{i-1} + p_{i+1}) / 2 (the free end
    shifted by the neighbours' pushes, each pair with its own variate E_i). The candidates
    (2 a_i b_i < BRIDGE_CUT variance) get p_i from their own bridge; each chain of candidates of consecutive
    pairs with a push is then solved by Newton's method (_chain). work = bridge_work(n). Returns the number
    of candidates."""
    push, candidates, values = work
    n = x.size
    count = 0
    for i in range(n):
        push[i] = 0.0
        j = right_of(i, n)
        if j == 0 and not math.isfinite(length):
            continue
        a = centre_distance(x, i, length) - sigma
        b = a + d[j] - d[i]
        if 2.0 * a * b < BRIDGE_CUT * variance:
            u = uniform(bridge_key, i)
            candidates[count] = i
            values[count, 0], values[count, 1], values[count, 2], values[count, 3] = a, b, u, x[i] + 0.5 * a
            push[i], _, values[count, 7] = _bridge(a, b, variance, u, -1.0)
            count += 1
    tolerance = _TOLERANCE * math.sqrt(variance)
    if count == n:  # every pair of the ring: one cyclic chain
        _chain(0, n, n, True, variance, tolerance, work)
        return count
    for k in range(count):  # the chains, from the candidates whose left neighbour is none (the seam's included)
        i = candidates[k]
        if candidates[left_of(k, count)] == left_of(i, n):
            continue
        size, pushed = 1, push[i] > 0.0
        while size < count and candidates[_member(k, size, count)] == right_of(candidates[_member(k, size - 1, count)], n):
            pushed = pushed or push[candidates[_member(k, size, count)]] > 0.0
            size += 1
        if pushed and size > 1:
            _chain(k, size, count, False, variance, tolerance, work)
    return count


@numba.njit(cache=True)
def propagate(x, d, length, sigma, variance, key, layer, work):
    """Move rods by their trial displacements d and restore the hard core by the layer REFLECT or BRIDGE
    (module docstring); variance = 4 D dt of a gap's increment, key = this step's key of the replica,
    work = bridge_work(n); after the step push = work[0] has push[i] > 0 if and only if pair (i, i + 1)
    touched (bridge). Returns the number of bridge candidates and the number of exchanges."""
    n = x.size
    count = 0
    if layer == BRIDGE:
        push = work[0]
        count = _pushes(x, d, length, sigma, variance, fold_key(key, _BRIDGE_STREAM), work)
        for i in range(n):
            p = push[i]
            if p > 0.0:  # half on each rod of the pair
                d[i] -= 0.5 * p
                d[right_of(i, n)] += 0.5 * p
    for i in range(n):
        x[i] += d[i]
    return count, exchange(x, length, sigma, 1e-12 * sigma)


@numba.njit(inline="always", cache=True)
def phase_bin(phase, bins):
    """The bin of a phase (position over the wavelength, any real) among ``bins`` bins of one wavelength."""
    b = int((phase - math.floor(phase)) * bins)
    return b if b < bins else 0


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
        tally[phase_bin(values[k, 3] / wavelength, bins), 0] += weight * p
