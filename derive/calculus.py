"""The stochastic calculus of the contact noise: the one type that derive, the engines and the
command line share (no SymPy here, so the runtime can import it).

The calculus fixes the point theta of the step at which the noise amplitude is evaluated:
theta = 0 (Itô), 1/2 (Stratonovich), 1 (Hänggi–Klimontovich); it enters D through
nu = (1 - theta) mu (docs/physics.md#contact-mobility-and-the-calculus) and decides the matching
integrator of the contact step (Euler–Maruyama, stochastic Heun, end point).
"""

from __future__ import annotations

from enum import StrEnum
from fractions import Fraction


class Calculus(StrEnum):
    """A stochastic calculus; its value is the name used in law files, configurations and flags."""

    ITO = "ito"
    STRATONOVICH = "stratonovich"
    HK = "hk"

    @property
    def theta(self) -> Fraction:
        """Evaluation point of the noise amplitude within a step (0, 1/2, 1)."""
        return {"ito": Fraction(0), "stratonovich": Fraction(1, 2), "hk": Fraction(1)}[self.value]

    @property
    def index(self) -> int:
        """The integer the compiled engines use for this calculus' scheme (0, 1, 2)."""
        return list(Calculus).index(self)


#: The names of the calculi, in order (a law's default list).
CALCULI: tuple[str, ...] = tuple(c.value for c in Calculus)


def velocity_verlet_refusal(calculus: str) -> str:
    """Why a pair force of velocity Verlet (LAMMPS) cannot integrate the noise of ``calculus``; "" for Itô.

    Velocity Verlet evaluates the pair force once per step, at the half-kicked start-of-step
    velocities: Euler–Maruyama, the Itô scheme. Stratonovich (Heun) and HK (end point) need a second
    evaluation with the same normals."""
    if calculus == Calculus.ITO:
        return ""
    return (
        f"calculus {calculus!r}: the LAMMPS pair style integrates the contact noise with velocity Verlet, which evaluates the "
        "pair force once per step at the start-of-step (half-kicked) velocities: that is Euler–Maruyama, consistent with the "
        "Itô amplitude only; Stratonovich (Heun) and HK (end point) need a second force evaluation with the same normals. "
        "Use --calculus ito (or fricgen's own engine for the other calculi)"
    )
