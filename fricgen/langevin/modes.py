"""The explicit contact kick of the rolling and spinning modes (docs/physics-modes.md).

For a pair i < k within reach (WCA range) and each mode m whose law acts (rolling, spinning), with
x = v_m . (e1 + i e2) the mode's velocity in an orthonormal basis of its space
(fricgen.langevin.contact_step.rolling_mode), u = |x|, mu_m = R_eff^2 (1/I_i + 1/I_k),
R_eff = R_i R_k / (R_i + R_k):

- friction, a generalized force -C_m^T (f/u) v_m: the torque on i
  tau_i = -R_eff n x F_roll (rolling, 3-D), -R_eff F_roll z (2-D), -R_eff F_spin n (spinning);
- noise (where the mode's noise acts: Couplings.rolling_noise, spinning_noise), the impulse
  sqrt(D) sqrt(2 kT dt) C_m^T xi with xi standard normal in the mode's space (one normal per
  component, keyed on (seed, step, ROLLING or SPINNING, i, k)): the same torques
  with F replaced by -sqrt(D) sqrt(2 kT dt) xi;

and tau_k = -tau_i (a couple: no force). ``mode_slots`` writes them into one slot per pair of the
neighbour list and ``gather_modes`` adds them to the particles' friction and noise torques in the sorted
order of each list (as fricgen.langevin.pairs.gather), so results do not depend on the thread count.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..rng import pair_key, ziggurat_normal
from .contact_step import ROLL, SPIN, rolling_mode
from .pairs import cross, pair_reach

#: Per pair i < k, in the slot of (i, k): friction torque on i (0:3), noise torque impulse on i (3:6).
MODE_FIELDS = 6


@numba.njit(inline="always", cache=True)
def _torque(jp, jq, e1, e2, n, reff, mode, dims):
    """R_eff times C_m^T's spin block of i applied to the mode-space vector J = jp e1 + jq e2 (tangents
    e1, e2 and normal n as 3-tuples): R_eff n x J (rolling, 3-D), R_eff J (2-D rolling, e1 = z; spinning, e1 = n)."""
    jx, jy, jz = jp * e1[0] + jq * e2[0], jp * e1[1] + jq * e2[1], jp * e1[2] + jq * e2[2]
    if mode == ROLL and dims == 3:
        jx, jy, jz = cross(n[0], n[1], n[2], jx, jy, jz)
    return reff * jx, reff * jy, reff * jz


@numba.njit(parallel=True, cache=True)
def mode_slots(coordinates, bodies, dyn, couplings, modes, lists, keys, noise_on, slots):
    """Fill the mode slots of every pair i < k within range (module docstring). ``coordinates`` = (x, v, omega),
    ``modes`` = records.MODE_KERNELS, ``keys`` the step's (ROLLING, SPINNING) stream keys."""
    pos, omega = coordinates[0], coordinates[2]
    radius, inv_inertia, inv_mass = bodies.radius, bodies.inv_inertia, bodies.inv_mass
    start, neighbors = lists[0], lists[1]
    box, inv_box, dims, kT = dyn.box, dyn.inv_box, dyn.dims, dyn.kT
    roll_params, spin_params = couplings.rolling_law, couplings.spinning_law
    roll_contact, roll_weight, spin_contact, spin_weight = modes[0], modes[2], modes[3], modes[5]
    noise_scale = math.sqrt(2.0 * kT * dyn.dt)
    for i in numba.prange(pos.shape[0]):
        for slot in range(start[i], start[i + 1]):
            k = neighbors[slot]
            if k < i:
                continue
            for j in range(MODE_FIELDS):
                slots[slot, j] = 0.0
            if inv_mass[i] == 0.0 and inv_mass[k] == 0.0:
                continue
            sigma = radius[i] + radius[k]
            dx, dy, dz, r = pair_reach(pos, i, k, sigma, box, inv_box, dims)
            if r == np.inf:
                continue
            nx, ny, nz = dx / r, dy / r, dz / r
            reff = radius[i] * radius[k] / sigma
            mu = reff * reff * (inv_inertia[i] + inv_inertia[k])
            for mode in (ROLL, SPIN):
                if not (couplings.rolling if mode == ROLL else couplings.spinning):
                    continue
                params, key = (roll_params, keys[0]) if mode == ROLL else (spin_params, keys[1])
                contact, weight = (roll_contact, roll_weight) if mode == ROLL else (spin_contact, spin_weight)
                weighted = couplings.rolling_weight if mode == ROLL else couplings.spinning_weight
                w = weight(r / sigma, params) / sigma if weighted else 1.0
                x, ax, ay, az, bx, by, bz, comps = rolling_mode(omega, i, k, reff, nx, ny, nz, dims, mode)
                ratio, amplitude = contact(math.sqrt(x.real * x.real + x.imag * x.imag), w, r, mu, kT, params)
                tx, ty, tz = _torque(-ratio * x.real, -ratio * x.imag, (ax, ay, az), (bx, by, bz), (nx, ny, nz), reff, mode, dims)
                slots[slot, 0] += tx
                slots[slot, 1] += ty
                slots[slot, 2] += tz
                if noise_on and (couplings.rolling_noise if mode == ROLL else couplings.spinning_noise):
                    kick, draws = math.sqrt(amplitude) * noise_scale, pair_key(key, i, k)
                    xi1, xi2 = ziggurat_normal(draws, 0), ziggurat_normal(draws, 1) if comps == 2 else 0.0
                    tx, ty, tz = _torque(kick * xi1, kick * xi2, (ax, ay, az), (bx, by, bz), (nx, ny, nz), reff, mode, dims)
                    slots[slot, 3] += tx
                    slots[slot, 4] += ty
                    slots[slot, 5] += tz


@numba.njit(parallel=True, cache=True)
def gather_modes(size, lists, slots, terms):
    """terms[2, i] += the mode friction torques on i and terms[4, i] += the noise torque impulses, over i's pairs
    in the sorted order of its list (-tau_i for the partner k > i's slot read by k)."""
    start, neighbors, reverse = lists
    for i in numba.prange(size):
        for slot in range(start[i], start[i + 1]):
            source, sign = (slot, 1.0) if neighbors[slot] > i else (reverse[slot], -1.0)
            for a in range(3):
                terms[2, i, a] += sign * slots[source, a]
                terms[4, i, a] += sign * slots[source, 3 + a]
