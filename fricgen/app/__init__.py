"""The application layer: the ``fricgen`` command line and what it runs for a user, grouped by what
a user does: ``cli`` (the command line), ``run`` (one run of a TOML file), ``sweep`` (a grid of runs)
and ``studies`` (the demo, the thermostat check, Poiseuille flow, viscosity, MIPS, BCD rods). The
groups import downwards, cli -> sweep -> run <- studies; the runner finds the studies of its kinds
of run in ``run.registry``, which importing ``studies`` fills. It uses both engines; neither engine
imports it.
"""

from . import studies  # noqa: F401 (fills the registry of studies before any run)
from .run.config import RunConfig, load_config, resolve_source
from .run.runner import execute, plan
from .studies.demo import run_demo
from .studies.thermostat_check import passive_check, passive_run, thermostat_check

__all__ = ["RunConfig", "execute", "load_config", "passive_check", "passive_run", "plan", "resolve_source", "run_demo", "thermostat_check"]
