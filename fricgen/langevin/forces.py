"""Conservative pair forces F_i = sum_k -U'(r_ik) r_hat_ik, in one of two bit-identical ways.

- On one thread, each pair i < k once: F_ik is added to i and -F_ik to k (half the work).
- On several threads, each particle sums its own neighbour list, computing F_ik itself (each pair
  twice, no shared writes).

Both add the same numbers in the same order: a particle's contributions in the sorted order of its
neighbour list (partners k < i first, whose pairs the serial loop meets earlier), starting from 0;
and k computes -F_ik exactly, since the minimum image is exactly antisymmetric. So trajectories do
not depend on the thread count, and the total force is exactly zero.

Both also mark the pairs i < k that touch (within WCA_RANGE sigma_ik, not both immobile) in
``touching``, one flag per neighbour-list slot: the pairwise contact step reads them instead of
measuring every distance again (fricgen.langevin.contact_step.find_contacts).
"""

from __future__ import annotations

import numba
import numpy as np

from .pairs import pair_reach


@numba.njit(cache=True)
def _each_pair_once(pos, bodies, cell, pot_force, params, lists, force, touching):
    radius, inv_mass, start, neighbors = bodies.radius, bodies.inv_mass, lists[0], lists[1]
    box, inv_box, dims = cell
    force[:] = 0.0
    closest = np.inf
    for i in range(pos.shape[0]):
        for slot in range(start[i], start[i + 1]):
            k = neighbors[slot]
            touching[slot] = False
            if k < i or (inv_mass[i] == 0.0 and inv_mass[k] == 0.0):
                continue
            sigma = radius[i] + radius[k]
            dx, dy, dz, r = pair_reach(pos, i, k, sigma, box, inv_box, dims)
            if r == np.inf:
                continue
            magnitude = pot_force(r / sigma, params) / sigma  # -dU/dr, scaled to sigma_ik
            fx, fy, fz = -magnitude * (dx / r), -magnitude * (dy / r), -magnitude * (dz / r)  # on i from k
            touching[slot] = True
            closest = min(closest, r / sigma)
            force[i, 0] += fx
            force[i, 1] += fy
            force[i, 2] += fz
            force[k, 0] += -fx
            force[k, 1] += -fy
            force[k, 2] += -fz
    return closest


@numba.njit(parallel=True, cache=True)
def _each_particle(pos, bodies, cell, pot_force, params, lists, force, touching):
    radius, inv_mass, start, neighbors = bodies.radius, bodies.inv_mass, lists[0], lists[1]
    box, inv_box, dims = cell
    closest = np.full(pos.shape[0], np.inf)
    for i in numba.prange(pos.shape[0]):
        fx, fy, fz = 0.0, 0.0, 0.0
        for slot in range(start[i], start[i + 1]):
            k = neighbors[slot]
            touching[slot] = False
            if inv_mass[i] == 0.0 and inv_mass[k] == 0.0:
                continue
            sigma = radius[i] + radius[k]
            dx, dy, dz, r = pair_reach(pos, i, k, sigma, box, inv_box, dims)
            if r == np.inf:
                continue
            magnitude = pot_force(r / sigma, params) / sigma
            touching[slot] = k > i
            closest[i] = min(closest[i], r / sigma)
            fx += -magnitude * (dx / r)
            fy += -magnitude * (dy / r)
            fz += -magnitude * (dz / r)
        force[i, 0], force[i, 1], force[i, 2] = fx, fy, fz
    return closest.min() if pos.shape[0] else np.inf


@numba.njit(cache=True)
def conservative_forces(pos, bodies, dyn, couplings, pot_force, lists, force, touching):
    """force[i] = conservative force on i (pairs within the potential's range WCA_RANGE sigma_ik) and
    touching[slot] whether the slot's pair (i < k) is one of them; returns the smallest r / sigma_ik of
    those pairs. ``lists`` = (start, neighbors, reverse)."""
    if dyn.threads == 1:
        # the box as numbers: arrays passed to the inlined _pair_reach within a serial loop would cost
        # two atomic reference-count operations per pair (a parallel loop's body is spared them)
        cell = ((dyn.box[0], dyn.box[1], dyn.box[2]), (dyn.inv_box[0], dyn.inv_box[1], dyn.inv_box[2]), dyn.dims)
        return _each_pair_once(pos, bodies, cell, pot_force, couplings.potential, lists, force, touching)
    return _each_particle(pos, bodies, (dyn.box, dyn.inv_box, dyn.dims), pot_force, couplings.potential, lists, force, touching)
