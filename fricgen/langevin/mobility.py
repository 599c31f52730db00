"""The contact mobilities of a system's kinds of particle, for which a simulation tabulates an integral-form D.

mu = 1/m_i + 1/m_k + R_i^2/I_i + R_k^2/I_k (sliding, an inverse mass) and mu_m = R_eff^2 (1/I_i + 1/I_k)
(rolling, spinning), bit for bit as the compiled contact step computes them. Light: no engine is compiled to read them
(``fricgen noise`` uses them).
"""

from __future__ import annotations

import numpy as np

from .system import Particles

#: Most contact mobilities that a simulation tabulates an integral-form D for (one table each).
TABLES = 4


def pair_mobilities(particles: Particles, limit: int = TABLES) -> np.ndarray:
    """The contact mobilities mu = 1/m_i + 1/m_k + R_i^2/I_i + R_k^2/I_k of pairs (i, k) of the most common kinds of
    particle (mass, radius, inertia), bit for bit as fricgen.langevin.contact_step.find_contacts computes them, at most
    ``limit``: the law module's tabulate_<c> builds a noise table for each (fricgen.derive.backends.tables); a pair of
    other kinds is evaluated by quadrature."""

    def sliding(i, k):
        (mi, ri, ii), (mk, rk, ik) = i, k
        return float(mi + mk + ri**2 * ii + rk**2 * ik)

    return _of_kinds((particles.inv_mass, particles.radius, particles.inv_inertia), sliding, limit)


def mode_mobilities(particles: Particles, mode: str, limit: int = TABLES) -> np.ndarray:
    """As :func:`pair_mobilities`, for the rolling and spinning modes: mu_m = R_eff^2 (1/I_i + 1/I_k),
    R_eff = R_i R_k / (R_i + R_k), bit for bit as fricgen.langevin.contact_step.update_rolling computes it."""
    if mode == "sliding":
        return pair_mobilities(particles, limit)

    def turning(i, k):
        (ri, ii), (rk, ik) = i, k
        reff = float(ri * rk / (ri + rk))
        return reff * reff * float(ii + ik)

    return _of_kinds((particles.radius, particles.inv_inertia), turning, limit)


def _of_kinds(columns, mobility, limit: int) -> np.ndarray:
    """The distinct positive ``mobility(i, k)`` of the pairs of kinds of particle (the distinct rows of ``columns``), the
    most common kinds first, each pair in both orders (the sums differ in their last bit), at most ``limit``."""
    kinds, counts = np.unique(np.stack(columns, axis=1), axis=0, return_counts=True)
    kinds = kinds[np.argsort(-counts, kind="stable")]
    found: list[float] = []
    for top in range(len(kinds)):
        for i in range(top + 1):
            for a, b in ((kinds[i], kinds[top]), (kinds[top], kinds[i])):
                mu = mobility(a, b)
                if mu > 0.0 and mu not in found and len(found) < limit:
                    found.append(mu)
    return np.array(found)
