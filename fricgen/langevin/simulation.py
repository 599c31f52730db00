"""A Langevin simulation of frictional spheres: a configuration on a state, advanced in chunks.

The contact law comes resolved (:mod:`fricgen.langevin.contact_law`: kernels, never a name); the contact is integrated
in the calculus its noise amplitude D was derived for, pairwise or explicitly (fricgen.langevin.config.Law).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from typing import NamedTuple

import numba
import numpy as np

from ..accuracy import check_noise
from ..errors import ConfigError, SimulationError
from ..kernels import LawKernels, load_potential, no_weight
from . import integrator
from .config import LangevinConfig
from .contact_law import ContactLaw, ModeLaw, bind, law_names
from .mobility import mode_mobilities
from .records import Bodies, Couplings, Dynamics, Motion, NeighborList
from .system import Particles, State
from .threads import ThreadChoice


class ContactTally(NamedTuple):
    """The pairwise contact step's proposals, its rejections, and the sum of the proposals' rejection
    probabilities 1 - min(1, alpha), since the simulation was created."""

    proposals: int
    rejections: int
    rejection_sum: float

    @property
    def rejection_rate(self) -> float | None:
        """The mean rejection probability of a proposal (the expected fraction rejected; less noisy than
        rejections / proposals), None without proposals."""
        return self.rejection_sum / self.proposals if self.proposals else None


class Simulation:
    """Runs a configuration on a state, in place: frictional spheres with thermal contact noise.

    Each step integrates the thermostat (F-39, 40), the pair potential, the active and bulk forces
    and, per contact, the friction f(u) and its random force sqrt(D) with D of the law's calculus
    (docs/physics.md). Results do not depend on the thread count.

    Parameters
    ----------
    config : LangevinConfig
        The configuration.
    particles : Particles
        The particles.
    state : State
        The initial state; advanced in place (``simulation.state``).
    law : ContactLaw or LawKernels or sequence of LawKernels
        The resolved contact law: a :class:`~fricgen.langevin.contact_law.ContactLaw`, or the kernels
        of ``config.law.name`` (:func:`fricgen.load_law`), or a sequence of them for ``name``,
        ``rolling`` and ``spinning`` (those given, in this order), checked here against
        ``config.law`` (:func:`~fricgen.langevin.contact_law.bind`). Never a name: the engine looks
        nothing up.

    Attributes
    ----------
    threads : int or None
        None (the default) measures 1 thread against all that numba may use as the run goes and
        takes the faster; a number fixes it.

    Raises
    ------
    ConfigError
        For a law that does not fit ``config.law`` or the dimension, or a 2-D state with z != 0.

    Examples
    --------
    >>> import fricgen
    >>> from fricgen.langevin import LangevinConfig, Particles, Simulation, lattice_state, temperatures
    >>> particles = Particles.spheres(16)
    >>> state = lattice_state(particles, dim=2, fraction=0.3, seed=1)
    >>> simulation = Simulation(LangevinConfig(), particles, state, law=fricgen.load_law("coulomb_newton"))
    >>> simulation.run(200, every=100)
    >>> simulation.state.step, [round(t, 2) for t in temperatures(simulation.state, particles)]
    (200, [0.57, 1.0])
    """

    threads: int | None = None

    def __init__(self, config: LangevinConfig, particles: Particles, state: State, law: ContactLaw | LawKernels | Sequence[LawKernels]):
        self.config, self.particles, self.state = config, particles, state
        self.law = _contact_law(config, law, state.dim)
        first = self.law.first
        self.kernels = first.kernels
        self.contact = self.kernels.contact(self.law.calculus)
        self.potential = load_potential(config.potential)
        extra = {mode: self.law.modes.get(mode) for mode in ("rolling", "spinning")}
        laws = {mode: (self._values(found, mode) if found else np.zeros(0)) for mode, found in extra.items()}
        sliding = self.kernels.mode == "sliding"
        self.couplings = Couplings(
            potential=np.array([config.epsilon, 1.0]),
            law=self._values(first, self.kernels.mode),
            has_weight=self.kernels.has_weight and sliding,
            sliding=sliding,
            rolling=extra["rolling"] is not None,
            spinning=extra["spinning"] is not None,
            rolling_law=laws["rolling"],
            spinning_law=laws["spinning"],
            rolling_weight=bool(extra["rolling"] and extra["rolling"].kernels.has_weight),
            spinning_weight=bool(extra["spinning"] and extra["spinning"].kernels.has_weight),
            rolling_noise=config.law.rolling_noise,
            spinning_noise=config.law.spinning_noise,
        )
        self.neighbor_list, self.neighbor_builds = NeighborList.unbuilt(), 0  # the list is kept while valid
        self.tally = ContactTally(0, 0, 0.0)
        self.thread_choice = ThreadChoice(numba.get_num_threads())
        if state.dim == 2 and (state.position[:, 2].any() or config.bulk.vector[2]):
            raise ConfigError("bulk.force", "2-D states have z = 0 and no bulk force along z", "give [Fx, Fy]")

    def _values(self, law: ModeLaw, mode: str) -> np.ndarray:
        """A law's parameter values for the engine: its overrides, sigma and epsilon where the law has them, the
        noise tables of an integral-form D for the mode's most common mobilities."""
        kernels = law.kernels
        fixed = {"sigma": 1.0, "epsilon": self.config.epsilon}  # the engine scales distances by sigma_ik = R_i + R_k
        engine = {name: value for name, value in fixed.items() if name in kernels.parameter_names}
        values = kernels.parameters(**(dict(law.parameters) | engine))
        tabulate = getattr(kernels.module, f"tabulate_{self.law.calculus}", None)  # noise tables of an integral-form D
        if tabulate is not None:
            values = tabulate(mode_mobilities(self.particles, mode), self.config.thermostat.kT, values)
        c = self.config.law
        if c.friction and c.contact_noise and getattr(c, f"{mode}_noise", True):  # D at the run's values (docs/trust-model.md)
            check_noise(kernels, str(c.calculus), values, mode_mobilities(self.particles, mode), self.config.thermostat.kT)
        return values

    def mode_kernels(self) -> tuple:
        """The rolling and spinning laws' kernels, as the compiled engine takes them.

        Returns
        -------
        tuple
            (contact, slope, weight) of each mode as records.MODE_KERNELS; the sliding law's where a mode
            has no law (the couplings say which act).
        """
        calculus, modes, out = self.law.calculus, self.law.modes, []
        for mode in ("rolling", "spinning"):
            kernels = modes[mode].kernels if mode in modes else self.kernels
            out += [kernels.contact(calculus), kernels.friction_slope, kernels.module.weight if kernels.has_weight else no_weight]
        return tuple(out)

    @property
    def scheme(self) -> str:
        """The calculus whose scheme integrates the contact."""
        return self.config.law.integrator.value

    def step_kernels(self) -> tuple:
        """The kernels of the compiled engine.

        Returns
        -------
        tuple
            (force, contact, slope, weight) as records.KERNELS.
        """
        weight = self.kernels.module.weight if self.kernels.has_weight else no_weight
        return self.potential.force, self.contact, self.kernels.friction_slope, weight

    def dynamics(self) -> Dynamics:
        """The step parameters of the compiled engine.

        Returns
        -------
        Dynamics
            Box, dt [t0], kT, gamma, gamma_rot, forces, seed, scheme and numerics of this run.
        """
        c, s, t = self.config, self.state, self.config.thermostat
        inv_box = np.array([1.0 / s.box[a] if a < s.dim else 0.0 for a in range(3)])
        return Dynamics(
            box=s.box,
            inv_box=inv_box,
            bulk=np.array(c.bulk.vector, dtype=float),
            dims=s.dim,
            dt=t.dt,
            kT=t.kT,
            gamma=t.gamma,
            gamma_rot=t.gamma_rot,
            active=c.active.force,
            seed=c.seed,
            scheme=c.law.integrator.index,
            friction=c.law.friction,
            noise=c.law.contact_noise,
            pairwise=c.law.contact_scheme == "pairwise",
            skin=c.skin,
            overlap_limit=c.overlap_limit,
            threads=numba.get_num_threads(),
        )

    def advance(self, steps: int) -> None:
        """Advance by compiled steps.

        Parameters
        ----------
        steps : int
            The number of steps of ``config.thermostat.dt``.

        Raises
        ------
        SimulationError
            If the run blows up (particles overlap).
        """
        before = numba.get_num_threads()
        try:
            if self.threads is not None:
                numba.set_num_threads(self.threads)
                self._advance(steps)
            while self.threads is None and steps > 0:
                threads = self.thread_choice.next()
                chunk = self.thread_choice.steps(threads, steps)
                numba.set_num_threads(threads)
                start = time.perf_counter()
                self._advance(chunk)
                self.thread_choice.record(threads, chunk, time.perf_counter() - start)
                steps -= chunk
        finally:
            numba.set_num_threads(before)

    def _advance(self, steps: int) -> None:
        c, p, s = self.config, self.particles, self.state
        status, done, builds, *tally, self.neighbor_list = integrator.advance(
            Motion(s.position, s.velocity, s.omega, s.orientation),
            Bodies(p.radius, p.inv_mass, p.inv_inertia),
            self.dynamics(),
            self.couplings,
            self.step_kernels(),
            self.mode_kernels(),
            self.neighbor_list,
            s.step,
            steps,
        )
        s.step += done
        self.neighbor_builds += builds
        self.tally = ContactTally(*(total + part for total, part in zip(self.tally, tally)))
        dt = c.thermostat.dt
        if status == integrator.NOT_FINITE:
            raise SimulationError(
                f"velocities became infinite or NaN at step {s.step} (t = {s.step * dt:g}): dt = {dt:g} is too large for "
                "the forces or the friction stiffness (the contact mode relaxes at rate mu f/u; keep mu (f/u) dt well below 1)"
            )
        if status == integrator.OVERLAP:
            raise SimulationError(
                f"particles overlap (r < {c.overlap_limit} sigma) at step {s.step} (t = {s.step * dt:g}): the system exploded; "
                "reduce dt or start from a configuration without overlaps"
            )

    def run(self, steps: int, every: int = 1000, observers: list[Callable[[Simulation], None]] = ()) -> None:
        """Advance in chunks, calling each observer after each chunk.

        Parameters
        ----------
        steps : int
            The number of steps (time steps * dt [t0]).
        every : int
            The chunk length in steps.
        observers : sequence of callable
            Each called as ``observer(simulation)`` after each chunk (e.g. :class:`Sampler`, :class:`GSDWriter`).

        Raises
        ------
        SimulationError
            If the run blows up.
        """
        if steps < 0 or every <= 0:
            raise ConfigError("steps", f"must be >= 0 with chunks every > 0, got steps = {steps}, every = {every}", "fix the call")
        done = 0
        while done < steps:
            chunk = min(every, steps - done)
            self.advance(chunk)
            done += chunk
            for observe in observers:
                observe(self)


def _contact_law(config: LangevinConfig, law: object, dim: int) -> ContactLaw:
    """The simulation's contact law: ``law`` as it is when it was resolved for ``config.law`` (the same
    names and calculus), else bound from kernels; TypeError, on one line, for anything else (a name)."""
    if isinstance(law, ContactLaw):
        names = law_names(config.law)
        if law.names != names or law.calculus != config.law.calculus:
            given = f"the contact law handed to the simulation is {law.names} ({law.calculus}), not {names} ({config.law.calculus})"
            raise ConfigError("law", given, "resolve it for this configuration")
        return law
    kernels = [law] if isinstance(law, LawKernels) else list(law) if isinstance(law, Sequence) and not isinstance(law, str) else None
    if not kernels or not all(isinstance(k, LawKernels) for k in kernels):
        raise TypeError(
            f"Simulation's law must be the resolved law (fricgen.load_law(name), or a ContactLaw), not {law!r}: the engine looks no name up"
        )
    return bind(config.law, kernels, dim)
