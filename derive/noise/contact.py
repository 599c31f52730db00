"""A pair with one law per contact mode: the proof that the combination keeps Maxwell–Boltzmann.

A contact may carry up to one law on each of its modes (sliding, rolling, spinning; at most two in
2-D), each with its own noise amplitude D_m and its own independent noise. :func:`prove_contact`
checks, never assumes:

- ``one_law_per_mode``: the modes are distinct (two laws on one mode would be one law f_1 + f_2);
- ``one_calculus``: all the laws' models are for one calculus (the contact step evaluates the
  amplitudes of a pair at one point of the step);
- ``modes_exist``: every mode exists in the dimensions asked for (spinning in 3-D only);
- ``laws_verified``: each model passes its own proof (:func:`.verification.prove`, or the
  ``verifier`` given, e.g. :func:`fricgen.derive.driver.verify` with the kernel check);
- ``zero_current_<d>d``: the probability current of the sum, from the definition of the calculus on
  the full pair phase space with every D_m(u_m), f_m(u_m) arbitrary, is the sum of the modes'
  currents, so it vanishes when each D_m solves its own ODE (:func:`.mode_proofs.combined_current`).

The modes exchange momentum where C_a M^-1 C_b^T != 0 (``details["coupling ..."]``): sliding and
rolling do for unequal spheres, by R_eff (R_k/I_k - R_i/I_i) P; spinning never. The coupling changes
how the modes relax, not the equilibrium: it does not enter the current, because each D_m depends
on its own speed only and the noises are independent (a noise shared between modes fails the
proof). The physics: docs/physics-modes.md.
"""

from __future__ import annotations

import itertools
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import sympy as sp

from ..law.lawdata import CONTACT_MODES, mode_refusal
from . import lemma_cache
from .derivation import NoiseModel
from .mode_proofs import mobility_matrix
from .phase_space import pair_phase_space
from .verification import Report, prove


@dataclass(frozen=True)
class ContactReport:
    """The proof of one contact's set of laws (see the module for the checks)."""

    modes: tuple[str, ...]
    calculus: str
    checks: dict[str, bool]
    details: dict[str, str] = field(default_factory=dict)
    reports: tuple[Report, ...] = ()
    seconds: float = 0.0

    @property
    def verified(self) -> bool:
        return all(self.checks.values())

    @property
    def reason(self) -> str:
        """Why the combination is refused, on one line; "" when verified."""
        failed = [k for k, v in self.checks.items() if not v]
        return "; ".join(f"{k}: {self.details.get(k, 'failed')}" for k in failed)

    def as_dict(self) -> dict:
        return {
            "modes": list(self.modes),
            "calculus": self.calculus,
            "verified": self.verified,
            "checks": dict(self.checks),
            "details": dict(self.details),
            "laws": [r.as_dict() for r in self.reports],
            "seconds": round(self.seconds, 3),
        }


def coupling(a: str, b: str, dim: int) -> str:
    """C_a M^-1 C_b^T in words: "0", or a scalar c with "c P" (3-D tangential modes) or "c" (scalars)."""
    space = pair_phase_space(dim)
    matrix = mobility_matrix(space, a, b)
    if all(e == 0 for e in matrix):
        return "0"
    if matrix.shape == (1, 1):
        return str(sp.factor(matrix[0, 0]))
    n = sp.Matrix(space.normal)
    scalar = sp.factor(space.reduce(matrix.trace()) / 2)
    projector = sp.eye(3) - n * n.T
    if matrix.shape == (3, 3) and all(space.reduce(sp.numer(sp.together(e))) == 0 for e in matrix - scalar * projector):
        return f"({scalar}) P"
    return str(matrix)


def prove_contact(
    models: Sequence[NoiseModel], dims: Sequence[int] | None = None, verifier: Callable[[NoiseModel], Report] = prove
) -> ContactReport:
    """Prove that one law per mode on a pair (the ``models``, one per law) leaves P_B stationary.

    Args:
        models: the noise models of the pair's laws, one per contact mode.
        dims: the dimensions the pair lives in; a mode that does not exist in one of them refuses the
            combination (spinning with 2 among ``dims``). None: every dimension in which all the
            modes exist.
        verifier: the proof of each single model (:func:`.verification.prove` by default).

    Returns:
        The report; ``reason`` says, on one line, why a combination is refused. Never raises for a
        combination that fails.
    """
    start = time.perf_counter()
    modes = tuple(m.law.mode for m in models)
    calculi = sorted({m.calculus.value for m in models})
    checks: dict[str, bool] = {}
    details: dict[str, str] = {}
    checks["one_law_per_mode"] = bool(modes) and len(set(modes)) == len(modes)
    if not checks["one_law_per_mode"]:
        twice = sorted({m for m in modes if modes.count(m) > 1})
        details["one_law_per_mode"] = f"modes {list(modes)}: one law per mode ({twice} more than once)" if modes else "no law"
    checks["one_calculus"] = len(calculi) <= 1
    if not checks["one_calculus"]:
        details["one_calculus"] = f"calculi {calculi}: a pair's noise amplitudes are evaluated at one point of the step"
    if dims is None:
        dims = tuple(d for d in (3, 2) if all(d in CONTACT_MODES.get(m, ()) for m in modes)) or (3, 2)
    refusals = sorted({why for m in set(modes) for d in dims if (why := mode_refusal(m, d))})
    checks["modes_exist"] = not refusals
    if refusals:
        details["modes_exist"] = "; ".join(refusals)
    reports = tuple(verifier(m) for m in models)
    checks["laws_verified"] = all(r.verified for r in reports)
    if not checks["laws_verified"]:
        details["laws_verified"] = ", ".join(
            f"{r.law} ({r.calculus}): {[k for k, v in r.checks.items() if not v]}" for r in reports if not r.verified
        )
    if checks["one_law_per_mode"] and checks["one_calculus"] and checks["modes_exist"]:
        for dim in dims:
            ordered = tuple(m for m in CONTACT_MODES if m in modes)  # one cache entry per set of modes
            result = lemma_cache.combined(ordered, dim, calculi[0]) if len(modes) > 1 else {"holds": True}
            checks[f"zero_current_{dim}d"] = result["holds"] is True
            if len(modes) > 1 and not result["holds"]:
                details[f"zero_current_{dim}d"] = f"the current of {'+'.join(modes)} is not the sum of the modes' currents"
            for a, b in itertools.combinations(modes, 2):
                details[f"coupling {a}-{b} {dim}d"] = coupling(a, b, dim)
    return ContactReport(modes, calculi[0] if calculi else "", checks, details, reports, time.perf_counter() - start)
