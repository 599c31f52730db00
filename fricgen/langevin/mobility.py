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
    kinds, counts = np.unique(np.stack([particles.inv_mass, particles.radius, particles.inv_inertia], axis=1), axis=0, return_counts=True)
    kinds = kinds[np.argsort(-counts, kind="stable")]
    found: list[float] = []
    for top in range(len(kinds)):
        for i, k in ((j, top) for j in range(top + 1)):
            for (mi, ri, ii), (mk, rk, ik) in ((kinds[i], kinds[k]), (kinds[k], kinds[i])):  # (i, k) and (k, i): sums in another order
                mu = float(mi + mk + ri**2 * ii + rk**2 * ik)
                if mu > 0.0 and mu not in found and len(found) < limit:
                    found.append(mu)
    return np.array(found)


def mode_mobilities(particles: Particles, mode: str, limit: int = TABLES) -> np.ndarray:
    """As :func:`pair_mobilities`, for the rolling and spinning modes: mu_m = R_eff^2 (1/I_i + 1/I_k),
    R_eff = R_i R_k / (R_i + R_k), bit for bit as fricgen.langevin.contact_step.update_rolling computes it."""
    if mode == "sliding":
        return pair_mobilities(particles, limit)
    kinds, counts = np.unique(np.stack([particles.radius, particles.inv_inertia], axis=1), axis=0, return_counts=True)
    kinds = kinds[np.argsort(-counts, kind="stable")]
    found: list[float] = []
    for top in range(len(kinds)):
        for i, k in ((j, top) for j in range(top + 1)):
            for (ri, ii), (rk, ik) in ((kinds[i], kinds[k]), (kinds[k], kinds[i])):
                reff = float(ri * rk / (ri + rk))
                mu = reff * reff * float(ii + ik)
                if mu > 0.0 and mu not in found and len(found) < limit:
                    found.append(mu)
    return np.array(found)
