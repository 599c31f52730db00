"""Baxter's sticky rods as a boundary condition of each gap (eps = 0, B-29): attach, stay, detach.

In Baxter's limit the pair weight is W(r) = Theta(r - sigma) + gamma delta(r - sigma): a gap g = r - sigma
has the measure dg + gamma delta_0(dg), so a bonded pair (g = 0) holds gamma times the pair density at
contact, rho_2(x, x + sigma+) (gamma in lambda). Its dynamics is sticky Brownian motion, whose sojourn at 0
no step can resolve (Bou-Rabee & Holmes-Cerfon, SIAM Rev. 62, 164, 2020, simulate it by a random walk
on a grid; this is the same balance on the step's own scale). One step of dt for the gap of two
clusters of m and k rods (variance v = 2 D dt (1/m + 1/k), relative drift c dt, alpha = c dt / sqrt v):

* free: the bridge of fricgen.rods.contact from a = g_0 to the free end b; if its minimum is below 0
  (P = exp(-2 a b / v) for b > 0) the pair touched and ends the step bonded, the two clusters merged at
  contact with their centre sum(x) kept (BCD's inelastic merge, B-17);
* bonded: detaches with probability q = sqrt(v) Q(alpha) / gamma per step (a geometric, nearly exponential
  sojourn of mean dt / q), ending at the gap g = sqrt(v) y with y drawn from the emission law
  h(y) / Q(alpha), h(y) = exp(2 alpha y) Phi(-y - alpha) + Phi(alpha - y), Q = int_0^inf h; the pieces
  keep their centre.

For a constant drift the stationary gap law is p0 [exp(c g / D_rel) dg + gamma delta_0(dg)]. After the free
step, which kills the paths that touch, the free law lacks the density p0 h(b / sqrt v) at b, in all
p0 sqrt(v) Q(alpha): this is the emission that keeps the free law, and q is the balance B q = p0 sqrt(v) Q
with B = gamma p0. So the scheme is exact for a pair with a constant drift at any dt (q <= 1), and
Q(alpha) = alpha Phi(alpha) + phi(alpha) + erf(alpha / sqrt 2) / (2 alpha), 2 phi(0) at alpha = 0. Without
alpha (the drift-free law, Q(0)) the bonded mass is gamma Q(alpha) / Q(0) of exact: an O(sqrt(dt)) bias.

Derivation and measurements: docs/physics-bcd-sticky-boundary.md.
"""

from __future__ import annotations

import math

import numba

from ..rng import fold_key, uniform
from .contact import BRIDGE_CUT, centre_distance, left_of, right_of

OK, ALL_IN_CONTACT, LONG_STEP = 0, 2, 3  # step statuses, shared with fricgen.rods.bcd
_STICKY_STREAM = 0x737469636B790001  # the boundary's uniforms: a sub-stream of the step's BCD key
_SQRT2 = math.sqrt(2.0)
_PHI0 = 1.0 / math.sqrt(2.0 * math.pi)
_SMALL_ALPHA = 1e-6  # below it, the emission's distribution to first order in alpha (error alpha^2)


@numba.njit(inline="always", cache=True)
def _cdf(s):
    return 0.5 * math.erfc(-s / _SQRT2)


@numba.njit(inline="always", cache=True)
def _pdf(s):
    return _PHI0 * math.exp(-0.5 * s * s)


@numba.njit(inline="always", cache=True)
def _g(s):
    """G(s) = int_-inf^s Phi = s Phi(s) + phi(s)."""
    return s * _cdf(s) + _pdf(s)


@numba.njit(cache=True)
def emission_norm(alpha):
    """Q(alpha) = int_0^inf h(y) dy = G(alpha) + erf(alpha / sqrt 2) / (2 alpha): the touching mass per step of a
    pair at a stationary contact density 1, in units of sqrt(v)."""
    ratio = _PHI0 if alpha == 0.0 else math.erf(alpha / _SQRT2) / (2.0 * alpha)
    return _g(alpha) + ratio


@numba.njit(cache=True)
def emission_cdf(y, alpha):
    """(H(y), h(y)): int_0^y h and h(y) for the emission density h(y) = exp(2 alpha y) Phi(-y - alpha) + Phi(alpha - y)."""
    density = math.exp(2.0 * alpha * y) * _cdf(-y - alpha) + _cdf(alpha - y)
    second = _g(alpha) - _g(alpha - y)
    if abs(alpha) < _SMALL_ALPHA:  # int_0^y exp(2 alpha t) Phi(-t - alpha) dt to first order in alpha
        first = _PHI0 - _pdf(y) + y * _cdf(-y) + alpha * (y * y * _cdf(-y) - y * _pdf(y))
    else:  # by parts: [exp(2 alpha t) Phi(-t - alpha) + Phi(t - alpha)]_0^y / (2 alpha)
        reached = 0.5 * (math.erf((y - alpha) / _SQRT2) + math.erf(alpha / _SQRT2))  # Phi(y - alpha) - Phi(-alpha)
        first = (math.exp(2.0 * alpha * y) * _cdf(-y - alpha) - _cdf(-alpha) + reached) / (2.0 * alpha)
    return first + second, density


@numba.njit(cache=True)
def emitted_gap(alpha, u):
    """The emission variate y >= 0 (in units of sqrt(v)) with H(y) = u Q(alpha), by Newton's method
    safeguarded by bisection, to 1e-12."""
    target = u * emission_norm(alpha)
    low, high = 0.0, 1.0
    while emission_cdf(high, alpha)[0] < target:
        low, high = high, 2.0 * high
    y = 0.5 * (low + high)
    for _ in range(100):
        value, density = emission_cdf(y, alpha)
        if value < target:
            low = y
        else:
            high = y
        step = (value - target) / density if density > 0.0 else math.inf
        guess = y - step
        y = guess if low < guess < high else 0.5 * (low + high)
        if abs(step) < 1e-12 or high - low < 1e-12:
            break
    return y


@numba.njit(cache=True)
def detach_probability(alpha, spread, gamma):
    """q = sqrt(v) Q(alpha) / gamma: the probability per step that a bond of gap spread sqrt(v) = ``spread``
    and drift alpha sqrt(v) breaks (above 1: the step is too long for the stickiness)."""
    return spread * emission_norm(alpha) / gamma


@numba.njit(cache=True)
def _first_free(link, n):
    """A rod whose left pair is not linked (the start of a cluster), or -1 if all are."""
    for s in range(n):
        if not link[left_of(s, n)]:
            return s
    return -1


@numba.njit(cache=True)
def _repack(x, y, link, length, sigma):
    """x = y, except that each run of linked rods is put at contact with its sum of positions kept."""
    n = x.size
    s = _first_free(link, n)
    k = 0
    while k < n:
        size, total = 1, y[(s + k) % n] + (length if s + k >= n else 0.0)
        while k + size < n and link[(s + k + size - 1) % n]:
            total += y[(s + k + size) % n] + (length if s + k + size >= n else 0.0)
            size += 1
        start = total / size - 0.5 * (size - 1) * sigma
        for j in range(size):
            t = s + k + j
            x[t % n] = y[t % n] if size == 1 else start + j * sigma - (length if t >= n else 0.0)
        k += size


@numba.njit(cache=True)
def sticky_step(x, d, drift, length, sigma, variance, gamma, key, tolerance, work):
    """One step of the sticky boundary (module docstring) for rods at x (ordered, unwrapped) with trial
    displacements d (drift plus noise) and drifts ``drift`` = mu F dt; variance = 2 D dt of one rod's
    displacement, pairs with gap <= tolerance are bonded. work = (y, cluster, size, link, prefix): float, int,
    int, bool, float arrays of n + 1. Returns OK, ALL_IN_CONTACT or LONG_STEP (a detach probability above 1)."""
    y, cluster, size, link, prefix = work
    n = x.size
    sticky_key = fold_key(key, _STICKY_STREAM)
    for i in range(n):
        link[i] = centre_distance(x, i, length) - sigma <= tolerance
    s = _first_free(link, n)
    if s < 0:
        return ALL_IN_CONTACT
    k, c = 0, 0
    while k < n:  # the clusters at the start: rigid, each bond may break
        m = 1
        while link[(s + k + m - 1) % n]:
            m += 1
        mean, prefix[0] = 0.0, 0.0
        for j in range(m):
            i = (s + k + j) % n
            mean += d[i] / m
            prefix[j + 1] = prefix[j] + drift[i]
            cluster[i] = c
        size[c] = m
        emitted, shift = 0.0, 0.0
        for j in range(m):  # y = x + mean + (gaps emitted before j) - their mean over the cluster
            i = (s + k + j) % n
            if j > 0:
                left, right = j, m - j
                pair = (s + k + j - 1) % n
                spread = math.sqrt(variance * (1.0 / left + 1.0 / right))
                alpha = ((prefix[m] - prefix[j]) / right - prefix[j] / left) / spread
                q = detach_probability(alpha, spread, gamma)
                if q > 1.0:
                    return LONG_STEP
                if uniform(sticky_key, 2 * pair) < q:
                    link[pair] = False
                    emitted += spread * emitted_gap(alpha, uniform(sticky_key, 2 * pair + 1))
            y[i] = x[i] + mean + emitted
            shift += emitted / m
        for j in range(m):
            y[(s + k + j) % n] -= shift
        k += m
        c += 1
    for i in range(n):  # free pairs between clusters: bonded if their bridge touched
        j = right_of(i, n)
        if link[i] or cluster[i] == cluster[j] or (j == 0 and not math.isfinite(length)):
            continue
        a, b = centre_distance(x, i, length) - sigma, centre_distance(y, i, length) - sigma
        pair_variance = variance * (1.0 / size[cluster[i]] + 1.0 / size[cluster[j]])
        if b <= 0.0:
            link[i] = True
        elif 2.0 * a * b < BRIDGE_CUT * pair_variance:
            link[i] = -math.log1p(-uniform(sticky_key, 2 * i)) > 2.0 * a * b / pair_variance
    for _ in range(n):  # merge the touched clusters; a merge that overlaps a neighbour joins it too
        if _first_free(link, n) < 0:
            return ALL_IN_CONTACT
        _repack(x, y, link, length, sigma)
        overlapped = False
        for i in range(n):
            if not link[i] and centre_distance(x, i, length) - sigma < 0.0:
                link[i] = overlapped = True
        if not overlapped:
            break
        y[:] = x
    return OK
