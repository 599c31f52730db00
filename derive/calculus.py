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
