"""The records that carry a Langevin state and its parameters into the compiled engine.

Named tuples of arrays and scalars with fixed Numba types, so that the compiled step functions
take a handful of arguments and are compiled once for every law (the kernels enter beside them as
first-class functions of the types in :mod:`fricgen.kernels`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import types

from ..kernels import CONTACT_KERNEL, FRICTION_KERNEL, SCALAR_KERNEL

_F, _I, _B = types.float64, types.int64, types.boolean
_V, _M, _L = types.Array(_F, 1, "C"), types.Array(_F, 2, "C"), types.Array(_I, 1, "C")


class Motion(NamedTuple):
    """The dynamic arrays, (N, 3) positions, velocities, angular velocities and (N, 4) quaternions."""

    position: np.ndarray
    velocity: np.ndarray
    omega: np.ndarray
    orientation: np.ndarray


class Bodies(NamedTuple):
    """Per-particle radius and inverse mass and moment of inertia (0 for immobile particles)."""

    radius: np.ndarray
    inv_mass: np.ndarray
    inv_inertia: np.ndarray


class Dynamics(NamedTuple):
    """Box lengths (Lz = 0 in 2-D), their inverses (0 beyond the dimension), bulk force, dimension and the parameters of one step: dt, kT,
    solvent gamma and gamma_rot, active force F0, noise seed, the calculus of the contact step (Calculus.index),
    friction and contact-noise switches, the pairwise (else explicit) contact step, neighbour-list skin and
    overlap limit (r / sigma_ik), and the number of threads numba runs this call on (set from Python:
    numba.get_num_threads inside compiled code would keep the engine out of Numba's disk cache)."""

    box: np.ndarray
    inv_box: np.ndarray
    bulk: np.ndarray
    dims: int
    dt: float
    kT: float
    gamma: float
    gamma_rot: float
    active: float
    seed: int
    scheme: int
    friction: bool
    noise: bool
    pairwise: bool
    skin: float
    overlap_limit: float
    threads: int


_NONE = np.zeros(0)


class Couplings(NamedTuple):
    """Parameter values of the pair potential and of the friction law, and whether the law has a
    weight w(r) (else w = 1); then the contact modes (docs/physics-modes.md): whether the law of
    ``law`` acts (``sliding``; else the sliding slot holds no law), whether a rolling and a spinning
    law act, their parameter values and whether each has a weight."""

    potential: np.ndarray
    law: np.ndarray
    has_weight: bool
    sliding: bool = True
    rolling: bool = False
    spinning: bool = False
    rolling_law: np.ndarray = _NONE
    spinning_law: np.ndarray = _NONE
    rolling_weight: bool = False
    spinning_weight: bool = False
    rolling_noise: bool = True
    spinning_noise: bool = True

    @property
    def modes_only_sliding(self) -> bool:
        """Whether only the sliding law acts (the engine's sliding-only path)."""
        return self.sliding and not (self.rolling or self.spinning)


class NeighborList(NamedTuple):
    """A Verlet list kept from one call of the engine to the next: CSR ``start``, ``neighbors`` and
    the ``reverse`` slots (fricgen.langevin.neighbors), the (N, 3) positions it was built at, and the
    box lengths and cutoff it was built for."""

    start: np.ndarray
    neighbors: np.ndarray
    reverse: np.ndarray
    reference: np.ndarray
    box: np.ndarray
    cutoff: float

    @classmethod
    def unbuilt(cls) -> NeighborList:
        """A list valid for no state: the engine builds one on its first step."""
        none = np.zeros(0, dtype=np.int64)
        return cls(none, none, none, np.zeros((0, 3)), np.zeros(3), 0.0)


MOTION = types.NamedUniTuple(_M, 4, Motion)
BODIES = types.NamedUniTuple(_V, 3, Bodies)
DYNAMICS = types.NamedTuple([_V, _V, _V, _I, _F, _F, _F, _F, _F, _I, _I, _B, _B, _B, _F, _F, _I], Dynamics)
COUPLINGS = types.NamedTuple([_V, _V, _B, _B, _B, _B, _V, _V, _B, _B, _B, _B], Couplings)
#: The compiled kernels of a run, (force, contact, slope, weight): the pair potential's force(r / sigma_ik, params), the law's
#: contact(u, w, r, mu, kT, params) -> (f/u, D) in its calculus, the friction slope df/du(u, w, r, params) and the weight
#: w(r / sigma_ik, params) (fricgen.kernels). A plain tuple: Numba converts compiled kernels to first-class functions in
#: a tuple, not in a named tuple.
KERNELS = types.Tuple([SCALAR_KERNEL, CONTACT_KERNEL, FRICTION_KERNEL, SCALAR_KERNEL])
#: The kernels of the rolling and spinning laws, (contact, slope, weight) of each as in KERNELS (those of
#: another law where a mode has none: Couplings says which act).
MODE_KERNELS = types.Tuple([CONTACT_KERNEL, FRICTION_KERNEL, SCALAR_KERNEL] * 2)
NEIGHBOR_LIST = types.NamedTuple([_L, _L, _L, _M, _V, _F], NeighborList)
