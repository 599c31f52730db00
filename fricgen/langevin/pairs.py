"""Pair forces of frictional spheres, each pair computed once into its slot of the neighbour list.

For a pair i < k within reach (WCA range 2^(1/6) sigma_ik): the conservative force on i, the
friction force F_f = (f/u) u_perp with u_perp of (F-4), its torque arm r_hat x F_f (tau_i = R_i
r_hat x F_f, tau_k = R_k r_hat x F_f; F-5..8), and the noise impulse sqrt(D) sqrt(2 kT dt) P z of
one random tangential force (z keyed on (seed, step, i, k); along t = z x r_hat in 2-D), see
docs/physics.md#one-tangential-random-force and #the-two-dimensional-reduction. ``gather`` sums the
slots per particle in the sorted order of its list, with -F for the partner: exact antisymmetry,
and results that do not depend on the thread count.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..rng import normal_pair_at
from .neighbors import separation

WCA_RANGE = 2.0 ** (1.0 / 6.0)

#: Per pair i < k, in the slot of (i, k): conservative force on i (0:3), friction force on i (3:6),
#: r_hat x friction force (6:9), noise impulse on i (9:12), r_hat x noise impulse (12:15).
PAIR_FIELDS = 15
#: terms[j, i, :] of a pass: force, friction, friction torque, noise impulse, noise torque impulse.
TERMS = 5


@numba.njit(inline="always", cache=True)
def cross(a0, a1, a2, b0, b1, b2):
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@numba.njit(inline="always", cache=True)
def pair_reach(pos, i, k, sigma, box, inv_box, dims):
    """(dx, dy, dz, r) of the pair (i, k), r = |r_k - r_i| (minimum image), or r = inf beyond the
    potential's range WCA_RANGE sigma (sigma = sigma_ik = R_i + R_k)."""
    dx, dy, dz = separation(pos, i, k, box, inv_box, dims)
    r2 = dx * dx + dy * dy + dz * dz
    reach = WCA_RANGE * sigma
    return dx, dy, dz, (math.sqrt(r2) if r2 < reach * reach else np.inf)


@numba.njit(parallel=True, cache=True)
def pair_slots(coordinates, bodies, dyn, couplings, pot_force, contact, weight, lists, switches, slots):
    """Fill the slots of every pair i < k within range; returns min r / sigma_ik.

    ``coordinates`` = (x, v, omega) at which the forces are evaluated, kernels as in fricgen.kernels
    (potential force, contact, weight), ``lists`` = (start, neighbors, reverse) of the neighbour
    list, ``switches`` = (noise key, friction, noise, conservative force) of this pass."""
    pos, vel, omega = coordinates
    radius, inv_mass, inv_inertia = bodies
    start, neighbors = lists[0], lists[1]
    noise_key, friction_on, noise_on, conservative = switches
    box, inv_box, dims, kT = dyn.box, dyn.inv_box, dyn.dims, dyn.kT
    # bound here: taken from their tuple within the loop, each kernel call would cost two atomic reference counts
    potential, law = couplings.potential, couplings.law
    size = pos.shape[0]
    closest = np.full(size, np.inf)
    noise_scale = math.sqrt(2.0 * kT * dyn.dt)
    for i in numba.prange(size):
        ri = radius[i]
        for slot in range(start[i], start[i + 1]):
            k = neighbors[slot]
            if k < i:
                continue
            for j in range(PAIR_FIELDS):
                slots[slot, j] = 0.0
            if inv_mass[i] == 0.0 and inv_mass[k] == 0.0:
                continue  # two immobile (wall) particles: no effect, and mu_ik = 0
            rk = radius[k]
            sigma = ri + rk
            dx, dy, dz, r = pair_reach(pos, i, k, sigma, box, inv_box, dims)
            if r == np.inf:
                continue
            closest[i] = min(closest[i], r / sigma)
            nx, ny, nz = dx / r, dy / r, dz / r
            if conservative:
                magnitude = pot_force(r / sigma, potential) / sigma  # -dU/dr, scaled to sigma_ik
                slots[slot, 0], slots[slot, 1], slots[slot, 2] = -magnitude * nx, -magnitude * ny, -magnitude * nz
            if not friction_on:
                continue
            # u_perp = P (v_k - v_i) - (R_i w_i + R_k w_k) x n   (F-4)
            wx = ri * omega[i, 0] + rk * omega[k, 0]
            wy = ri * omega[i, 1] + rk * omega[k, 1]
            wz = ri * omega[i, 2] + rk * omega[k, 2]
            rvx, rvy, rvz = vel[k, 0] - vel[i, 0], vel[k, 1] - vel[i, 1], vel[k, 2] - vel[i, 2]
            along = rvx * nx + rvy * ny + rvz * nz
            cx, cy, cz = cross(wx, wy, wz, nx, ny, nz)
            ux, uy, uz = rvx - along * nx - cx, rvy - along * ny - cy, rvz - along * nz - cz
            u = math.sqrt(ux * ux + uy * uy + uz * uz)
            w = weight(r / sigma, law) / sigma if couplings.has_weight else 1.0
            mu = inv_mass[i] + inv_mass[k] + ri * ri * inv_inertia[i] + rk * rk * inv_inertia[k]
            ratio, amplitude = contact(u, w, r, mu, kT, law)
            fx, fy, fz = ratio * ux, ratio * uy, ratio * uz
            slots[slot, 3], slots[slot, 4], slots[slot, 5] = fx, fy, fz
            slots[slot, 6], slots[slot, 7], slots[slot, 8] = cross(nx, ny, nz, fx, fy, fz)
            if noise_on:
                kick = math.sqrt(amplitude) * noise_scale  # sqrt(D) sqrt(2 kT dt)
                if dims == 3:  # P z: one random tangential force
                    z0, z1 = normal_pair_at(noise_key, i, k, 0)
                    z2 = normal_pair_at(noise_key, i, k, 1)[0]
                    zn = z0 * nx + z1 * ny + z2 * nz
                    jx, jy, jz = kick * (z0 - zn * nx), kick * (z1 - zn * ny), kick * (z2 - zn * nz)
                else:  # along t = z x n
                    z0 = normal_pair_at(noise_key, i, k, 0)[0]
                    jx, jy, jz = -kick * z0 * ny, kick * z0 * nx, 0.0
                slots[slot, 9], slots[slot, 10], slots[slot, 11] = jx, jy, jz
                slots[slot, 12], slots[slot, 13], slots[slot, 14] = cross(nx, ny, nz, jx, jy, jz)
    return closest.min() if size else np.inf


@numba.njit(parallel=True, cache=True)
def gather(radius, lists, slots, terms):
    """terms[:, i] = sums over i's pairs in the sorted order of its list (-F and R_k torques for k > i)."""
    start, neighbors, reverse = lists
    for i in numba.prange(radius.size):
        for j in range(TERMS):
            for a in range(3):
                terms[j, i, a] = 0.0
        for slot in range(start[i], start[i + 1]):
            source, sign = (slot, 1.0) if neighbors[slot] > i else (reverse[slot], -1.0)
            for j in range(TERMS):
                scale = radius[i] if j == 2 or j == 4 else sign  # torques: R_i r_hat x F for both partners
                for a in range(3):
                    terms[j, i, a] += scale * slots[source, 3 * j + a]
