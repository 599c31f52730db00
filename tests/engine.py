"""The engine's compiled passes as tests call them from Python (tests/lammps, the reference-count test): with the
kernels as first-class functions.

Called from Python with a law's kernels (Numba dispatchers), contact_step, pair_slots and the others compile
once per law and kernel (a calculus's contact is one), and that code is not cached: 20-70 s each. These
wrappers take the kernels as the first-class function types that integrator.advance passes them with
(fricgen.kernels), so each pass compiles once for every law, and the engine's own cache holds its code. They
are not cached themselves: Numba would check such a cache against this file only, not against the engine's
sources (fricgen.compiled.clear_stale_caches).
"""

from __future__ import annotations

import numba
from numba import types

from fricgen.kernels import CONTACT_KERNEL, FRICTION_KERNEL, SCALAR_KERNEL
from fricgen.langevin import contact_step as steps
from fricgen.langevin import forces, modes, pairs
from fricgen.langevin.records import BODIES, COUPLINGS, DYNAMICS, MODE_KERNELS, MOTION

_ROWS = types.Array(types.float64, 2, "C")
_LISTS = types.UniTuple(types.Array(types.int64, 1, "C"), 3)  # (start, neighbors, reverse)
_MASK = types.Array(types.boolean, 1, "C")
_COORDINATES = types.UniTuple(_ROWS, 3)  # (x, v, omega)
_LAW = types.Tuple([CONTACT_KERNEL, FRICTION_KERNEL, SCALAR_KERNEL])  # (contact, slope, weight)
_KEY = types.uint64


@numba.njit((_ROWS, BODIES, DYNAMICS, COUPLINGS, SCALAR_KERNEL, _LISTS, _ROWS, _MASK))
def conservative_forces(pos, bodies, dyn, couplings, pot_force, lists, force, touching):
    """forces.conservative_forces."""
    return forces.conservative_forces(pos, bodies, dyn, couplings, pot_force, lists, force, touching)


@numba.njit((_ROWS, BODIES, DYNAMICS, COUPLINGS, SCALAR_KERNEL, _LISTS, _MASK))
def find_contacts(pos, bodies, dyn, couplings, weight, lists, touching):
    """contact_step.find_contacts."""
    return steps.find_contacts(pos, bodies, dyn, couplings, weight, lists, touching)


@numba.njit((MOTION, BODIES, DYNAMICS, COUPLINGS, _LAW, _LISTS, _MASK, _KEY))
def contact_step(motion, bodies, dyn, couplings, law, lists, touching, key):
    """contact_step.contact_step."""
    return steps.contact_step(motion, bodies, dyn, couplings, law, lists, touching, key)


@numba.njit((MOTION, BODIES, DYNAMICS, COUPLINGS, _LAW, MODE_KERNELS, _LISTS, _MASK, types.UniTuple(_KEY, 3)))
def contact_step_modes(motion, bodies, dyn, couplings, law, kernels, lists, touching, keys):
    """contact_step.contact_step_modes."""
    return steps.contact_step_modes(motion, bodies, dyn, couplings, law, kernels, lists, touching, keys)


_SWITCHES = types.Tuple([_KEY, types.boolean, types.boolean, types.boolean])  # (noise key, friction, noise, conservative force)


@numba.njit((_COORDINATES, BODIES, DYNAMICS, COUPLINGS, SCALAR_KERNEL, CONTACT_KERNEL, SCALAR_KERNEL, _LISTS, _SWITCHES, _ROWS))
def pair_slots(coordinates, bodies, dyn, couplings, pot_force, contact, weight, lists, switches, out):
    """pairs.pair_slots."""
    return pairs.pair_slots(coordinates, bodies, dyn, couplings, pot_force, contact, weight, lists, switches, out)


@numba.njit((_COORDINATES, BODIES, DYNAMICS, COUPLINGS, MODE_KERNELS, _LISTS, types.UniTuple(_KEY, 2), types.boolean, _ROWS))
def mode_slots(coordinates, bodies, dyn, couplings, kernels, lists, keys, noise, out):
    """modes.mode_slots."""
    return modes.mode_slots(coordinates, bodies, dyn, couplings, kernels, lists, keys, noise, out)
