"""The application layer: the ``fricgen`` command line and what it runs for a user.

Modules: ``cli`` (the commands), ``arguments`` (one-line parser errors, negative numbers as
values, errors named by flags), ``outputs`` (output folders checked before a run, valid JSON),
``config`` (``fricgen run`` files: the engine's sections plus system, walls, run, output),
``build`` (a validated file to a simulation at step 0), ``runner`` (outputs, progress, Ctrl-C,
resume), ``observables`` (CSV tables), ``demo`` and ``plots`` (the main job), ``progress``,
``noise`` (``fricgen noise``), ``rods_study`` (``fricgen bcd``), ``examples/`` (bundled configurations).
It uses both engines; neither engine imports it.
"""

from .config import RunConfig, load_config, resolve_source
from .demo import run_demo
from .runner import execute, plan

__all__ = ["RunConfig", "execute", "load_config", "plan", "resolve_source", "run_demo"]
