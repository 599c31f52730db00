"""The contact modes of a pair: sliding, rolling and spinning, each a linear map C_m of the velocities.

A pair (i, k) with unit normal n = r_hat = (r_k - r_i)/|r_k - r_i| and velocities
v = (v_i, v_k, omega_i, omega_k) (:mod:`.phase_space`) has up to three relative motions at its
contact, each linear in v, v_m = C_m v (units of velocity):

- sliding (the paper's F-4): u_perp = P (v_k - v_i) - (R_i omega_i + R_k omega_k) x n, P = 1 - n n^T;
- rolling: v_roll = R_eff (omega_i - omega_k) x n, tangential;
- spinning (3-D only): v_spin = R_eff (omega_i - omega_k) . n, a scalar;

with the reduced radius R_eff = R_i R_k / (R_i + R_k) [length]. In 2-D (discs in the xy-plane,
spinning about z) sliding and rolling are the scalars along t_hat = z x n,
u_t = t_hat . (v_k - v_i) - R_i omega_i - R_k omega_k and v_roll = R_eff (omega_i - omega_k); no
spinning exists there. A law acting on mode m pushes back along C_m^T: the generalized force on
(p_i, p_k, j_i, j_k) is -C_m^T v_m f(u)/u with u = |v_m|, so that its power is -f u <= 0, and its
noise is sqrt(D) C_m^T w with a white noise w in the mode's space. Its mobility is mu_m, with
C_m M^-1 C_m^T = mu_m x (a projector), and nu_m = (1 - theta) mu_m (F-21).

:func:`describe` gives one :class:`ContactMode`: C_m, and v_m, the forces, the noise and mu_m in the
explicit forms the engines apply (rolling: tau_i = -R_eff n x F_roll, tau_k = -tau_i, no force);
:mod:`fricgen.derive.noise.mode_proofs` proves that these forms are C_m^T, dissipate, and leave the
Boltzmann distribution stationary, for every mode alike.

The sign of a mode's velocity flips with n (LAMMPS GRANULAR takes n from j to i and so writes
v_roll with the opposite sign); its magnitude, the friction and the noise do not depend on it.
The physics: docs/physics-modes.md.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from ..law.lawdata import CONTACT_MODES, DEFAULT_MODE, ModeError, mode_refusal
from .derivation import contact_mobility
from .phase_space import PairPhaseSpace, cross_matrix, pair_phase_space

__all__ = ["CONTACT_MODES", "DEFAULT_MODE", "ContactMode", "ModeError", "describe", "dimensions", "mode_mobility"]


@dataclass(frozen=True)
class ContactMode:
    """One contact mode on the pair phase space ``space``, as the engines apply it.

    Attributes:
        name: "sliding", "rolling" or "spinning".
        space: the pair phase space (2-D or 3-D).
        contact_map: C_m with v_m = C_m v (k_m x 12 in 3-D, 1 x 6 in 2-D).
        velocity: v_m as the engines compute it, from cross and dot products (not from C_m) [velocity].
        drag: the engines' friction force and torques on (p_i, p_k, j_i, j_k) per unit f(u)/u, so that
            the friction drift is (f/u) drag.
        noises: sigma_hat_m with noise sigma = sqrt(kT D) sigma_hat_m on (p_i, p_k, j_i, j_k), unit
            white noises; the first drives the proofs of the current, the others are further written
            forms of the same noise (sliding in 3-D: the paper's random force and torque, F-24, F-25).
        mobility: mu_m as the engines compute it [1/mass].
    """

    name: str
    space: PairPhaseSpace
    contact_map: sp.Matrix
    velocity: sp.Matrix
    drag: sp.Matrix
    noises: tuple[sp.Matrix, ...]
    mobility: sp.Expr

    @property
    def noise_matrix(self) -> sp.Matrix:
        """sigma_hat_m, the noise the proofs of the current use."""
        return self.noises[0]

    def friction_drift(self, friction_over_u: sp.Expr) -> sp.Matrix:
        """The friction force and torques for a friction f(u)/u = ``friction_over_u``."""
        return friction_over_u * self.drag


def check_mode(mode: str, dim: int | None) -> None:
    """ModeError (one line) for an unknown mode, or one that the ``dim``-D pair does not have (any
    dimension when None)."""
    why = mode_refusal(mode, dim)
    if why:
        raise ModeError(why)


def dimensions(mode: str) -> tuple[int, ...]:
    """The dimensions in which ``mode`` exists, 3-D first (the order of the proof's checks)."""
    check_mode(mode, None)
    return tuple(sorted(CONTACT_MODES[mode], reverse=True))


@cache
def describe(mode: str, dim: int, radius: sp.Expr | None = None) -> ContactMode:
    """The contact mode ``mode`` of the ``dim``-D pair; ModeError for a mode the pair does not have.

    ``radius`` stands for R_eff = R_i R_k / (R_i + R_k) when given: the zero-current proofs put a
    positive symbol in its place (an identity for every R_eff > 0 holds for R_i R_k / (R_i + R_k)),
    which keeps their algebra polynomial and fast; the facts on C_m and mu_m are proven with
    R_i R_k / (R_i + R_k). Sliding has no R_eff.
    """
    check_mode(mode, dim)
    space = pair_phase_space(dim)
    if mode == "sliding":
        return _sliding(space)
    radius_i, radius_k = space.radii
    radius = radius_i * radius_k / (radius_i + radius_k) if radius is None else radius
    _, _, inertia_i, inertia_k = space.masses
    mobility = radius**2 * (1 / inertia_i + 1 / inertia_k)
    return (_rolling if mode == "rolling" else _spinning)(space, radius, mobility)


def _sliding(space: PairPhaseSpace) -> ContactMode:
    """Sliding: C = [-P, P, R_i A, R_k A] (F-4), the paper's force and torques (F-7, F-8), its noise
    sigma_hat (Methods IV A) and random force and torque (F-24, F-25), mu = 1/m_i + 1/m_k + R_i^2/I_i
    + R_k^2/I_k (F-21). In 2-D C = [-t, t, -R_i, -R_k] with t = z x n, and the noise is one tangential
    random force sqrt(D) eta t with <eta eta'> = 2 kT delta(t - t'): sigma_hat = sqrt(2) (t, -t, R_i, R_k)."""
    v_i, v_k, w_i, w_k = space.blocks(space.velocities)
    radius_i, radius_k = space.radii
    m_i, m_k, inertia_i, inertia_k = space.masses
    mobility = 1 / m_i + 1 / m_k + radius_i**2 / inertia_i + radius_k**2 / inertia_k
    if space.dim == 2:
        tangent = sp.Matrix([-space.normal[1], space.normal[0]])
        velocity = sp.Matrix([tangent.dot(v_k - v_i) - radius_i * w_i[0] - radius_k * w_k[0]])
        contact_map = sp.Matrix([[*(-tangent), *tangent, -radius_i, -radius_k]])
        force_i, torque_per_radius = velocity[0] * tangent, velocity
        noise = sp.sqrt(2) * sp.Matrix([*tangent, *(-tangent), radius_i, radius_k])
        drag = sp.Matrix.vstack(force_i, -force_i, radius_i * torque_per_radius, radius_k * torque_per_radius)
        return ContactMode("sliding", space, contact_map, velocity, drag, (noise,), mobility)
    n = sp.Matrix(space.normal)
    proj, cross, zero = sp.eye(3) - n * n.T, cross_matrix(n), sp.zeros(3)
    spin = radius_i * w_i + radius_k * w_k
    velocity = proj * (v_k - v_i) - spin.cross(n)
    force_i, torque_per_radius = proj * (v_k - v_i) + n.cross(spin), n.cross(v_k - v_i) - proj * spin
    drag = sp.Matrix.vstack(force_i, -force_i, radius_i * torque_per_radius, radius_k * torque_per_radius)
    sigma_hat = sp.Matrix.vstack(
        sp.Matrix.hstack(proj, zero, -cross, zero),
        sp.Matrix.hstack(-proj, zero, cross, zero),
        sp.Matrix.hstack(radius_i * cross, zero, radius_i * proj, zero),
        sp.Matrix.hstack(radius_k * cross, zero, radius_k * proj, zero),
    )
    random_force = sp.Matrix.vstack(  # (F, F_k, tau_i, tau_k)^R = sqrt(D) G (xi, N), <xi xi> = <N N> = kT
        sp.Matrix.hstack(proj, -cross),
        sp.Matrix.hstack(-proj, cross),
        sp.Matrix.hstack(radius_i * cross, radius_i * proj),
        sp.Matrix.hstack(radius_k * cross, radius_k * proj),
    )
    contact_map = sp.Matrix.hstack(-proj, proj, radius_i * cross, radius_k * cross)
    return ContactMode("sliding", space, contact_map, velocity, drag, (sigma_hat, random_force), mobility)


def _rolling(space: PairPhaseSpace, radius: sp.Expr, mobility: sp.Expr) -> ContactMode:
    """Rolling: C = [0, 0, -R_eff A, R_eff A] (2-D: [0, 0, R_eff, -R_eff]); a pure couple
    tau_i = -R_eff n x F_roll, tau_k = +R_eff n x F_roll (2-D: -/+ R_eff F_roll); random torques
    tau_i = R_eff n x w, tau_k = -R_eff n x w from one random vector w with <w w^T> = 2 kT D delta(t - t')
    per component (its normal part exerts nothing): sigma_hat = sqrt(2) [0; 0; R_eff A; -R_eff A]."""
    _, _, w_i, w_k = space.blocks(space.velocities)
    if space.dim == 2:
        velocity = sp.Matrix([radius * (w_i[0] - w_k[0])])
        column = sp.Matrix([0, 0, 0, 0, radius, -radius])
        drag = sp.Matrix([0, 0, 0, 0, -radius * velocity[0], radius * velocity[0]])
        return ContactMode("rolling", space, column.T, velocity, drag, (sp.sqrt(2) * column,), mobility)
    n = sp.Matrix(space.normal)
    cross = cross_matrix(n)
    velocity = radius * (w_i - w_k).cross(n)
    torque = -radius * n.cross(velocity)
    contact_map = sp.Matrix.hstack(sp.zeros(3), sp.zeros(3), -radius * cross, radius * cross)
    noise = sp.sqrt(2) * sp.Matrix.vstack(sp.zeros(6, 3), radius * cross, -radius * cross)
    return ContactMode("rolling", space, contact_map, velocity, sp.Matrix.vstack(sp.zeros(6, 1), torque, -torque), (noise,), mobility)


def _spinning(space: PairPhaseSpace, radius: sp.Expr, mobility: sp.Expr) -> ContactMode:
    """Spinning (3-D): C = [0, 0, R_eff n^T, -R_eff n^T]; tau_i = -R_eff F_spin n, tau_k = +R_eff F_spin n;
    random torques tau_i = R_eff eta n, tau_k = -R_eff eta n with <eta eta'> = 2 kT D delta(t - t')."""
    _, _, w_i, w_k = space.blocks(space.velocities)
    n = sp.Matrix(space.normal)
    velocity = sp.Matrix([radius * (w_i - w_k).dot(n)])
    torque = -radius * velocity[0] * n
    contact_map = sp.Matrix.hstack(sp.zeros(1, 3), sp.zeros(1, 3), radius * n.T, -radius * n.T)
    noise = sp.sqrt(2) * sp.Matrix.vstack(sp.zeros(6, 1), radius * n, -radius * n)
    return ContactMode("spinning", space, contact_map, velocity, sp.Matrix.vstack(sp.zeros(6, 1), torque, -torque), (noise,), mobility)


def mode_mobility(mode: str, m_i, m_k, radius_i, radius_k, inertia_i=None, inertia_k=None) -> sp.Expr:
    """mu_m of :func:`describe` for given particles (solid spheres I = 2/5 m R^2 by default) [1/mass].

    Raises ValueError for non-positive masses, radii or moments of inertia, ModeError for an unknown mode.
    """
    contact_mobility(m_i, m_k, radius_i, radius_k, inertia_i, inertia_k)  # the same checks of the values
    space = pair_phase_space(3 if mode == "spinning" else 2)
    values = [sp.nsimplify(sp.sympify(v)) for v in (m_i, m_k, radius_i, radius_k)]
    pairs = ((values[0], values[2], inertia_i), (values[1], values[3], inertia_k))
    inertia = [sp.Rational(2, 5) * m * R**2 if i is None else sp.nsimplify(sp.sympify(i)) for m, R, i in pairs]
    symbols = (*space.masses[:2], *space.radii, *space.masses[2:])
    return sp.simplify(describe(mode, space.dim).mobility.subs(dict(zip(symbols, [*values, *inertia]))))
