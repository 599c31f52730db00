"""The phase space of one frictional pair: its momenta, velocities, masses and unit normal.

A pair (i, k) has momenta x = (p_i, p_k, j_i, j_k): 12 components in 3-D, and 6 in the 2-D
reduction (discs in the xy-plane spinning about z), with velocities v = dH/dx = M^-1 x. Masses m_i,
m_k, moments of inertia I_i, I_k and radii R_i, R_k are positive symbols, kept unequal; the unit
normal n = r_hat = (r_k - r_i)/|r_k - r_i| is a vector of real symbols, and every identity on the pair
is proven modulo n . n = 1 (:meth:`PairPhaseSpace.reduce`).

The contact modes that live on this space (their maps C_m, forces, noises and mobilities) are
described in :mod:`fricgen.derive.noise.modes`; the proofs on it in :mod:`.mode_proofs`.
The physics: docs/physics.md#zero-probability-current-proved-symbolically.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp


@dataclass(frozen=True)
class PairPhaseSpace:
    """Symbols of one contact pair in ``dim`` = 2 or 3 dimensions."""

    dim: int
    momenta: tuple[sp.Symbol, ...]
    velocities: sp.Matrix  # v = dH/dx, same length as momenta
    normal: tuple[sp.Symbol, ...]  # components of r_hat, with n . n = 1
    masses: tuple[sp.Symbol, ...]  # m_i, m_k, I_i, I_k
    radii: tuple[sp.Symbol, ...]  # R_i, R_k

    def reduce(self, expr: sp.Expr) -> sp.Expr:
        """Expand ``expr`` (polynomial in the normal) and reduce it modulo n . n = 1."""
        last = self.normal[-1]
        rest = sum(c**2 for c in self.normal[:-1])
        poly = sp.Poly(sp.expand(expr), last)
        return sp.expand(poly.rem(sp.Poly(last**2 + rest - 1, last)).as_expr())

    def blocks(self, vector: sp.Matrix) -> tuple[sp.Matrix, ...]:
        """A pair vector split into its (i, k, i's rotation, k's rotation) blocks: 3, 3, 3, 3 in 3-D, 2, 2, 1, 1 in 2-D."""
        sizes = (3, 3, 3, 3) if self.dim == 3 else (2, 2, 1, 1)
        parts, start = [], 0
        for size in sizes:
            parts.append(vector[start : start + size, 0])
            start += size
        return tuple(parts)

    @property
    def inverse_mass(self) -> sp.Matrix:
        """M^-1 with v = M^-1 x: diag(1/m_i, 1/m_k, 1/I_i, 1/I_k) per component [1/mass, 1/(mass length^2)]."""
        return sp.diag(*[sp.cancel(v / x) for v, x in zip(self.velocities, self.momenta)])


def cross_matrix(n: sp.Matrix) -> sp.Matrix:
    """A with A a = n x a."""
    return sp.Matrix([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])


@cache
def pair_phase_space(dim: int) -> PairPhaseSpace:
    """The pair phase space in 3-D (12 momenta) or its 2-D reduction (6 momenta)."""
    masses = sp.symbols("m_i m_k I_i I_k", positive=True)
    radii = sp.symbols("R_i R_k", positive=True)
    m_i, m_k, inertia_i, inertia_k = masses
    if dim == 3:
        normal = sp.symbols("n_x n_y n_z", real=True)
        p_i, p_k, j_i, j_k = (sp.symbols(f"{name}_x:z", real=True) for name in ("p_i", "p_k", "j_i", "j_k"))
        momenta = (*p_i, *p_k, *j_i, *j_k)
        inverse = [1 / m_i] * 3 + [1 / m_k] * 3 + [1 / inertia_i] * 3 + [1 / inertia_k] * 3
    elif dim == 2:
        normal = sp.symbols("n_x n_y", real=True)
        momenta = (*sp.symbols("p_i_x p_i_y p_k_x p_k_y", real=True), *sp.symbols("j_i j_k", real=True))
        inverse = [1 / m_i] * 2 + [1 / m_k] * 2 + [1 / inertia_i, 1 / inertia_k]
    else:
        raise ValueError(f"dim must be 2 or 3, got {dim!r}")
    velocities = sp.Matrix([p * c for p, c in zip(momenta, inverse)])
    return PairPhaseSpace(dim, momenta, velocities, normal, masses, radii)
