"""The Metropolis test of a bridge step: the exact equilibrium of hard rods in a field at any time step.

A step of the bridge layer (fricgen.rods.contact) proposes end positions y and pair pushes p_j >= 0 from x:
free ends Z_i = x_i + b_i dt + sqrt(2 D dt) N_i (drift b_i = mu F(x_i)), then per candidate pair j the push
p_j = max(0, -m_j), m_j the minimum of the bridge from the gap a_j of x to c_j = b_j - s_j (b_j: the gap of Z,
s_j = (p_{j-1} + p_{j+1}) / 2) drawn with its exponential variate E_j, so that y_i = Z_i + (p_{i-1} - p_i) / 2.
The map from (Z, E) to (y, p) is invertible: Z = y - P(p), c_j = g_j(y) - p_j, and for a pushed pair
E_j = 2 (a_j + p_j)(c_j + p_j) / v (v = 4 D dt). So the proposal's density is known in closed form,

    q(x -> y, p) = prod_i phi(Z_i - x_i - b_i dt; 2 D dt) * prod_{pushed j} e^{-E_j} * |det dE/dp|
                   * prod_{candidates j not pushed} (1 - e^{-2 a_j c_j / v}),

with dE/dp tridiagonal over each chain of consecutive pushed pairs (dE_j/dp_j = 2 (a_j + c_j + 2 p_j) / v,
dE_j/dp_{j+-1} = -(a_j + p_j) / v). The step from y back to x with the same pushes has the density of the same
form. Accepting (y, p) with probability min(1, e^{-beta U(y)} q(y -> x, p) / (e^{-beta U(x)} q(x -> y, p)))
makes the chain of configurations reversible with respect to e^{-beta U} on the hard rods' space, at any dt,
chains of three or more rods included (where the bridge is not the exact reflected motion, its density is
still the proposal's). Pairs that are no candidates (2 a b >= BRIDGE_CUT v) are never pushed (density 1); a
step that the reverse could not make (a pushed pair no candidate from y, an unpushed one overlapping) or that
needed exchanges is rejected. Free rods (b = 0) are always accepted: for them the layer is exact.

Derivation and measurements: docs/physics-bcd-field-drift.md.
"""

from __future__ import annotations

import math

import numba

from .contact import BRIDGE_CUT, centre_distance


@numba.njit(cache=True)
def log_proposal(start, end, push, forces, mu, dt, diffusion, length, sigma):
    """log q(start -> end, push) of the bridge layer's step (module docstring), up to factors that the step back
    with the same pushes shares (the Gaussians' normalisation, 2 / v per pushed pair, and 1 - e^{-2 a c / v} of an
    unpushed pair that is a candidate both ways: the step back swaps a and c); -inf where the layer cannot make
    the step. push[j] of pair (j, j + 1); forces[i] = F_i at ``start`` [kT / length], mu the mobility."""
    n = start.size
    variance = 4.0 * diffusion * dt
    ring = math.isfinite(length)
    log_q = 0.0
    for i in range(n):
        before = push[i - 1] if i > 0 else (push[n - 1] if ring else 0.0)
        free = end[i] - 0.5 * (before - push[i]) - start[i] - mu * forces[i] * dt
        log_q -= free * free / variance  # the rod's Gaussian, variance 2 D dt = v / 2
    pairs = n if ring else n - 1
    first = -1  # a pair whose left neighbour is not pushed: chains start after it
    for j in range(pairs):
        if push[j] == 0.0:
            first = j
            break
    if first < 0:
        return -math.inf  # every pair pushed (a ring in one chain): not taken
    determinant, previous, left = 1.0, 1.0, 0.0  # of the current chain; left = a + p of its last pair (0: none)
    for step in range(1, pairs + 1):
        j = first + step
        j = j - pairs if j >= pairs else j
        a, p = centre_distance(start, j, length) - sigma, push[j]
        c = centre_distance(end, j, length) - sigma - p
        before = push[j - 1] if j > 0 else (push[pairs - 1] if ring else 0.0)
        after = push[j + 1] if j + 1 < pairs else (push[0] if ring else 0.0)
        candidate = 2.0 * a * (c + 0.5 * (before + after)) < BRIDGE_CUT * variance  # the layer's test on the free gap
        if p > 0.0:
            if not candidate:
                return -math.inf
            log_q -= 2.0 * (a + p) * (c + p) / variance  # E_j
            diagonal = a + c + 2.0 * p  # dE_j/dp_j, scaled by v / 2 as the off-diagonal terms
            determinant, previous = diagonal * determinant - 0.25 * (a + p) * left * previous, determinant
            left = a + p
            continue
        if left > 0.0:  # the chain before this pair ended: its Jacobian
            log_q += math.log(determinant)
            determinant, previous, left = 1.0, 1.0, 0.0
        if c <= 0.0:
            return -math.inf  # overlapping without a push
        if candidate and not 2.0 * c * (a + 0.5 * (before + after)) < BRIDGE_CUT * variance:  # a candidate this way only
            log_q += math.log(-math.expm1(-2.0 * a * c / variance))
    return log_q
