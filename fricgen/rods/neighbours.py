"""What lies beyond the rods' hard core, as the pair weight W(r) of the transfer operator of
fricgen.rods.theory: nothing (hard rods), Baxter's sticky contact (its delta_eps representation (B-31) or the
limit eps = 0, a bond gamma delta(r - sigma)), or a pair potential V(r) of neighbours, W = exp(-V/kT)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import ConfigError


@dataclass(frozen=True)
class PairWeight:
    """The pair weight beyond the hard core: W(sigma + g) = 1 + excess(g) for 0 <= g < reach
    (excess(g) = exp[-beta V(sigma + g)] - 1, vectorised in g), plus Baxter's bond gamma delta(r - sigma)."""

    excess: Callable[[np.ndarray], np.ndarray] | None = None
    reach: float = 0.0
    bond: float = 0.0


HARD_CORE = PairWeight()


@dataclass(frozen=True)
class Neighbours:
    """The interaction of neighbouring rods beyond the hard core.

    None (hard rods), the sticky contact of stickiness ``gamma`` > 0 in the delta_eps representation
    (B-31/32; what BCD simulates) or, with ``eps=None``, Baxter's limit (B-29); or a continuous pair
    potential ``pair`` V(r) of neighbours on sigma <= r < sigma + ``pair_range`` (zero beyond).

    Attributes
    ----------
    gamma : float
        The stickiness [lambda]; 0: none.
    eps : float or None
        The range of the delta_eps representation [lambda]; None: Baxter's limit.
    p : float
        Its exponent [1].
    pair : callable or None
        V(r) [kT] of the gap's pair, for arrays of distances [lambda].
    pair_range : float or None
        V = 0 beyond sigma + pair_range [lambda].
    """

    gamma: float = 0.0
    eps: float | None = None
    p: float = 3.0
    pair: Callable[[np.ndarray], np.ndarray] | None = None
    pair_range: float | None = None

    def weight(self, sigma: float, wavelength: float, kT: float) -> PairWeight:
        """The pair weight W - 1 of these neighbours.

        Parameters
        ----------
        sigma : float
            The rod length [lambda].
        wavelength : float
            The field's period [lambda].
        kT : float
            The thermal energy [kT].

        Returns
        -------
        PairWeight
            The weight of the transfer operator.

        Raises
        ------
        ConfigError
            For inconsistent values.
        """
        gamma, eps, p, pair, pair_range = self.gamma, self.eps, self.p, self.pair, self.pair_range
        if gamma < 0 or (eps is not None and not 0 < eps < min(sigma, wavelength)) or p <= 1:
            raise ConfigError("rod_profile", "need gamma >= 0, 0 < eps < min(sigma, wavelength) and p > 1")
        if pair is not None:
            if gamma > 0:
                raise ConfigError("rod_profile", "give a pair potential or sticky rods (gamma > 0), not both")
            if pair_range is None or not 0 < pair_range < min(sigma, wavelength):
                raise ConfigError(
                    "rod_profile", f"the pair potential needs its range a (V = 0 beyond sigma + a) with 0 < a < sigma, got {pair_range}"
                )
            return PairWeight(lambda g: np.expm1(-np.asarray(pair(sigma + g), dtype=float) / kT), pair_range)
        if gamma == 0:
            return HARD_CORE
        if eps is None:
            return PairWeight(bond=gamma)
        return PairWeight(lambda g: gamma * (p + 1) / eps ** (p + 1) * (eps - g) ** p, eps)


HARD_RODS = Neighbours()
