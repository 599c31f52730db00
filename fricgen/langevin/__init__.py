"""The Langevin engine: frictional spheres with thermal contact noise, in 2-D and 3-D.

Public API::

    from fricgen.langevin import LangevinConfig, Law, Thermostat, Particles, Simulation, lattice_state

    particles = Particles.spheres(256)
    state = lattice_state(particles, dim=2, fraction=0.6, seed=1)
    config = LangevinConfig(law=Law("coulomb_newton", calculus="ito"), thermostat=Thermostat(dt=1e-3), seed=1)
    law = fricgen.load_law("coulomb_newton")  # resolved once: the engine takes kernels, never a name
    Simulation(config, particles, state, law).run(20_000, every=100, observers=[Sampler(particles)])

Modules: ``config`` (what to simulate), ``system`` (particles, states, initial configurations,
walls), ``contact_law`` (a ``[law]`` section's kernels, checked once), ``simulation`` (the run
loop), ``integrator``, ``pairs``, ``neighbors`` and ``records`` (the compiled step), ``analysis``
(T_eff, histograms, KL), ``trajectory`` (GSD, checkpoints), ``mobility`` (the contact mobilities of the kinds of
particle); the
statistical test of a law's thermostat is a study, fricgen.app.thermostat_check. Imports only the
kernel layer, the RNG, fricgen.schema/errors and fricgen.derive.calculus: never SymPy, the rods
engine or the application.
"""

import fricgen.compiled  # noqa: F401  (first: sets Numba up before anything imports it)

# isort: split

from ..lazy import on_first_use
from .analysis import Estimate, Sampler, block_estimate, kl_divergence, maxwell_boltzmann, scaled_components, temperatures, velocity_profile
from .config import Active, Bulk, LangevinConfig, Law, Thermostat
from .system import Particles, State, add_slab_walls, lattice_state, packing_box, thermal_state

__all__ = [
    "Active",
    "Bulk",
    "Estimate",
    "GSDWriter",
    "LangevinConfig",
    "Law",
    "Particles",
    "Sampler",
    "Simulation",
    "State",
    "Thermostat",
    "add_slab_walls",
    "block_estimate",
    "kl_divergence",
    "lattice_state",
    "checkpoint_config",
    "load_checkpoint",
    "maxwell_boltzmann",
    "packing_box",
    "save_checkpoint",
    "scaled_components",
    "temperatures",
    "thermal_state",
    "velocity_profile",
]

#: The run loop and what reads and writes its runs, loaded on first use: ``simulation`` compiles the engine (about
#: 200 s on a cold cache on 2 cores), which the configuration, the particles and the analysis do not need.
__getattr__, __dir__ = on_first_use(
    __name__, {".simulation": ("Simulation",), ".trajectory": ("GSDWriter", "checkpoint_config", "load_checkpoint", "save_checkpoint")}
)
