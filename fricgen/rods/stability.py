"""Whether a time step lies within the range of BCD's schemes: a ratio per scale, refused beyond its limit
by ``fricgen bcd``, warned about near it (units as in fricgen.rods: lambda = 1, D = 1, kT = 1).

* the field's Euler step, r_U = mu max|U''| dt: the drift step multiplies a rod's offset from a well's
  bottom by 1 - mu U'' dt. Beyond r_U = 1 it overshoots the bottom (beyond 2 it diverges); its bias is
  about -r_U / 4 of the contact density (c - 1 = -30 dt at U0 = 6, where r_U = 118 dt;
  docs/physics-bcd-contact-layer.md).
* the neighbour force, r_f = mu max|f| dt / a of (B-33), a its range (eps for the sticky contact): beyond
  1 a step jumps across the whole well.
* the sticky boundary (eps = 0), r_b = sqrt(4 D dt) / gamma: a bond breaks with probability 0.8 r_b per step
  (fricgen.rods.sticky); from 1 the step is too long for the stickiness (a bond would not last one step).
* the hard core, r_g = sqrt(4 D dt) / (L / N - sigma): the rms change of a gap per step against the free
  room per rod; beyond 1 every step pushes chains of rods around the ring (a warning only: the contact
  layers keep the hard core at any step).
"""

from __future__ import annotations

import math
import warnings
from typing import NamedTuple

import numpy as np

from ..errors import ConfigError
from .config import RodModel
from .interactions import field_kernels, stability_ratio

#: Grid points per wavelength on which max |U''| is taken (central differences of the force).
FIELD_POINTS = 4096


class StepRatio(NamedTuple):
    """One scale's ratio, the value above which a run is warned about and the one from which it is refused
    (inf: never)."""

    name: str
    value: float
    warn: float
    refuse: float
    meaning: str
    power: float = 1.0  # the ratio grows as dt^power

    def text(self) -> str:
        return f"{self.name} = {self.value:.3g} ({self.meaning})"


def field_ratio(model: RodModel, dt: float) -> float:
    """r_U = mu max|U''| dt over one wavelength, dimensionless."""
    module, params = field_kernels(model)
    h = model.wavelength / FIELD_POINTS
    x = np.arange(FIELD_POINTS + 2) * h - h
    force = np.empty_like(x)
    module.force_field(x, params, force)
    return float(model.mu * np.max(np.abs(force[2:] - force[:-2])) / (2 * h) * dt)


def step_ratios(model: RodModel, dt: float) -> list[StepRatio]:
    """The four ratios of the module docstring for ``model`` at time step ``dt``."""
    free = model.length / model.n - model.sigma if not model.open_line else math.inf
    spread = math.sqrt(4 * model.diffusion * dt)
    return [
        StepRatio("mu max|U''| dt", field_ratio(model, dt), 0.2, 1.0, "the field's Euler step: at 1 it overshoots a well's bottom"),
        StepRatio("mu max|f| dt / a", stability_ratio(model, dt), 0.1, 1.0, "B-33: at 1 a step crosses the neighbour force's range a"),
        StepRatio(
            "sqrt(4 D dt) / gamma",
            spread / model.gamma if model.sticky_boundary else 0.0,
            0.5,
            1.0,
            "the sticky boundary: at 1 a bond breaks in most steps",
            0.5,
        ),  # fmt: skip
        StepRatio("sqrt(4 D dt) / (L/N - sigma)", spread / free, 1.0, math.inf, "a gap's step over the room", 0.5),
    ]


def refuse_step(model: RodModel, dt: float) -> None:
    """ConfigError at numerics.dt if a ratio is at or beyond its limit, naming the largest dt within range."""
    for ratio in step_ratios(model, dt):
        if not ratio.value < ratio.refuse:
            largest = dt * (ratio.refuse / ratio.value) ** (1 / ratio.power) if math.isfinite(ratio.value) else 0.0
            raise ConfigError(
                "numerics.dt",
                f"dt = {dt:g} is beyond the scheme's range: {ratio.text()}; nothing was run",
                f"give dt below {largest:.2g}" if largest > 0 else "change the model",
            )


def warn_step(model: RodModel, dt: float, tested: bool = False) -> None:
    """A warning (one line) for each ratio above its warning level; tested: each step passes a Metropolis test
    (drift_scheme "metropolis"), which keeps the profile exact and rejects more steps instead."""
    effect = "the Metropolis test rejects many steps (the profile stays exact, the rods move less)" if tested else "the profile is biased"
    for ratio in step_ratios(model, dt):
        if ratio.value > ratio.warn:
            what = f"{ratio.name} = {ratio.value:.3g} is not << 1 at dt = {dt:g} ({ratio.meaning})"
            warnings.warn(f"{what}: {effect}; reduce dt", stacklevel=3)
