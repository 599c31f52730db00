"""Conservative interactions as SymPy expressions; forces by differentiation, F = -dU/dx.

- ``wca``: Weeks–Chandler–Andersen pair potential (F-34), cut and shifted at 2^(1/6) sigma.
- ``sticky``: Baxter's sticky contact of hard rods of length sigma in the power-law
  delta_eps representation (B-31): V(r) = -kT ln[1 + gamma delta_eps(r - sigma)] for
  sigma <= r < sigma + eps (the hard core r < sigma is enforced by the dynamics), zero beyond.
  Its force is (B-32).
- ``cosine``: external potential U(x) = (U0/2) cos(2 pi x / lambda) (B-21).
- ``ratchet``: the asymmetric (ratchet) external potential
  U(x) = (U0/2) [sin(2 pi x / lambda) + (a/4) sin(4 pi x / lambda)] (Bartussek, Hänggi & Kissner,
  Europhys. Lett. 28, 459 (1994)); a = 0 is the cosine field shifted by a quarter wavelength.

External potentials are periodic fields of amplitude ``U0`` (kT) and period ``lambda``, both
parameters (the BCD engine folds its profiles onto one period): see check_external.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import sympy as sp

from .symbols import kT, r

#: The text this module was imported from: generated potentials carry its hash (fricgen.derive.law.lawdata.potential_source_hash).
SOURCE = Path(__file__).read_bytes()

x = sp.Symbol("x", real=True)


@dataclass(frozen=True)
class Potential:
    """A potential energy U(variable; parameters) with default parameter values and units."""

    name: str
    energy: sp.Expr
    variable: sp.Symbol
    defaults: dict[str, float]
    units: dict[str, str] = field(default_factory=dict)
    reference: str = ""

    @property
    def symbols(self) -> dict[str, sp.Symbol]:
        by_name = {str(s): s for s in self.energy.free_symbols}
        return {name: by_name[name] for name in self.defaults if name in by_name}

    @property
    def force(self) -> sp.Expr:
        """F = -dU/d(variable), branch by branch for piecewise energies."""
        return sp.piecewise_fold(-sp.diff(self.energy, self.variable))


def _wca() -> Potential:
    eps, sigma = sp.symbols("epsilon sigma", positive=True)
    cut = 2 ** sp.Rational(1, 6) * sigma
    energy = sp.Piecewise((4 * eps * ((sigma / r) ** 12 - (sigma / r) ** 6) + eps, r <= cut), (0, True))
    return Potential("wca", energy, r, {"epsilon": 1.0, "sigma": 1.0}, {"epsilon": "kT", "sigma": "sigma"}, "F-34")


def delta_eps(distance: sp.Expr, p: sp.Expr, eps: sp.Expr) -> sp.Expr:
    """Power-law representation of delta(distance) on 0 <= distance < eps (B-31)."""
    return (p + 1) / eps ** (p + 1) * (eps - distance) ** p


def _sticky() -> Potential:
    gamma, p, eps, sigma = sp.symbols("gamma p eps sigma", positive=True)
    inside = -kT * sp.log(1 + gamma * delta_eps(r - sigma, p, eps))
    energy = sp.Piecewise((inside, r < sigma + eps), (0, True))
    return Potential(
        "sticky",
        energy,
        r,
        {"gamma": 1.0, "p": 3.0, "eps": 0.05, "sigma": 1.0},
        {"gamma": "sigma", "p": "1", "eps": "sigma", "sigma": "sigma"},
        "B-31",
    )


def _cosine() -> Potential:
    amplitude, wavelength = sp.symbols("U0 lambda", positive=True)
    energy = amplitude / 2 * sp.cos(2 * sp.pi * x / wavelength)
    return Potential("cosine", energy, x, {"U0": 6.0, "lambda": 1.0}, {"U0": "kT", "lambda": "sigma"}, "B-21")


def _ratchet() -> Potential:
    amplitude, wavelength = sp.symbols("U0 lambda", positive=True)
    asymmetry = sp.Symbol("a", real=True)
    phase = 2 * sp.pi * x / wavelength
    energy = amplitude / 2 * (sp.sin(phase) + asymmetry / 4 * sp.sin(2 * phase))
    return Potential(
        "ratchet", energy, x, {"U0": 6.0, "lambda": 1.0, "a": 1.0}, {"U0": "kT", "lambda": "sigma", "a": "1"}, "Bartussek et al. 1994"
    )


def check_external(potential: Potential) -> None:
    """Raise ValueError unless U(x; U0, lambda, ...) has the parameters U0 and lambda and
    U(x + lambda) - U(x) simplifies to exactly 0."""
    missing = {"U0", "lambda"} - set(potential.symbols)
    if potential.variable != x or missing:
        raise ValueError(f"external potential {potential.name} must be U(x) with parameters U0 and lambda (missing {sorted(missing)})")
    shift = potential.energy.subs(x, x + potential.symbols["lambda"]) - potential.energy
    if sp.simplify(sp.expand_trig(shift)) != 0:
        difference = sp.simplify(shift)
        raise ValueError(f"external potential {potential.name} is not periodic with period lambda: U(x + lambda) - U(x) = {difference}")


#: Pair potentials U(r); a law's weight may name one (w = -dU/dr).
PAIR_POTENTIALS: dict[str, Potential] = {p.name: p for p in (_wca(), _sticky())}
#: External potentials U(x).
EXTERNAL_POTENTIALS: dict[str, Potential] = {p.name: p for p in (_cosine(), _ratchet())}
