"""A Langevin simulation of frictional spheres: configuration, validation, and the run loop.

The contact law's kernels come from ``generated/`` through the loader; the scheme is the one of
the calculus its noise amplitude D was derived for (Itô: Euler–Maruyama, Stratonovich: stochastic
Heun, HK: end point). Another scheme is refused unless ``force_scheme`` is set (a wrong thermostat:
for negative controls only).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from derive.lawdata import CALCULI

from . import langevin
from .kernels import load_law_kernels, load_potential
from .system import Particles, State

SCHEMES = {"ito": langevin.ITO, "stratonovich": langevin.STRATONOVICH, "hk": langevin.HK}


class SimulationError(RuntimeError):
    """A run that blew up; the state and the files hold the last good step."""


@dataclass(frozen=True)
class LangevinConfig:
    """What to simulate. Solvent: gamma, gamma_rot (F-39, 40; the paper's 3 pi and pi). Contact:
    ``law`` with ``parameters`` overrides, noise amplitude of ``calculus``, integrated by ``scheme``
    (default: the calculus' own). ``contact_noise=False`` drops the frictional noise (the
    inconsistent model); ``friction=False`` drops the contact friction entirely."""

    law: str = "coulomb_newton"
    calculus: str = "ito"
    scheme: str | None = None
    force_scheme: bool = False
    parameters: dict[str, float] = field(default_factory=dict)
    kT: float = 1.0
    dt: float = 1e-3
    gamma: float = 3 * math.pi
    gamma_rot: float = math.pi
    friction: bool = True
    contact_noise: bool = True
    active_force: float = 0.0
    bulk_force: tuple[float, float, float] = (0.0, 0.0, 0.0)
    potential: str = "wca"
    epsilon: float = 1.0
    seed: int = 1
    skin: float = 0.3
    overlap_limit: float = 0.6

    def __post_init__(self):
        if self.calculus not in CALCULI:
            raise ValueError(f"calculus must be one of {CALCULI}, got {self.calculus!r}")
        scheme = self.scheme or self.calculus
        if scheme not in SCHEMES:
            raise ValueError(f"scheme must be one of {tuple(SCHEMES)}, got {scheme!r}")
        if scheme != self.calculus and not self.force_scheme:
            raise ValueError(
                f"the noise amplitude D of the {self.calculus} calculus needs the {self.calculus} scheme, not {scheme}: "
                "this pairing is not a consistent thermostat (set force_scheme=True only for a negative control)"
            )
        for name in ("kT", "dt", "skin"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} must be positive, got {getattr(self, name)}")
        for name in ("gamma", "gamma_rot", "epsilon"):
            if not getattr(self, name) >= 0:
                raise ValueError(f"{name} must be >= 0, got {getattr(self, name)}")
        if self.seed < 0:
            raise ValueError("seed must be >= 0")


class Simulation:
    """Runs a configuration on a state (in place); ``run`` calls observers between chunks."""

    def __init__(self, config: LangevinConfig, particles: Particles, state: State):
        self.config, self.particles, self.state = config, particles, state
        self.kernels = load_law_kernels(config.law)
        self.kernels.contact(config.calculus)  # raises for a calculus the law does not have
        params = dict(config.parameters)
        if params.get("sigma", 1.0) != 1.0:
            raise ValueError("the law parameter sigma is set by the particle radii (sigma_ik = R_i + R_k): set the radii instead")
        if "sigma" in self.kernels.parameter_names:
            params["sigma"] = 1.0  # the engine scales distances by sigma_ik = R_i + R_k
        if "epsilon" in self.kernels.parameter_names:
            params.setdefault("epsilon", config.epsilon)
        self.law_params = self.kernels.parameters(**params)
        self.potential = load_potential(config.potential)
        self.pot_params = np.array([config.epsilon, 1.0])
        self.neighbor_builds = 0
        if state.dim == 2 and (state.position[:, 2].any() or config.bulk_force[2]):
            raise ValueError("2-D states have z = 0 and no bulk force along z")

    @property
    def scheme(self) -> str:
        return self.config.scheme or self.config.calculus

    def advance(self, steps: int) -> None:
        """Advance by ``steps`` compiled steps; raises SimulationError if the run blows up."""
        c, p, s = self.config, self.particles, self.state
        status, done, builds = langevin.advance(
            s.position,
            s.velocity,
            s.omega,
            s.orientation,
            p.radius,
            p.inv_mass,
            p.inv_inertia,
            s.box,
            s.dim,
            steps,
            s.step,
            c.dt,
            c.kT,
            c.gamma,
            c.gamma_rot,
            c.active_force,
            np.array(c.bulk_force, dtype=float),
            c.seed,
            SCHEMES[self.scheme],
            c.friction,
            c.contact_noise,
            self.potential.force,
            self.pot_params,
            self.kernels.contact(c.calculus),
            self.kernels.module.weight if self.kernels.has_weight else langevin.no_weight,
            self.law_params,
            self.kernels.has_weight,
            c.skin,
            c.overlap_limit,
        )
        s.step += done
        self.neighbor_builds += builds
        if status == langevin.NOT_FINITE:
            raise SimulationError(
                f"velocities became infinite or NaN at step {s.step} (t = {s.step * c.dt:g}): dt = {c.dt:g} is too large for "
                "the forces or the friction stiffness (the contact mode relaxes at rate mu f/u; keep mu (f/u) dt well below 1)"
            )
        if status == langevin.OVERLAP:
            raise SimulationError(
                f"particles overlap (r < {c.overlap_limit} sigma) at step {s.step} (t = {s.step * c.dt:g}): the system exploded; "
                "reduce dt or start from a configuration without overlaps"
            )

    def run(self, steps: int, every: int = 1000, observers: list[Callable[[Simulation], None]] = ()) -> None:
        """Advance ``steps`` steps in chunks of ``every``, calling each observer after each chunk."""
        if steps < 0 or every <= 0:
            raise ValueError("steps must be >= 0 and every > 0")
        done = 0
        while done < steps:
            chunk = min(every, steps - done)
            self.advance(chunk)
            done += chunk
            for observe in observers:
                observe(self)
