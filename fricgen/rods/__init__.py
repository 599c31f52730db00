"""The rods engine: Brownian cluster dynamics of hard and sticky rods in external fields, with the
exact equilibrium theory to test it against (Antonov et al. 2022; docs/physics.md#brownian-cluster-dynamics).

Public API::

    from fricgen.rods import RodSimulation, deviations, exact_profile, rod_config

    config = rod_config(n=40, length=100.0, sigma=0.5, U0=6.0, dt=1e-5, replicas=16)
    simulation = RodSimulation(config)  # Monte Carlo equilibrium start
    simulation.equilibrate(0.25)  # BCD forms its contact layer
    print(deviations(simulation.run(50_000), exact_profile(config)))

Modules: ``config`` (RodModel, RodNumerics, RodSampling in a RodConfig), ``interactions`` (field and
neighbour force kernels), ``bcd`` (the compiled step), ``contact`` (its O(dt) contact layers), ``sticky``
(Baxter's limit eps = 0 as a sticky boundary), ``mc`` (Monte Carlo start), ``simulation``
(replicas and profiles), ``stability`` (the time step against the schemes' range), ``theory`` (exact
transfer-operator profiles), ``comparison``. Imports only
the kernel layer, the RNG and fricgen.schema/errors: never SymPy, the Langevin engine or the
command line.
"""

import fricgen.compiled  # noqa: F401  (first: sets Numba up before anything imports it)

# isort: split

from ..lazy import on_first_use
from .comparison import deviations, exact_profile
from .config import RodConfig, RodModel, RodNumerics, RodSampling, rod_config
from .interactions import best_exponent, field_energy, field_kernels, pair_kernels, stability_ratio, sticky_force_max
from .neighbours import HARD_RODS, Neighbours
from .residuals import percus_residual, sticky_residual
from .theory import RodProfile, rod_profile
from .uniform import sticky_rods, tonks

__all__ = [
    "HARD_RODS",
    "Neighbours",
    "RodConfig",
    "RodModel",
    "RodNumerics",
    "RodProfile",
    "RodProfiles",
    "RodSampling",
    "RodSimulation",
    "best_exponent",
    "deviations",
    "exact_profile",
    "extrapolate_to_zero_dt",
    "field_energy",
    "field_kernels",
    "pair_kernels",
    "percus_residual",
    "rod_config",
    "rod_profile",
    "stability_ratio",
    "sticky_force_max",
    "sticky_residual",
    "sticky_rods",
    "tonks",
]

#: The names of ``simulation``, loaded on first use: it compiles the BCD engine (about 40 s on a cold cache), which the
#: command line's rod flags (read from ``config``) and the Langevin commands do not need.
__getattr__, __dir__ = on_first_use(__name__, {".simulation": ("RodProfiles", "RodSimulation", "extrapolate_to_zero_dt")})
