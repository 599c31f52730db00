"""The proofs on the pair phase space (12 momenta in 3-D, 6 in 2-D), one path for every contact mode.

For each mode m (:func:`fricgen.derive.noise.modes.describe`; sliding is one of them), with masses,
inertias and radii symbolic and unequal, and the unit normal n reduced modulo n . n = 1:

- :func:`mode_facts`: the engines' velocity of the mode is C_m v; their friction force and torques
  are -C_m^T v_m f/u (so the power is v . F = -f u <= 0, F-9); every written form of their noise has
  covariance sigma sigma^T / 2 = kT D C_m^T C_m (F-50; sliding: the paper's sigma_hat and its random
  force and torque, F-24, F-25); and C_m M^-1 C_m^T = mu_m Pi_m with Pi_m an orthogonal projector
  (isotropic on the mode's space; mu_m = tr(K^2)/tr(K) read off K = C_m M^-1 C_m^T, and
  K C_m = mu_m C_m proven), mu_m equal to the formula the engines use.
- :func:`zero_current` (the lemma): for arbitrary D(u), f(u), the probability current of the
  calculus, from its definition (F-47 Itô, F-48 Stratonovich, F-49 HK) with d ln P_B/dx = -v/kT
  (F-17) and the chain rule for u = |v_m|, is u (J^f + J^fn)/P_B = -C_m^T v_m [f - u D + X D'].
  X is not assumed: it is read off the current (the coefficient of D') and comes out as
  X = (1 - theta) kT mu_m = nu_m kT, so the calculus alone fixes theta. Each law is left with the
  scalar ODE (F-20), whose nu kT the verifier takes from here (fricgen.derive.noise.verification).
- :func:`combined_current`: for several modes at once, each with its own law and an independent
  noise, (J^f + J^fn)/P_B = -sum_m C_m^T v_m [f_m - u_m D_m + X_m D_m'] / u_m on every component:
  the current of the sum is the sum of the modes' currents, whatever the cross-mobilities
  C_a M^-1 C_b^T (:func:`mobility_matrix`; sliding and rolling couple for unequal spheres). With a
  noise shared by two modes the identity fails, and the proof says so.

Everything is exact polynomial algebra: D, D' and f are symbols, no simplification heuristics for
the identities. The physics: docs/physics.md#zero-probability-current-proved-symbolically and
docs/physics-modes.md.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from ..law.symbols import kT
from .modes import check_mode, describe
from .phase_space import PairPhaseSpace, pair_phase_space


@dataclass(frozen=True)
class Lemma:
    """What the zero-current lemma proves for one mode, dimension and calculus.

    Attributes:
        holds: u (J^f + J^fn)/P_B + C_m^T v_m [f - u D + X D'] = 0 on every component, with X read
            off the current (not assumed) and X = c kT mu_m for a rational number c.
        nu_over_mu: c = nu_m/mu_m = X/(kT mu_m) as derived from the current (1 - theta), None if
            the current has no such form.
    """

    holds: bool
    nu_over_mu: sp.Rational | None

    def __bool__(self) -> bool:
        return self.holds

    def nu_kT(self, mobility: sp.Expr) -> sp.Expr | None:
        """X = nu kT for a contact of mobility ``mu`` (a symbol, number or expression)."""
        return None if self.nu_over_mu is None else self.nu_over_mu * kT * mobility


@dataclass(frozen=True)
class Placeholders:
    """The undefined functions of one mode in a proof: D(u), dD/du, f(u) and u = |v_m| itself."""

    amplitude: sp.Symbol
    slope: sp.Symbol
    friction: sp.Symbol
    speed: sp.Symbol

    @property
    def residual(self) -> sp.Expr:
        """f - u D, the part of the bracket without D'."""
        return self.friction - self.speed * self.amplitude


def placeholders(mode: str) -> Placeholders:
    """Symbols D_m, D'_m, f_m, u_m of ``mode`` (distinct per mode, so that modes cannot share them)."""
    return Placeholders(*sp.symbols(f"D_{mode} Dprime_{mode} f_{mode} u_{mode}", real=True))


#: The reduced radius in the zero-current proofs: a positive symbol, so that their algebra stays
#: polynomial (an identity for every R_eff > 0 holds for R_i R_k / (R_i + R_k) in particular).
RHO = sp.Symbol("R_eff", positive=True)


def _equal(space: PairPhaseSpace, left: sp.Matrix, right: sp.Matrix) -> bool:
    return left.shape == right.shape and all(space.reduce(a - b) == 0 for a, b in zip(left, right))


def reduce_unit(space: PairPhaseSpace, expr: sp.Expr) -> sp.Expr:
    """``expr`` expanded and reduced modulo n . n = 1 by n_z^2 -> 1 - n_x^2 - n_y^2 (2-D: n_y).

    The same remainder as :meth:`PairPhaseSpace.reduce` (degree <= 1 in the last component) without
    building a polynomial ring over all the other symbols: 10 to 100 times faster on the currents.
    Exact for expressions that are polynomials in the normal whose other factors are products of
    powers of symbols (so that expansion is a normal form): the proofs use it with R_eff = RHO.
    """
    last, rest = space.normal[-1], 1 - sum(c**2 for c in space.normal[:-1])
    expanded = sp.expand(expr)
    powers = {p for p in expanded.atoms(sp.Pow) if p.base == last and p.exp.is_Integer and p.exp >= 2}
    return sp.expand(expanded.xreplace({p: last ** (int(p.exp) % 2) * rest ** (int(p.exp) // 2) for p in powers}))


def mobility_matrix(space: PairPhaseSpace, a: str, b: str) -> sp.Matrix:
    """C_a M^-1 C_b^T, each entry reduced modulo n . n = 1 and factored."""
    product = describe(a, space.dim).contact_map * space.inverse_mass * describe(b, space.dim).contact_map.T
    return product.applyfunc(lambda e: sp.factor(space.reduce(e)))


@cache
def read_mobility(mode: str, dim: int, radius: sp.Expr | None = None) -> tuple[sp.Expr | None, int]:
    """mu_m read off K = C_m M^-1 C_m^T as tr(K^2)/tr(K), and the rank tr(K)/mu_m of Pi_m = K/mu_m;
    (None, 0) unless K C_m = mu_m C_m holds exactly (then K/mu_m is a symmetric idempotent, an
    orthogonal projector whose range holds every v_m: the mode is isotropic)."""
    space = pair_phase_space(dim)
    contact = describe(mode, dim, radius).contact_map
    k = (contact * space.inverse_mass * contact.T).applyfunc(space.reduce)
    trace, trace2 = sp.factor(space.reduce(k.trace())), sp.factor(space.reduce((k * k).trace()))
    if trace == 0:
        return None, 0
    mobility = sp.factor(trace2 / trace)
    if not _equal(space, sp.expand(k * contact * sp.denom(mobility)), sp.expand(sp.numer(mobility) * contact)):
        return None, 0
    rank = sp.simplify(trace / mobility)
    return mobility, int(rank) if rank.is_Integer else 0


#: The names of :func:`mode_facts`, the same for every mode and dimension.
FACTS = ("velocity_is_C_v", "forces_from_C_transpose", "dissipation", "noise_covariance", "isotropic", "mobility_formula")


@cache
def mode_facts(mode: str, dim: int) -> dict[str, bool]:
    """The law-independent facts of ``mode`` in ``dim`` D (each an exact identity; see the module)."""
    described = describe(mode, dim)
    space, contact, velocity = described.space, described.contact_map, described.velocity
    over_u = sp.Symbol("f_over_u", real=True)
    drift = described.friction_drift(over_u)
    target = (contact.T * contact).applyfunc(sp.expand)
    mobility, rank = read_mobility(mode, dim)
    expected_rank = 1 if dim == 2 or mode == "spinning" else 2
    facts = {
        "velocity_is_C_v": _equal(space, contact * space.velocities, velocity),
        "forces_from_C_transpose": _equal(space, drift, -over_u * contact.T * velocity),
        "dissipation": space.reduce(space.velocities.dot(drift) + over_u * velocity.dot(velocity)) == 0,
        "noise_covariance": all(_equal(space, (s * s.T / 2).applyfunc(sp.expand), target) for s in described.noises),
        "isotropic": mobility is not None and rank == expected_rank,
        "mobility_formula": mobility is not None and sp.simplify(mobility - described.mobility) == 0,
    }
    return {name: facts[name] for name in FACTS}


def _noise_current(space: PairPhaseSpace, sigma: sp.Matrix, calculus: str, d) -> list[sp.Expr]:
    """J^fn / P_B of one noise sigma by (F-47), (F-48) or (F-49); ``d(expr, b)`` is d/dx_b with the chain rule."""
    log_boltzmann = [-v / kT for v in space.velocities]  # d ln P_B / dx_b (F-17)
    size, noises = sigma.shape
    if calculus == "stratonovich":
        inner = [sum(d(sigma[b, g], b) + sigma[b, g] * log_boltzmann[b] for b in range(size)) for g in range(noises)]
        return [-sum(sigma[a, g] * inner[g] for g in range(noises)) / 2 for a in range(size)]
    diffusion = (sigma * sigma.T).applyfunc(sp.expand)
    if calculus == "ito":
        return [-sum(d(diffusion[a, b], b) + diffusion[a, b] * log_boltzmann[b] for b in range(size)) / 2 for a in range(size)]
    if calculus == "hk":
        return [-sum(diffusion[a, b] * log_boltzmann[b] for b in range(size)) / 2 for a in range(size)]
    raise ValueError(f"unknown calculus {calculus!r}")


def current(space: PairPhaseSpace, modes: tuple[str, ...], calculus: str, shared: bool = False, radius: sp.Expr | None = RHO) -> sp.Matrix:
    """(J^f + J^fn) / P_B of the pair with one law on each of ``modes``, all in ``calculus``.

    Each mode m has friction -C_m^T v_m f_m/u_m and noise sqrt(kT D_m(u_m)) sigma_hat_m; D_m depends on
    u_m = |v_m| alone (chain rule du_m/dx_b = (d|v_m|^2/dx_b) / (2 u_m)). The noises are independent
    (one block of columns each), unless ``shared``: then all modes are driven by the same white noise
    (their sigma_hat padded to equal width and added), the mutation the proof must refuse.
    """
    x = space.momenta
    parts = []
    for mode in modes:
        held, described = placeholders(mode), describe(mode, space.dim, radius)
        q = sp.expand(described.velocity.dot(described.velocity))
        parts.append((described, held, [sp.diff(q, xb) / (2 * held.speed) for xb in x]))

    def d(expr: sp.Expr, b: int) -> sp.Expr:
        total = sp.diff(expr, x[b])
        for _, held, du in parts:
            total += sp.diff(expr, held.amplitude) * held.slope * du[b]
        return total

    drift = sp.zeros(len(x), 1)
    sigmas = []
    for described, held, _ in parts:
        drift += described.friction_drift(held.friction / held.speed)
        sigmas.append(sp.sqrt(kT * held.amplitude) * described.noise_matrix)
    if shared:
        width = max(s.shape[1] for s in sigmas)
        sigmas = [sum((sp.Matrix.hstack(s, sp.zeros(len(x), width - s.shape[1])) for s in sigmas), sp.zeros(len(x), width))]
    noise = [sum(column) for column in zip(*(_noise_current(space, s, calculus, d) for s in sigmas))]
    return drift + sp.Matrix(noise)


def derivative_coefficient(space: PairPhaseSpace, flux: sp.Matrix, direction: sp.Matrix, held: Placeholders) -> sp.Expr | None:
    """X with u J/P_B = -C_m^T v_m X D' + (terms without D'), read off one component of the current.

    The D' part of the (reduced) component is compared with the (reduced) direction C_m^T v_m term
    by term: their leading coefficients as polynomials in the momenta and the normal. None when no
    component has a nonzero direction or the leading monomials differ (then no such X exists).
    """
    gens = (*space.momenta, *space.normal)
    for j, g in zip(flux, direction):
        reduced_g = space.reduce(g)
        if reduced_g == 0:
            continue
        part = space.reduce(sp.expand(held.speed * j).coeff(held.slope))
        left, right = sp.Poly(part, *gens), sp.Poly(reduced_g, *gens)
        if left.is_zero:
            return sp.Integer(0)
        if left.LM() != right.LM():
            return None
        return sp.cancel(-left.LC() / right.LC())
    return None


def _direction(mode: str, dim: int) -> sp.Matrix:
    """C_m^T v_m, with R_eff = RHO."""
    described = describe(mode, dim, RHO)
    return described.contact_map.T * described.velocity


@cache
def zero_current(mode: str, dim: int, calculus: str) -> Lemma:
    """u (J^f + J^fn)/P_B + C_m^T v_m [f - u D + X D'] = 0 for arbitrary D(u), f(u), on mode ``mode``.

    X is read off the current (:func:`derivative_coefficient`) and must equal c kT mu_m with a
    rational c (mu_m from :func:`read_mobility`); the identity is then proven on every component.
    ``Lemma.nu_over_mu`` is c (1 - theta of the calculus)."""
    check_mode(mode, dim)
    space = pair_phase_space(dim)
    held = placeholders(mode)
    flux = current(space, (mode,), calculus)
    direction = _direction(mode, dim)
    mobility, _ = read_mobility(mode, dim, RHO)
    coefficient = derivative_coefficient(space, flux, direction, held)
    if coefficient is None or mobility is None:
        return Lemma(False, None)
    ratio = sp.simplify(coefficient / (kT * mobility))
    if not ratio.is_Rational:
        return Lemma(False, None)
    residual = held.residual + ratio * mobility * kT * held.slope
    holds = all(reduce_unit(space, held.speed * j + g * residual) == 0 for j, g in zip(flux, direction))
    return Lemma(holds, ratio)


@cache
def combined_current(modes: tuple[str, ...], dim: int, calculus: str, shared: bool = False) -> dict[str, object]:
    """The current of a pair with one law on each of ``modes`` (distinct), all in ``calculus``.

    Returns ``{"holds": bool, "nu_over_mu": {mode: c}}``: holds when, on every component,
    (prod_m u_m) J/P_B + sum_m (prod_{l != m} u_l) C_m^T v_m [f_m - u_m D_m + c_m kT mu_m D_m'] = 0
    with c_m read off the mode's own lemma (:func:`zero_current`), so that J = 0 whenever every
    D_m solves its own ODE; ``shared`` drives all modes with one noise (for the mutation test).
    """
    for mode in modes:
        check_mode(mode, dim)
    if len(set(modes)) != len(modes):
        raise ValueError(f"modes must be distinct, got {list(modes)}")
    space = pair_phase_space(dim)
    lemmas = {mode: zero_current(mode, dim, calculus) for mode in modes}
    if not all(lemmas.values()):
        return {"holds": False, "nu_over_mu": {m: None for m in modes}}
    flux = current(space, modes, calculus, shared)
    total = sp.zeros(len(space.momenta), 1)
    product = sp.Mul(*(placeholders(m).speed for m in modes))
    for mode in modes:
        held = placeholders(mode)
        residual = held.residual + lemmas[mode].nu_kT(read_mobility(mode, dim, RHO)[0]) * held.slope
        total += (product / held.speed) * residual * _direction(mode, dim)
    holds = all(reduce_unit(space, product * j + g) == 0 for j, g in zip(flux, total))
    return {"holds": holds, "nu_over_mu": {m: lemmas[m].nu_over_mu for m in modes}}
