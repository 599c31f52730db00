"""The automated statistical test of a law's thermostat: a passive system at kT, measured.

Runs N spheres (2-D area fraction 0.6 or 3-D volume fraction 0.3 by default, the paper's passive
check) with WCA, the paper's solvent (gamma = 3 pi, gamma_R = pi; or none) and the law's friction
with (or without) its noise, then fits T_eff of translation and rotation (block errors) and the KL
divergence (F-41) of velocity and angular velocity components. Passed when both temperatures equal
kT within ``z_limit`` standard errors and both KL divergences are below ``kl_limit``. The pairwise
contact step keeps kT at any dt and for any D; it reports its rejection rate instead, which vanishes
like dt^1.5 for the right D (more slowly where f has a kink: dt^1.3 for coulomb_newton) and like
dt^0.5 for a wrong one. A wrong D shows in the temperatures of the explicit kick
(``contact_scheme = "explicit"``; docs/physics.md#the-pairwise-contact-step).
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING

from ... import langevin
from ...kernels import LawKernels, load_law
from ...langevin.analysis import Sampler, block_estimate, kl_divergence
from ...langevin.config import LangevinConfig, Law, Thermostat
from ...langevin.contact_law import ContactLaw
from ...langevin.system import CLOSE_PACKING, Particles, cubic_side, interaction_reach, lattice_limit, lattice_state, memory_estimate
from ...schema import Section

if TYPE_CHECKING:  # the engine loads when a check runs (langevin.Simulation), not for the command line's flags
    from ...langevin.simulation import Simulation

#: Spheres and packing fraction of the check when not given, per dimension (the paper's passive check).
DEFAULT_N, DEFAULT_PHI = {2: 256, 3: 216}, {2: 0.6, 3: 0.3}
#: The spheres of the check: radius and mass (I = 2/5 m R^2).
RADIUS, MASS = 0.5, 1.0
#: Blocks of the temperatures' standard errors (two samples per block at least).
BLOCKS = 20


@dataclass(frozen=True)
class PassiveCheck(Section):
    """The set-up of a check: ``law`` and ``thermostat`` sections, dimension ``dim``, ``n`` spheres
    (default 256 in 2-D, 216 in 3-D; at least 2, in a box wider than twice the interaction range, and
    within the machine's memory) at packing fraction ``phi`` (default 0.6 / 0.3; below close packing
    and the lattice start's limit, see fricgen.langevin.system.lattice_limit), ``total_time``
    in t0 (the first 10 % equilibrate from a lattice), noise ``seed``, the verdict's ``z_limit``
    (standard errors) and ``kl_limit``, and a sample every ``every`` steps (default 0.05 t0)."""

    law: Law
    thermostat: Thermostat = field(default_factory=Thermostat)
    dim: int = 2
    n: int | None = None
    phi: float | None = None
    total_time: float = 40.0
    seed: int = 1
    z_limit: float = 4.0
    kl_limit: float = 2e-3
    every: int | None = None

    def __post_init__(self):
        self.require(self.dim in (2, 3), "dim", f"must be 2 or 3, got {self.dim}", "give 2 or 3")
        self.require(self.n is None or self.n >= 2, "n", f"needs at least 2 spheres, got {self.n}", "give n >= 2")
        self.require(self.phi is None or 0 < self.phi < 1, "phi", f"must be in (0, 1), got {self.phi}", "give a packing fraction")
        self.require_positive("total_time", "z_limit", "kl_limit")
        self.require(self.every is None or self.every >= 1, "every", f"must be >= 1, got {self.every}", "give the steps between samples")
        self.require_steps("total_time", self.total_time / self.thermostat.dt)
        self.require(self.steps >= 20, "total_time", f"{self.total_time} t0 is under 20 steps of dt", "give a longer time")
        samples, needed = (self.steps - self.steps // 10) // self.sample_period, 2 * BLOCKS
        self.require(
            samples >= needed,
            "total_time",
            f"{self.total_time:g} t0 gives {samples} samples, under the {needed} that {BLOCKS} error blocks need",
            f"give at least {math.ceil(needed * self.sample_period * self.thermostat.dt / 0.9 * 1.01 * 100) / 100:g}",
        )
        n, phi, dim = self.size, self.fraction, self.dim
        densest, lattice = CLOSE_PACKING[dim], lattice_limit(n, dim)
        self.require(phi < densest, "phi", f"{phi:g} is impossible: close packing is {densest:.4f} in {dim}-D", "give a smaller value")
        self.require(
            phi < lattice,
            "phi",
            f"{phi:g} is too dense for the lattice start of {n} spheres (at most {lattice:.4f} in {dim}-D)",
            "give a smaller value",
        )
        side = cubic_side(n, RADIUS, dim, phi)
        config = self.langevin()  # checks the seed
        self.require_memory("n", memory_estimate(n, (side,) * dim, RADIUS, config.skin), f"{n} spheres")
        smallest = 2 * interaction_reach(RADIUS, config.skin)
        self.require(
            side > smallest,
            "n",
            f"{n} spheres at packing fraction {phi:g} fill a box of side {side:.3g}, under twice the interaction range ({smallest:.3g})",
            f"give n >= {math.floor(n * (smallest / side) ** dim) + 1}",
        )

    @property
    def steps(self) -> int:
        return int(round(self.total_time / self.thermostat.dt))

    @property
    def sample_period(self) -> int:
        """Steps between samples: ``every``, else 0.05 t0."""
        return self.every or max(1, int(round(0.05 / self.thermostat.dt)))

    @property
    def size(self) -> int:
        """The number of spheres (``n``, or the default of the dimension)."""
        return DEFAULT_N[self.dim] if self.n is None else self.n

    @property
    def fraction(self) -> float:
        """The packing fraction (``phi``, or the default of the dimension)."""
        return DEFAULT_PHI[self.dim] if self.phi is None else self.phi

    def langevin(self) -> LangevinConfig:
        """The engine's configuration of the check."""
        return LangevinConfig(law=self.law, thermostat=self.thermostat, seed=self.seed)


def passive_check(law: str, solvent: bool = True, **options) -> PassiveCheck:
    """The set-up of a thermostat check from flat options.

    Parameters
    ----------
    law : str
        The law's name.
    solvent : bool
        False sets gamma = gamma_R = 0 (the friction thermostat alone).
    **options
        The fields of PassiveCheck (``dim``, ``n``, ``phi``, ``total_time`` [t0], ``seed``, ...), of Law
        (calculus, contact_noise, parameters, scheme, force_scheme, contact_scheme) and of Thermostat
        (kT [kT], dt [t0]).

    Returns
    -------
    PassiveCheck
        The checked set-up.
    """
    sections = {Law: {"name": law}, Thermostat: {} if solvent else {"gamma": 0.0, "gamma_rot": 0.0}}
    for section, values in sections.items():
        names = {f.name for f in dataclasses.fields(section)}
        values.update({key: options.pop(key) for key in list(options) if key in names})
    return PassiveCheck(Law(**sections[Law]), Thermostat(**sections[Thermostat]), **options)


@dataclass(frozen=True)
class CheckResult:
    law: str
    calculus: str
    scheme: str
    contact_scheme: str
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
    rejection_rate: float | None  # the pairwise contact step's mean rejection probability (None: explicit, no noise or no friction)
    rolling: str | None = None  # the rolling and spinning laws, if any, and whether their noise acted
    spinning: str | None = None
    rolling_noise: bool = True
    spinning_noise: bool = True

    @property
    def laws(self) -> str:
        """The laws of the check, by mode: "coulomb_newton + rolling_linear (rolling, no noise)"."""
        named = [self.law]
        for mode in ("rolling", "spinning"):
            if getattr(self, mode) is not None:
                named.append(f"{getattr(self, mode)} ({mode}{'' if getattr(self, f'{mode}_noise') else ', no noise'})")
        return " + ".join(named)

    def as_dict(self) -> dict:
        return asdict(self)


def passive_run(
    check: PassiveCheck, law: ContactLaw | LawKernels | Sequence[LawKernels], observers: Sequence[Callable[[Simulation], None]] = ()
) -> tuple[CheckResult, Sampler]:
    """Run a passive check: equilibrate, then sample the temperatures and velocity distributions.

    Parameters
    ----------
    check : PassiveCheck
        The set-up (:func:`passive_check`).
    law : ContactLaw or LawKernels or sequence of LawKernels
        The resolved law of ``check.law``, as :class:`~fricgen.langevin.Simulation` takes it
        (:func:`fricgen.load_law`'s kernels, or the edge's ContactLaw).
    observers : sequence of callable
        Called after every chunk of the equilibration and of the sampling.

    Returns
    -------
    tuple of (CheckResult, Sampler)
        The result (as :func:`thermostat_check`'s) and the sampler with the velocity and spin samples.
    """
    start = time.perf_counter()
    kT, dim = check.thermostat.kT, check.dim
    particles = Particles.spheres(check.size, RADIUS, MASS)
    state = lattice_state(particles, dim, check.fraction, kT=kT, seed=check.seed)
    simulation = langevin.Simulation(check.langevin(), particles, state, law)
    steps = check.steps
    every = check.sample_period
    # equilibration from the lattice start, in chunks of the sampling period: Ctrl-C stops between two
    simulation.run(steps // 10, every=min(every, steps // 10) or 1, observers=observers)
    sampler = Sampler(particles)
    simulation.run(steps - steps // 10, every=every, observers=[sampler, *observers])
    trans, rot = block_estimate(sampler.trans, BLOCKS), block_estimate(sampler.rot, BLOCKS)
    kl_trans, kl_rot = kl_divergence(sampler.scaled_velocities()), kl_divergence(sampler.scaled_spins())
    passed = (
        abs(trans.mean - kT) <= check.z_limit * trans.error
        and abs(rot.mean - kT) <= check.z_limit * rot.error
        and kl_trans < check.kl_limit
        and kl_rot < check.kl_limit
    )
    result = CheckResult(
        check.law.name,
        check.law.calculus,
        simulation.scheme,
        check.law.contact_scheme,
        dim,
        check.law.contact_noise,
        trans.mean,
        trans.error,
        rot.mean,
        rot.error,
        kl_trans,
        kl_rot,
        bool(passed),
        steps,
        time.perf_counter() - start,
        simulation.tally.rejection_rate,
        check.law.rolling,
        check.law.spinning,
        check.law.rolling_noise,
        check.law.spinning_noise,
    )
    return result, sampler


def thermostat_check(law: str | LawKernels, **options) -> CheckResult:
    """Run the passive check: a fluid of frictional spheres at kT, started on a lattice; the
    temperatures of translation and rotation must be kT within ``z_limit`` standard errors and the
    KL divergences (F-41) below ``kl_limit``.

    Parameters
    ----------
    law : str | LawKernels
        The law's kernels (:func:`fricgen.load_law`, for a law of one's own folder), or its name,
        which is resolved here as :func:`fricgen.load_law` resolves it (FRICGEN_LAWS's folders,
        then the built-in catalogue).
    **options
        Flat options as in :func:`passive_check`: ``dim``, ``n``, ``phi``, ``total_time``
        [t0], ``seed``, ``calculus``, ``contact_noise``, ``contact_scheme``, ``parameters``,
        ``kT``, ``dt``, ``solvent``, ...

    Returns
    -------
    CheckResult
        T_trans, T_rot [kT] with their block errors, the KL divergences, the verdict ``passed``
        and, for the pairwise contact step, its rejection rate.
    """
    kernels = law if isinstance(law, LawKernels) else load_law(law)
    return passive_run(passive_check(kernels.name, **options), kernels)[0]
