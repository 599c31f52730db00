"""The studies that analyse a run, by the kind of run (:attr:`~fricgen.app.run.config.RunConfig.kinds`).

The runner imports no study: it looks up each kind of its run in :data:`STUDIES`, adds the study's
entry to summary.json and its lines to the report. The package :mod:`fricgen.app.studies` fills the
registry when it is imported (``fricgen.app`` imports it, so any import of the application does).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from .config import RunConfig

if TYPE_CHECKING:  # the engine compiles on import: the registry, filled at any import of fricgen.app, needs its name only
    from ...langevin.simulation import Simulation


@dataclass(frozen=True)
class Study:
    """What a study adds to a run of its kind: the entry ``key`` of summary.json, made by
    ``summarize(config, simulation, folder, summary)`` from the final state, the output folder and the
    summary so far (None: nothing to add; it may write figures into the folder), and ``describe(entry)``,
    the entry's lines in the report of ``fricgen run``."""

    key: str
    summarize: Callable[[RunConfig, Simulation, Path, dict], dict | None]
    describe: Callable[[dict], list[str]]


#: The study of each kind of run, filled by fricgen.app.studies.
STUDIES: dict[str, Study] = {}
