"""The phase space of one frictional pair and its Fokker–Planck probability current.

A pair (i, k) has momenta x = (p_i, p_k, j_i, j_k): 12 components in 3-D, and 6 in the 2-D
reduction (discs in the xy-plane spinning about z). With velocities v = dH/dx, the relative
tangential contact velocity is linear in v, u_perp = C v (F-4), and u = |u_perp|.

The deterministic friction drift is taken from the paper's force and torque (F-7, F-8); the noise
is sigma = sqrt(kT D(u)) sigma_hat with the paper's reduced matrix sigma_hat (Methods IV A). The
probability current per Boltzmann weight follows the definitions (F-47..49) of the three calculi
and the product rule with d ln P_B / dx_beta = -v_beta / kT (F-17).

Everything is exact polynomial algebra: D, D' and f are kept as symbols, du/dx by the chain rule
du/dx_beta = (dQ/dx_beta) / (2u) with Q = u_perp . u_perp, and the unit normal n is reduced
modulo n . n = 1. The lemma proven here, for arbitrary D(u) and f(u),

    u (J^f + J^fn) / P_B = -C^T u_perp [f - u D + X dD/du],

leaves each law with the scalar ODE (F-20). X is not assumed: it is read off the current (the
coefficient of dD/du, a function of the symbolic masses, inertias, radii and kT) and then proven
to hold on every component; it comes out as X = nu kT with nu = (1 - theta) mu, so the calculus
alone (its definition F-47..49) fixes theta. The verifier uses this X, never the noise model's own
nu kT, for the residual of each law (fricgen.derive.noise.verification).

The physics: docs/physics.md#zero-probability-current-proved-symbolically.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from ..calculus import Calculus
from ..law.symbols import kT


@dataclass(frozen=True)
class PairPhaseSpace:
    """Symbols and linear maps of one contact pair in ``dim`` = 2 or 3 dimensions."""

    dim: int
    momenta: tuple[sp.Symbol, ...]
    velocities: sp.Matrix  # v = dH/dx, same length as momenta
    normal: tuple[sp.Symbol, ...]  # components of r_hat, with n . n = 1
    contact_map: sp.Matrix  # C with u_perp = C v
    masses: tuple[sp.Symbol, ...]  # m_i, m_k, I_i, I_k
    radii: tuple[sp.Symbol, ...]  # R_i, R_k

    @property
    def mobility(self) -> sp.Expr:
        """Contact mobility mu = 1/m_i + 1/m_k + R_i^2/I_i + R_k^2/I_k (F-21)."""
        m_i, m_k, inertia_i, inertia_k = self.masses
        radius_i, radius_k = self.radii
        return 1 / m_i + 1 / m_k + radius_i**2 / inertia_i + radius_k**2 / inertia_k

    def reduce(self, expr: sp.Expr) -> sp.Expr:
        """Expand ``expr`` (polynomial in the normal) and reduce it modulo n . n = 1."""
        last = self.normal[-1]
        rest = sum(c**2 for c in self.normal[:-1])
        poly = sp.Poly(sp.expand(expr), last)
        return sp.expand(poly.rem(sp.Poly(last**2 + rest - 1, last)).as_expr())


def _cross_matrix(n: sp.Matrix) -> sp.Matrix:
    """A with A a = n x a."""
    return sp.Matrix([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])


def _bodies() -> tuple[tuple[sp.Symbol, ...], tuple[sp.Symbol, ...]]:
    masses = sp.symbols("m_i m_k I_i I_k", positive=True)
    radii = sp.symbols("R_i R_k", positive=True)
    return masses, radii


@cache
def pair_phase_space(dim: int) -> PairPhaseSpace:
    """The pair phase space in 3-D (12 momenta) or its 2-D reduction (6 momenta)."""
    masses, radii = _bodies()
    m_i, m_k, inertia_i, inertia_k = masses
    radius_i, radius_k = radii
    if dim == 3:
        normal = sp.symbols("n_x n_y n_z", real=True)
        n = sp.Matrix(normal)
        proj, cross = sp.eye(3) - n * n.T, _cross_matrix(n)
        p_i, p_k, j_i, j_k = (sp.symbols(f"{name}_x:z", real=True) for name in ("p_i", "p_k", "j_i", "j_k"))
        momenta = (*p_i, *p_k, *j_i, *j_k)
        inverse = [1 / m_i] * 3 + [1 / m_k] * 3 + [1 / inertia_i] * 3 + [1 / inertia_k] * 3
        contact_map = sp.Matrix.hstack(-proj, proj, radius_i * cross, radius_k * cross)
    elif dim == 2:
        normal = sp.symbols("n_x n_y", real=True)
        tangent = sp.Matrix([-normal[1], normal[0]])  # t_hat = z x r_hat
        momenta = (*sp.symbols("p_i_x p_i_y p_k_x p_k_y", real=True), *sp.symbols("j_i j_k", real=True))
        inverse = [1 / m_i] * 2 + [1 / m_k] * 2 + [1 / inertia_i, 1 / inertia_k]
        contact_map = sp.Matrix([[*(-tangent), *tangent, -radius_i, -radius_k]])
    else:
        raise ValueError(f"dim must be 2 or 3, got {dim!r}")
    velocities = sp.Matrix([p * c for p, c in zip(momenta, inverse)])
    return PairPhaseSpace(dim, momenta, velocities, normal, contact_map, masses, radii)


def _split(vector: sp.Matrix, dim: int) -> tuple[sp.Matrix, ...]:
    """Split a pair vector into (v_i, v_k, omega_i, omega_k) blocks."""
    sizes = (3, 3, 3, 3) if dim == 3 else (2, 2, 1, 1)
    blocks, start = [], 0
    for size in sizes:
        blocks.append(vector[start : start + size, 0])
        start += size
    return tuple(blocks)


def tangential_velocity(space: PairPhaseSpace) -> sp.Matrix:
    """u_perp from the paper's (F-4) in 3-D, the signed u_t of the 2-D reduction in 2-D."""
    v_i, v_k, w_i, w_k = _split(space.velocities, space.dim)
    radius_i, radius_k = space.radii
    if space.dim == 3:
        n = sp.Matrix(space.normal)
        spin = radius_i * w_i + radius_k * w_k
        return (sp.eye(3) - n * n.T) * (v_k - v_i) - spin.cross(n)
    tangent = sp.Matrix([-space.normal[1], space.normal[0]])
    return sp.Matrix([tangent.dot(v_k - v_i) - radius_i * w_i[0] - radius_k * w_k[0]])


def friction_drift(space: PairPhaseSpace, friction_over_u: sp.Expr) -> sp.Matrix:
    """Deterministic friction force and torques on (p_i, p_k, j_i, j_k) (F-7, F-8; 2-D reduction)."""
    v_i, v_k, w_i, w_k = _split(space.velocities, space.dim)
    radius_i, radius_k = space.radii
    if space.dim == 3:
        n = sp.Matrix(space.normal)
        proj = sp.eye(3) - n * n.T
        spin = radius_i * w_i + radius_k * w_k
        force_i = friction_over_u * (proj * (v_k - v_i) + n.cross(spin))
        torque_per_radius = friction_over_u * (n.cross(v_k - v_i) - proj * spin)
    else:
        force_i = friction_over_u * tangential_velocity(space)[0] * sp.Matrix([-space.normal[1], space.normal[0]])
        torque_per_radius = friction_over_u * tangential_velocity(space)
    return sp.Matrix.vstack(force_i, -force_i, radius_i * torque_per_radius, radius_k * torque_per_radius)


def reduced_noise_matrix(space: PairPhaseSpace) -> sp.Matrix:
    """sigma_hat with sigma = sqrt(kT D) sigma_hat: the paper's (Methods IV A) in 3-D.

    In 2-D it is sqrt(2) (t_hat, -t_hat, R_i, R_k): one tangential random force sqrt(D) eta t_hat
    with <eta eta'> = 2 kT delta(t - t').
    """
    radius_i, radius_k = space.radii
    if space.dim == 3:
        n = sp.Matrix(space.normal)
        proj, cross, zero = sp.eye(3) - n * n.T, _cross_matrix(n), sp.zeros(3)
        return sp.Matrix.vstack(
            sp.Matrix.hstack(proj, zero, -cross, zero),
            sp.Matrix.hstack(-proj, zero, cross, zero),
            sp.Matrix.hstack(radius_i * cross, zero, radius_i * proj, zero),
            sp.Matrix.hstack(radius_k * cross, zero, radius_k * proj, zero),
        )
    tangent = [-space.normal[1], space.normal[0]]
    return sp.sqrt(2) * sp.Matrix([*tangent, *(-c for c in tangent), radius_i, radius_k])


def random_force_matrix(space: PairPhaseSpace) -> sp.Matrix:
    """G with (F, F_k, tau_i, tau_k)^R = sqrt(D) G (xi, N) as written in (F-24, F-25) (3-D)."""
    radius_i, radius_k = space.radii
    n = sp.Matrix(space.normal)
    proj, cross = sp.eye(3) - n * n.T, _cross_matrix(n)
    return sp.Matrix.vstack(
        sp.Matrix.hstack(proj, -cross),
        sp.Matrix.hstack(-proj, cross),
        sp.Matrix.hstack(radius_i * cross, radius_i * proj),
        sp.Matrix.hstack(radius_k * cross, radius_k * proj),
    )


CALCULI_THETA = {c.value: sp.Rational(c.theta) for c in Calculus}

# Placeholders of the lemma: D(u), dD/du, f(u) and u itself.
D_SYM, DD_SYM, F_SYM, U_SYM = sp.symbols("D Dprime f u_c", real=True)


def current_per_boltzmann(space: PairPhaseSpace, calculus: str) -> sp.Matrix:
    """(J^f + J^fn) / P_B for noise sigma = sqrt(kT D(u)) sigma_hat, by (F-47), (F-48) or (F-49)."""
    x = space.momenta
    u_perp = tangential_velocity(space)
    q = sp.expand(u_perp.dot(u_perp))
    du = [sp.diff(q, xb) / (2 * U_SYM) for xb in x]
    log_boltzmann = [-vb / kT for vb in space.velocities]  # d ln P_B / dx_beta (F-17)

    def d(expr: sp.Expr, beta: int) -> sp.Expr:
        """d/dx_beta with D = D(u(x)) by the chain rule."""
        return sp.diff(expr, x[beta]) + sp.diff(expr, D_SYM) * DD_SYM * du[beta]

    sigma = sp.sqrt(kT * D_SYM) * reduced_noise_matrix(space)
    size, noises = sigma.shape
    drift = friction_drift(space, F_SYM / U_SYM)
    if calculus == "ito":
        diffusion = (sigma * sigma.T).applyfunc(sp.expand)
        noise = [-sum(d(diffusion[a, b], b) + diffusion[a, b] * log_boltzmann[b] for b in range(size)) / 2 for a in range(size)]
    elif calculus == "stratonovich":
        inner = [sum(d(sigma[b, g], b) + sigma[b, g] * log_boltzmann[b] for b in range(size)) for g in range(noises)]
        noise = [-sum(sigma[a, g] * inner[g] for g in range(noises)) / 2 for a in range(size)]
    elif calculus == "hk":
        diffusion = (sigma * sigma.T).applyfunc(sp.expand)
        noise = [-sum(diffusion[a, b] * log_boltzmann[b] for b in range(size)) / 2 for a in range(size)]
    else:
        raise ValueError(f"unknown calculus {calculus!r}")
    return drift + sp.Matrix(noise)


@dataclass(frozen=True)
class Lemma:
    """What the zero-current lemma proves for one dimension and calculus.

    Attributes:
        holds: u (J^f + J^fn)/P_B + C^T u_perp [f - u D + X D'] = 0 on every component, with X
            read off the current (not assumed) and X = c kT mu for a rational number c.
        nu_over_mu: c = nu/mu = X/(kT mu) as derived from the current (1 - theta), None if the
            current has no such form.
    """

    holds: bool
    nu_over_mu: sp.Rational | None

    def __bool__(self) -> bool:
        return self.holds

    def nu_kT(self, mobility: sp.Expr) -> sp.Expr | None:
        """X = nu kT for a contact of mobility ``mu`` (a symbol, number or expression)."""
        return None if self.nu_over_mu is None else self.nu_over_mu * kT * mobility


def derivative_coefficient(space: PairPhaseSpace, current: sp.Matrix, direction: sp.Matrix) -> sp.Expr | None:
    """X with u J/P_B = -C^T u_perp X D' + (terms without D'), read off one component of the current.

    The D' part of the (reduced) component is compared with the (reduced) direction term by term:
    their leading coefficients as polynomials in the momenta and the normal. None when no component
    has a nonzero direction or the leading monomials differ (then no such X exists).
    """
    gens = (*space.momenta, *space.normal)
    for j, g in zip(current, direction):
        reduced_g = space.reduce(g)
        if reduced_g == 0:
            continue
        part = space.reduce(sp.expand(U_SYM * j).coeff(DD_SYM))
        left, right = sp.Poly(part, *gens), sp.Poly(reduced_g, *gens)
        if left.is_zero:
            return sp.Integer(0)
        if left.LM() != right.LM():
            return None
        return sp.cancel(-left.LC() / right.LC())
    return None


@cache
def zero_current_lemma(dim: int, calculus: str) -> Lemma:
    """Prove u (J^f + J^fn)/P_B + C^T u_perp [f - u D + X D'] = 0 for arbitrary D(u), f(u).

    X is read off the current (:func:`derivative_coefficient`) and must equal c kT mu with a
    rational c; the identity is then proven on every component. Exact: no simplification
    heuristics for the identity, only expansion and reduction modulo n . n = 1.
    """
    space = pair_phase_space(dim)
    current = current_per_boltzmann(space, calculus)
    direction = space.contact_map.T * tangential_velocity(space)
    coefficient = derivative_coefficient(space, current, direction)
    if coefficient is None:
        return Lemma(False, None)
    ratio = sp.simplify(coefficient / (kT * space.mobility))
    if not ratio.is_Rational:
        return Lemma(False, None)
    residual = F_SYM - U_SYM * D_SYM + ratio * space.mobility * kT * DD_SYM
    holds = all(space.reduce(U_SYM * j + g * residual) == 0 for j, g in zip(current, direction))
    return Lemma(holds, ratio)


@cache
def covariance_identities(dim: int) -> dict[str, bool]:
    """Noise covariance identities (F-50): sigma sigma^T / 2 = kT D C^T C, checked exactly.

    In 3-D both the paper's sigma_hat and the random force and torque (F-24, F-25) with
    <xi xi> = <N N> = kT are checked; in 2-D the single tangential random force.
    """
    space = pair_phase_space(dim)
    target = space.contact_map.T * space.contact_map
    sigma_hat = reduced_noise_matrix(space)
    facts = {"sigma_hat": _equal_mod_unit(space, sigma_hat * sigma_hat.T / 2, target)}
    if dim == 3:
        g = random_force_matrix(space)
        facts["random_force"] = _equal_mod_unit(space, g * g.T / 2, target)
    return facts


def _equal_mod_unit(space: PairPhaseSpace, left: sp.Matrix, right: sp.Matrix) -> bool:
    return all(space.reduce(a - b) == 0 for a, b in zip(left, right))
