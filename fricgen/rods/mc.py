"""Metropolis Monte Carlo of rods on a ring: equilibrium starting configurations for BCD.

BCD relaxes the occupation of the wells only by hopping over the barriers (about one hop per rod
and 20 time units at U0 = 6), so a start out of equilibrium leaves a bias for hundreds of time units.
This sampler has the same Boltzmann weight as the exact theory (fricgen.rods.theory), exp[-beta (sum_i
U(x_i) + sum_i V_int(x_{i+1} - x_i))] with the hard core, and moves each rod in turn to a uniform point
of its free interval (x_{i-1} + sigma, x_{i+1} - sigma): a symmetric proposal accepted with
probability min(1, exp(-beta Delta E)). Random numbers are counter-based (seed, sweep, replica, rod),
so a sweep count and seed give a bit-identical start. For Baxter's sticky rods (eps = 0, Ring.bond = gamma)
the proposal is drawn from the reference measure dx + gamma delta(x - left - sigma) + gamma delta(right -
sigma - x), whose weight relative to the target is still the field's Boltzmann factor: bonds form and
break exactly at contact.

The sweeps start from rods with Gamma-distributed gaps (``free_rods``), not from a lattice. The ring's
long-wavelength density modes, with |sum_j exp(2 pi i m x_j / L)|^2 of mean L chi in equilibrium
(chi = d rho_bar / d beta mu_ch; m << L / lambda), relax in these sweeps only diffusively, in about
13 000 sweeps for m = 1 (N = 140, L = 100, U0 = 6, rho_bar sigma = 0.7), and never within a BCD run. A
lattice has none of these fluctuations: after 2000 sweeps modes 1 and 2 held 0.27 and 0.68 of their
equilibrium, and the contact density of that dense ring stayed 0.35 % below the exact canonical one in
BCD at every dt (docs/physics-bcd-contact-layer.md). Gaps of shape k give chi_0 / k, chi_0 =
rho_bar (1 - rho_bar sigma)^2 that of free hard rods (k = 1); RodSimulation sets k = chi_0 / chi from the
exact theory (1.005 in that ring; 4.3 at rho_bar sigma = 0.5, one rod per well).
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types

from ..kernels import SCALAR_KERNEL
from ..rng import INITIAL, MONTE_CARLO, fold_key, stream_key, uniform, ziggurat_normal
from .records import RING

_F, _I = types.float64, types.int64


_FREE_START = 1  # the step of the INITIAL stream that draws the free-rod start


@numba.njit(cache=True)
def _gamma(shape, key):
    """A Gamma(shape) variate from the counter-based stream ``key`` (Marsaglia and Tsang 2000; for
    shape < 1, Gamma(shape + 1) U^(1 / shape))."""
    boost = shape < 1.0
    a = shape + 1.0 if boost else shape
    d = a - 1.0 / 3.0
    c = 1.0 / math.sqrt(9.0 * d)
    j = 0
    while True:
        x = ziggurat_normal(key, j)
        v = (1.0 + c * x) ** 3
        u = uniform(key, j + 1)
        j += 2
        if v > 0.0 and math.log1p(-u) < 0.5 * x * x + d - d * v + d * math.log(v):
            value = d * v
            break
    return value * (1.0 - uniform(key, j)) ** (1.0 / shape) if boost else value


@numba.njit(cache=True)
def free_rods(n, length, sigma, replicas, seed, shape=1.0):
    """Positions (replicas x n, ordered, unwrapped) of n rods on a ring of length L with the gaps
    g_i = (L - n sigma) G_i / sum G, G_i ~ Gamma(shape), after rod 0 at a uniform point of [0, L);
    x_{i+1} = x_i + sigma + g_i. For shape = 1 (a flat Dirichlet law) the exact equilibrium of free hard
    rods; their long density waves have chi_0 / shape, chi_0 = rho_bar (1 - rho_bar sigma)^2 (a renewal
    process: S(0) = Var(spacing) / <spacing>^2)."""
    out = np.empty((replicas, n))
    free = length - n * sigma
    gaps = np.empty(n)
    for r in range(replicas):
        key = fold_key(stream_key(seed, _FREE_START, INITIAL), r)
        for i in range(n):
            gaps[i] = -math.log1p(-uniform(key, i + 1)) if shape == 1.0 else _gamma(shape, fold_key(key, i + 1))
        scale = free / gaps.sum()
        out[r, 0] = length * uniform(key, 0)
        for i in range(1, n):
            out[r, i] = out[r, i - 1] + sigma + scale * gaps[i - 1]
    return out


@numba.njit(inline="always", cache=True)
def _energy(field, x, left, right, ring, pair):
    """The field energy ``field`` = U(x) plus the pair energies with the rods at ``left`` and ``right``
    (positions, unwrapped)."""
    energy = field
    if ring.pair_on:
        reach = ring.sigma + ring.pair_range
        if x - left < reach:
            energy += pair(x - left, ring.pair_params)
        if right - x < reach:
            energy += pair(right - x, ring.pair_params)
    return energy


@numba.njit(_F(types.Array(_F, 2, "C"), RING, SCALAR_KERNEL, SCALAR_KERNEL, _I, _I, _I), parallel=True, cache=True)
def metropolis_sweeps(positions, ring, external, pair, sweeps, first_sweep, seed):
    """``sweeps`` sweeps over all rods of every replica (rows of ``positions``, ordered, unwrapped;
    rod 0 follows rod N-1 at x_{N-1} - L). ``external(x)`` and ``pair(r)`` are energies, the pair one
    used for centre distances r < sigma + pair_range; U(x_i) is kept per rod between its moves (one
    field evaluation per move). Returns the acceptance ratio."""
    length, sigma, kT = ring.length, ring.sigma, ring.kT
    replicas, n = positions.shape
    accepted = np.zeros(replicas)
    for r in numba.prange(replicas):
        x = positions[r]
        field = np.empty(n)
        for i in range(n):
            field[i] = external(x[i], ring.field_params)
        for s in range(sweeps):
            key = fold_key(stream_key(seed, first_sweep + s, MONTE_CARLO), r)
            for i in range(n):
                left = x[i - 1] if i > 0 else x[n - 1] - length
                right = x[i + 1] if i + 1 < n else x[0] + length
                free = right - left - 2.0 * sigma
                if free <= 0.0:
                    continue
                trial = left + sigma + free * uniform(key, 2 * i)
                if ring.bond > 0.0:  # Baxter: the reference measure dx + gamma (delta at each contact)
                    share = (free + 2.0 * ring.bond) * uniform(key, 2 * i)
                    trial = left + sigma + share - 2.0 * ring.bond
                    if share < 2.0 * ring.bond:
                        trial = left + sigma if share < ring.bond else right - sigma
                trial_field = external(trial, ring.field_params)
                old = _energy(field[i], x[i], left, right, ring, pair)
                new = _energy(trial_field, trial, left, right, ring, pair)
                if new <= old or uniform(key, 2 * i + 1) < math.exp((old - new) / kT):
                    x[i], field[i] = trial, trial_field
                    accepted[r] += 1.0
    return accepted.sum() / max(1, replicas * n * sweeps)
