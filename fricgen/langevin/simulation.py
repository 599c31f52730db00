"""A Langevin simulation of frictional spheres: a configuration on a state, advanced in chunks.

The contact law's kernels come from the loader (fricgen.kernels), handed in or looked up by name; the contact is integrated in
the calculus its noise amplitude D was derived for, pairwise or explicitly (fricgen.langevin.config.Law).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import NamedTuple

import numba
import numpy as np

from ..errors import ConfigError, SimulationError
from ..kernels import LawKernels, load_law_kernels, load_potential, no_weight
from . import integrator
from .config import LangevinConfig
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


#: Most contact mobilities that a simulation tabulates an integral-form D for (one table each).
TABLES = 4


def pair_mobilities(particles: Particles, limit: int = TABLES) -> np.ndarray:
    """The contact mobilities mu = 1/m_i + 1/m_k + R_i^2/I_i + R_k^2/I_k of pairs (i, k) of the most common kinds of
    particle (mass, radius, inertia), bit for bit as fricgen.langevin.contact_step.find_contacts computes them, at most
    ``limit``: the law module's tabulate_<c> builds a noise table for each (fricgen.derive.backends.tables); a pair of
    other kinds is evaluated by quadrature."""
    kinds, counts = np.unique(np.stack([particles.inv_mass, particles.radius, particles.inv_inertia], axis=1), axis=0, return_counts=True)
    kinds = kinds[np.argsort(-counts, kind="stable")]
    found: list[float] = []
    for top in range(len(kinds)):
        for i, k in ((j, top) for j in range(top + 1)):
            for (mi, ri, ii), (mk, rk, ik) in ((kinds[i], kinds[k]), (kinds[k], kinds[i])):  # (i, k) and (k, i): sums in another order
                mu = float(mi + mk + ri**2 * ii + rk**2 * ik)
                if mu > 0.0 and mu not in found and len(found) < limit:
                    found.append(mu)
    return np.array(found)


class Simulation:
    """Runs a configuration on a state (in place); ``run`` calls observers between chunks.

    ``threads``: None (the default) measures 1 thread against all that numba may use as the run goes
    and takes the faster (fricgen.langevin.threads); a number fixes it. Results do not depend on it.
    ``neighbor_list``: the engine's Verlet list, handed back in at each call and rebuilt by the engine
    when it no longer holds for the state (fricgen.langevin.neighbors.still_valid), so a state
    changed between calls is safe.

    ``law``: the law's kernels, resolved once by the caller (:func:`fricgen.load_law`, for a law of a
    folder of one's own); by default ``config.law.name`` is looked up when the simulation is created
    (FRICGEN_LAWS's folders, then the built-in catalogue)."""

    threads: int | None = None

    def __init__(self, config: LangevinConfig, particles: Particles, state: State, law: LawKernels | None = None):
        self.config, self.particles, self.state = config, particles, state
        law, self.kernels = config.law, law if law is not None else load_law_kernels(config.law.name)
        if self.kernels.name != law.name:
            handed = f"is {law.name!r}, but the kernels handed to the simulation are those of {self.kernels.name!r}"
            raise ConfigError("law.name", handed, "give one law")
        self.contact = self.kernels.contact(law.calculus)  # raises for a calculus the law does not have
        fixed = {"sigma": 1.0, "epsilon": config.epsilon}  # the engine scales distances by sigma_ik = R_i + R_k
        params = dict(law.parameters) | {name: value for name, value in fixed.items() if name in self.kernels.parameter_names}
        self.potential = load_potential(config.potential)
        values = self.kernels.parameters(**params)
        tabulate = getattr(self.kernels.module, f"tabulate_{law.calculus}", None)  # noise tables of an integral-form D
        if tabulate is not None:
            values = tabulate(pair_mobilities(particles), config.thermostat.kT, values)
        self.couplings = Couplings(np.array([config.epsilon, 1.0]), values, self.kernels.has_weight)
        self.neighbor_list, self.neighbor_builds = NeighborList.unbuilt(), 0  # the list is kept while valid
        self.tally = ContactTally(0, 0, 0.0)
        self.thread_choice = ThreadChoice(numba.get_num_threads())
        if state.dim == 2 and (state.position[:, 2].any() or config.bulk.vector[2]):
            raise ConfigError("bulk.force", "2-D states have z = 0 and no bulk force along z", "give [Fx, Fy]")

    @property
    def scheme(self) -> str:
        """The calculus whose scheme integrates the contact."""
        return self.config.law.integrator.value

    def step_kernels(self) -> tuple:
        """The kernels of the compiled engine, (force, contact, slope, weight) as records.KERNELS."""
        weight = self.kernels.module.weight if self.kernels.has_weight else no_weight
        return self.potential.force, self.contact, self.kernels.friction_slope, weight

    def dynamics(self) -> Dynamics:
        """The step parameters of the compiled engine."""
        c, s, t = self.config, self.state, self.config.thermostat
        inv_box = np.array([1.0 / s.box[a] if a < s.dim else 0.0 for a in range(3)])
        return Dynamics(s.box, inv_box, np.array(c.bulk.vector, dtype=float), s.dim, t.dt, t.kT, t.gamma, t.gamma_rot, c.active.force,
                        c.seed, c.law.integrator.index, c.law.friction, c.law.contact_noise, c.law.contact_scheme == "pairwise",
                        c.skin, c.overlap_limit, numba.get_num_threads())  # fmt: skip

    def advance(self, steps: int) -> None:
        """Advance by ``steps`` compiled steps; raises SimulationError if the run blows up."""
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
        """Advance ``steps`` steps in chunks of ``every``, calling each observer after each chunk."""
        if steps < 0 or every <= 0:
            raise ConfigError("steps", f"must be >= 0 with chunks every > 0, got steps = {steps}, every = {every}", "fix the call")
        done = 0
        while done < steps:
            chunk = min(every, steps - done)
            self.advance(chunk)
            done += chunk
            for observe in observers:
                observe(self)
