"""The automated statistical test of a law's thermostat: a passive system at kT, measured.

Runs N spheres (2-D area fraction 0.6 or 3-D volume fraction 0.3 by default, the paper's passive
check) with WCA, the paper's solvent (gamma = 3 pi, gamma_R = pi; or none) and the law's friction
with (or without) its noise, then fits T_eff of translation and rotation (block errors) and the KL
divergence (F-41) of velocity and angular velocity components. Passed when both temperatures equal
kT within ``z_limit`` standard errors and both KL divergences are below ``kl_limit``.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass

from .analysis import Sampler, block_estimate, kl_divergence
from .simulation import LangevinConfig, Simulation
from .system import Particles, lattice_state


@dataclass(frozen=True)
class CheckResult:
    law: str
    calculus: str
    scheme: str
    dim: int
    contact_noise: bool
    T_trans: float
    T_trans_err: float
    T_rot: float
    T_rot_err: float
    kl_trans: float
    kl_rot: float
    passed: bool
    steps: int
    seconds: float

    def as_dict(self) -> dict:
        return asdict(self)


def passive_run(
    law: str,
    dim: int = 2,
    calculus: str = "ito",
    contact_noise: bool = True,
    n: int | None = None,
    phi: float | None = None,
    dt: float = 1e-3,
    total_time: float = 40.0,
    seed: int = 1,
    parameters: dict[str, float] | None = None,
    solvent: bool = True,
    scheme: str | None = None,
    force_scheme: bool = False,
    kT: float = 1.0,
    z_limit: float = 4.0,
    kl_limit: float = 2e-3,
    every: int | None = None,
    observers: Sequence[Callable[[Simulation], None]] = (),
) -> tuple[CheckResult, Sampler]:
    """Run the passive check; return its result and the sampler (velocity and spin samples).

    ``observers`` are called after every chunk of the equilibration and of the sampling."""
    start = time.perf_counter()
    n = n or (256 if dim == 2 else 216)
    phi = phi or (0.6 if dim == 2 else 0.3)
    particles = Particles.spheres(n)
    state = lattice_state(particles, dim, phi, kT=kT, seed=seed)
    config = LangevinConfig(
        law=law,
        calculus=calculus,
        scheme=scheme,
        force_scheme=force_scheme,
        parameters=parameters or {},
        kT=kT,
        dt=dt,
        gamma=3 * math.pi if solvent else 0.0,
        gamma_rot=math.pi if solvent else 0.0,
        contact_noise=contact_noise,
        seed=seed,
    )
    simulation = Simulation(config, particles, state)
    steps = int(round(total_time / dt))
    every = every or max(1, int(round(0.05 / dt)))
    simulation.run(steps // 10, every=steps // 10 or 1, observers=observers)  # equilibration from the lattice start
    sampler = Sampler(particles)
    simulation.run(steps - steps // 10, every=every, observers=[sampler, *observers])
    trans, rot = block_estimate(sampler.trans), block_estimate(sampler.rot)
    kl_trans, kl_rot = kl_divergence(sampler.scaled_velocities()), kl_divergence(sampler.scaled_spins())
    passed = (
        abs(trans.mean - kT) <= z_limit * trans.error
        and abs(rot.mean - kT) <= z_limit * rot.error
        and kl_trans < kl_limit
        and kl_rot < kl_limit
    )
    result = CheckResult(
        law,
        calculus,
        simulation.scheme,
        dim,
        contact_noise,
        trans.mean,
        trans.error,
        rot.mean,
        rot.error,
        kl_trans,
        kl_rot,
        bool(passed),
        steps,
        time.perf_counter() - start,
    )
    return result, sampler


def thermostat_check(law: str, **options) -> CheckResult:
    """Run the passive check (options as in :func:`passive_run`) and return temperatures, errors,
    KL divergences and the verdict."""
    return passive_run(law, **options)[0]
