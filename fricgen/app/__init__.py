"""The application layer: the ``fricgen`` command line and what it runs for a user, grouped by what
a user does: ``cli`` (the command line), ``run`` (one run of a TOML file), ``sweep`` (a grid of runs)
and ``studies`` (the demo, the thermostat check, Poiseuille flow, viscosity, MIPS, BCD rods). The
groups import downwards, cli -> sweep -> run <- studies; the runner finds the studies of its kinds
of run in ``run.registry``, which importing ``studies`` fills. It uses both engines; neither engine
imports it. What runs an engine (the runner, the demo, the thermostat check) loads on first use, so
that a command which runs none (``fricgen noise``, ``lammps``, ``generate``, ``bcd``) compiles no
Langevin engine.
"""

from ..lazy import on_first_use
from . import studies  # noqa: F401 (fills the registry of studies before any run)
from .run.config import RunConfig, load_config, resolve_source

__all__ = ["RunConfig", "execute", "load_config", "passive_check", "passive_run", "plan", "resolve_source", "run_demo", "thermostat_check"]

__getattr__, __dir__ = on_first_use(
    __name__,
    {
        ".run.runner": ("execute", "plan"),
        ".studies.demo": ("run_demo",),
        ".studies.thermostat_check": ("passive_check", "passive_run", "thermostat_check"),
    },
)
