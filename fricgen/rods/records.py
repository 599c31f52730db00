"""The records that carry a ring of rods and its parameters into the compiled BCD and Monte Carlo."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import types

_F, _I, _B = types.float64, types.int64, types.boolean
_V, _M, _T = types.Array(_F, 1, "C"), types.Array(_F, 2, "C"), types.Array(_F, 3, "C")


class Ring(NamedTuple):
    """The model of one ring: length L (inf: an open line), rod length sigma, mobility mu, thermal
    energy kT, diffusion D = mu kT, constant drive, the field's period lambda and parameters, the
    neighbour interaction's parameters, its range beyond contact and whether it is on, and Baxter's
    stickiness gamma of the sticky boundary (eps = 0, fricgen.rods.sticky; 0: none)."""

    length: float
    sigma: float
    mu: float
    kT: float
    diffusion: float
    drive: float
    wavelength: float
    field_params: np.ndarray
    pair_params: np.ndarray
    pair_range: float
    pair_on: bool
    bond: float = 0.0


class Stepping(NamedTuple):
    """Time step, number of steps, the first step's index (the noise counter), noise seed, the
    width of the gap histogram's bins, the contact layer (fricgen.rods.contact: MERGE, REFLECT, BRIDGE) and
    the field's drift scheme (fricgen.rods.bcd: EULER, or LM, the Leimkuhler-Matthews midpoint)."""

    dt: float
    steps: int
    first_step: int
    seed: int
    gap_width: float
    layer: int = 0
    drift: int = 0


RING = types.NamedTuple([_F, _F, _F, _F, _F, _F, _F, _V, _V, _F, _B, _F], Ring)
STEPPING = types.NamedTuple([_F, _I, _I, _I, _F, _I, _I], Stepping)
COUNTS = types.Tuple([_M, _T])
REJECTED = types.Array(_I, 1, "C")  # per replica: the steps that the Metropolis test rejected
