"""The contact modes of a pair: sliding, rolling and spinning, each a linear map C_m of the velocities.

A pair (i, k) with unit normal n = r_hat = (r_k - r_i)/|r_k - r_i| and velocities
v = (v_i, v_k, omega_i, omega_k) has up to three relative motions at its contact, each linear in v,
v_m = C_m v (units of velocity):

- sliding (the paper's F-4): u_perp = P (v_k - v_i) - (R_i omega_i + R_k omega_k) x n, P = 1 - n n^T;
- rolling: v_roll = R_eff (omega_i - omega_k) x n, tangential;
- spinning (3-D only): v_spin = R_eff (omega_i - omega_k) . n, a scalar;

with the reduced radius R_eff = R_i R_k / (R_i + R_k) [length]. In 2-D (discs in the xy-plane,
spinning about z) sliding and rolling are the scalars along t_hat = z x n,
u_t = t_hat . (v_k - v_i) - R_i omega_i - R_k omega_k and v_roll = R_eff (omega_i - omega_k); no
spinning exists there. A law acting on mode m pushes back along C_m^T: the generalized force on
(p_i, p_k, j_i, j_k) is -C_m^T v_m f(u)/u with u = |v_m|, so that its power is -f u <= 0, and its
noise is sqrt(D) C_m^T w with a white noise w in the mode's space. The engines apply them in the
explicit forms written here (rolling: tau_i = -R_eff n x F_roll, tau_k = -tau_i, no force);
:mod:`fricgen.derive.noise.mode_proofs` proves that these forms are C_m^T, dissipate, and leave the
Boltzmann distribution stationary.

The sign of a mode's velocity flips with n (LAMMPS GRANULAR takes n from j to i and so writes
v_roll with the opposite sign); its magnitude, the friction and the noise do not depend on it.
The physics: docs/physics-modes.md.
"""

from __future__ import annotations

import sympy as sp

from ..law.lawdata import CONTACT_MODES, DEFAULT_MODE, ModeError, mode_refusal
from .phase_space import PairPhaseSpace, friction_drift, pair_phase_space, reduced_noise_matrix, tangential_velocity

__all__ = [
    "CONTACT_MODES",
    "DEFAULT_MODE",
    "ModeError",
    "explicit_velocity",
    "friction_drift_of",
    "inverse_mass",
    "mobility_formula",
    "mode_map",
    "mode_mobility",
    "noise_matrix",
    "reduced_radius",
]


def check_mode(mode: str, dim: int | None) -> None:
    """ModeError (one line) for an unknown mode, or one that the ``dim``-D pair does not have (any
    dimension when None)."""
    why = mode_refusal(mode, dim)
    if why:
        raise ModeError(why)


def reduced_radius(space: PairPhaseSpace, radius: sp.Expr | None = None) -> sp.Expr:
    """R_eff = R_i R_k / (R_i + R_k) [length], or ``radius`` when given.

    Every function below takes ``radius`` too: the zero-current proofs put a positive symbol in its
    place (an identity for every R_eff > 0 holds for R_i R_k / (R_i + R_k)), which keeps their
    algebra polynomial and fast; the facts on C_m and mu_m are proven with R_i R_k / (R_i + R_k).
    """
    if radius is not None:
        return radius
    radius_i, radius_k = space.radii
    return radius_i * radius_k / (radius_i + radius_k)


def inverse_mass(space: PairPhaseSpace) -> sp.Matrix:
    """M^-1 with v = M^-1 x: diag(1/m_i, 1/m_k, 1/I_i, 1/I_k) per component [1/mass, 1/(mass length^2)]."""
    return sp.diag(*[sp.cancel(v / x) for v, x in zip(space.velocities, space.momenta)])


def _cross_matrix(n: sp.Matrix) -> sp.Matrix:
    """A with A a = n x a."""
    return sp.Matrix([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])


def _blocks(space: PairPhaseSpace) -> tuple[sp.Matrix, ...]:
    """The velocities split into (v_i, v_k, omega_i, omega_k)."""
    sizes = (3, 3, 3, 3) if space.dim == 3 else (2, 2, 1, 1)
    blocks, start = [], 0
    for size in sizes:
        blocks.append(space.velocities[start : start + size, 0])
        start += size
    return tuple(blocks)


def mode_map(mode: str, dim: int, radius: sp.Expr | None = None) -> sp.Matrix:
    """C_m, the matrix with v_m = C_m v on the ``dim``-D pair (k_m x 12 in 3-D, 1 x 6 in 2-D).

    Written block by block: sliding [-P, P, R_i A, R_k A] (3-D; the pair phase space's contact map),
    rolling [0, 0, -R_eff A, R_eff A], spinning [0, 0, R_eff n^T, -R_eff n^T], with A a = n x a;
    in 2-D sliding [-t, t, -R_i, -R_k] and rolling [0, 0, R_eff, -R_eff]. ModeError for a mode the
    pair does not have.
    """
    check_mode(mode, dim)
    space = pair_phase_space(dim)
    if mode == "sliding":
        return space.contact_map
    radius = reduced_radius(space, radius)
    if dim == 2:
        return sp.Matrix([[0, 0, 0, 0, radius, -radius]])
    n = sp.Matrix(space.normal)
    zero = sp.zeros(*(_cross_matrix(n).shape if mode == "rolling" else (1, 3)))
    if mode == "rolling":
        cross = _cross_matrix(n)
        return sp.Matrix.hstack(zero, zero, -radius * cross, radius * cross)
    return sp.Matrix.hstack(zero, zero, radius * n.T, -radius * n.T)


def explicit_velocity(mode: str, space: PairPhaseSpace, radius: sp.Expr | None = None) -> sp.Matrix:
    """v_m as the engines compute it, from the cross and dot products (not from C_m)."""
    check_mode(mode, space.dim)
    if mode == "sliding":
        return tangential_velocity(space)
    _, _, w_i, w_k = _blocks(space)
    radius = reduced_radius(space, radius)
    if space.dim == 2:
        return sp.Matrix([radius * (w_i[0] - w_k[0])])
    n = sp.Matrix(space.normal)
    if mode == "rolling":
        return radius * (w_i - w_k).cross(n)
    return sp.Matrix([radius * (w_i - w_k).dot(n)])


def friction_drift_of(mode: str, space: PairPhaseSpace, friction_over_u: sp.Expr, radius: sp.Expr | None = None) -> sp.Matrix:
    """The friction force and torques on (p_i, p_k, j_i, j_k) as the engines apply them.

    With F_m = f(u) v_m / u the friction of the mode [force]: sliding as the paper (F-7, F-8);
    rolling tau_i = -R_eff n x F_roll, tau_k = +R_eff n x F_roll (3-D), tau_i = -R_eff F_roll,
    tau_k = +R_eff F_roll (2-D); spinning tau_i = -R_eff F_spin n, tau_k = +R_eff F_spin n. Rolling
    and spinning exert no force: a pure couple.
    """
    if mode == "sliding":
        check_mode(mode, space.dim)
        return friction_drift(space, friction_over_u)
    force = friction_over_u * explicit_velocity(mode, space, radius)
    radius = reduced_radius(space, radius)
    if space.dim == 2:
        torque = -radius * force
        return sp.Matrix([0, 0, 0, 0, torque[0], -torque[0]])
    n = sp.Matrix(space.normal)
    torque = -radius * (n.cross(force) if mode == "rolling" else force[0] * n)
    return sp.Matrix.vstack(sp.zeros(6, 1), torque, -torque)


def noise_matrix(mode: str, space: PairPhaseSpace, radius: sp.Expr | None = None) -> sp.Matrix:
    """sigma_hat_m with noise sigma = sqrt(kT D) sigma_hat_m on (p_i, p_k, j_i, j_k), unit white noises.

    Sliding: the paper's (Methods IV A; :func:`fricgen.derive.noise.phase_space.reduced_noise_matrix`).
    Rolling: random torques tau_i = R_eff n x w, tau_k = -R_eff n x w from one random vector w with
    <w w^T> = 2 kT D delta(t - t') per component (its normal part exerts nothing), i.e. sqrt(2) times
    [0; 0; R_eff A; -R_eff A]; spinning tau_i = R_eff eta n, tau_k = -R_eff eta n with
    <eta eta'> = 2 kT D delta(t - t'); in 2-D rolling tau_i = R_eff eta, tau_k = -R_eff eta.
    """
    if mode == "sliding":
        check_mode(mode, space.dim)
        return reduced_noise_matrix(space)
    check_mode(mode, space.dim)
    radius = reduced_radius(space, radius)
    if space.dim == 2:
        return sp.sqrt(2) * sp.Matrix([0, 0, 0, 0, radius, -radius])
    n = sp.Matrix(space.normal)
    block = _cross_matrix(n) if mode == "rolling" else n
    return sp.sqrt(2) * sp.Matrix.vstack(sp.zeros(6, block.shape[1]), radius * block, -radius * block)


def mobility_formula(mode: str, space: PairPhaseSpace, radius: sp.Expr | None = None) -> sp.Expr:
    """mu_m as the engines compute it [1/mass]: sliding 1/m_i + 1/m_k + R_i^2/I_i + R_k^2/I_k (F-21),
    rolling and spinning R_eff^2 (1/I_i + 1/I_k). The proof checks it against C_m M^-1 C_m^T."""
    check_mode(mode, space.dim)
    if mode == "sliding":
        return space.mobility
    _, _, inertia_i, inertia_k = space.masses
    return reduced_radius(space, radius) ** 2 * (1 / inertia_i + 1 / inertia_k)


def mode_mobility(mode: str, m_i, m_k, radius_i, radius_k, inertia_i=None, inertia_k=None) -> sp.Expr:
    """mu_m of :func:`mobility_formula` for given particles (solid spheres I = 2/5 m R^2 by default).

    Raises ValueError for non-positive masses, radii or moments of inertia, ModeError for an unknown mode.
    """
    from .derivation import contact_mobility

    contact_mobility(m_i, m_k, radius_i, radius_k, inertia_i, inertia_k)  # the same checks of the values
    space = pair_phase_space(3 if mode == "spinning" else 2)
    values = [sp.nsimplify(sp.sympify(v)) for v in (m_i, m_k, radius_i, radius_k)]
    pairs = ((values[0], values[2], inertia_i), (values[1], values[3], inertia_k))
    inertia = [sp.Rational(2, 5) * m * R**2 if i is None else sp.nsimplify(sp.sympify(i)) for m, R, i in pairs]
    symbols = (*space.masses[:2], *space.radii, *space.masses[2:])
    return sp.simplify(mobility_formula(mode, space).subs(dict(zip(symbols, [*values, *inertia]))))
