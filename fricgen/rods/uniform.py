"""The uniform rod fluids in closed form, the limits the exact theory (fricgen.rods.theory) must reach far
from any field: Tonks's hard rods and Baxter's sticky rods (the paper's B section on sticky rods; Eq. 30
for the stickiness gamma). Units: lengths in sigma's, densities per length, energies in kT."""

import numpy as np


def tonks(mean_density: float, sigma: float) -> tuple[float, float]:
    """βP = ρ̄/(1 − ρ̄σ) and βμ_ch of the uniform hard-rod fluid (Tonks).

    Parameters
    ----------
    mean_density : float
        The mean density ρ̄ [1/lambda].
    sigma : float
        The rod length σ [lambda], ρ̄σ < 1.

    Returns
    -------
    tuple of float
        (βP [1/lambda], βμ_ch [1]).
    """
    packing = mean_density * sigma
    return mean_density / (1 - packing), float(np.log(mean_density / (1 - packing)) + packing / (1 - packing))


def sticky_rods(mean_density: float, sigma: float, gamma: float) -> tuple[float, float]:
    """(βP, βμ_ch) of Baxter's uniform sticky rods: βP (1 + γβP) = ρ̄/(1 − ρ̄σ),
    βμ_ch = βPσ + ln[βP/(1 + γβP)] (isobaric partition function).

    Parameters
    ----------
    mean_density : float
        The mean density ρ̄ [1/lambda].
    sigma : float
        The rod length σ [lambda], ρ̄σ < 1.
    gamma : float
        The stickiness γ [lambda].

    Returns
    -------
    tuple of float
        (βP [1/lambda], βμ_ch [1]).
    """
    a = mean_density / (1 - mean_density * sigma)
    pressure = (np.sqrt(1 + 4 * gamma * a) - 1) / (2 * gamma) if gamma > 0 else a
    return float(pressure), float(pressure * sigma + np.log(pressure / (1 + gamma * pressure)))
