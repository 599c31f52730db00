"""Long runs: a progress bar over simulation steps and a clean stop on Ctrl-C.

Both are observers for :meth:`fricgen.langevin.Simulation.run`, so they act between chunks: the
compiled steps are never interrupted, and a stop leaves every writer at the same step.
"""

from __future__ import annotations

import signal
import sys

from tqdm import tqdm

from ...langevin.simulation import Simulation


class ProgressBar:
    """A tqdm bar (steps done, rate in steps/s, ETA) standing at ``offset + simulation.state.step``.

    ``offset`` counts the steps of earlier simulations that share the bar (the demo's two runs);
    ``initial`` is where a resumed run starts, so its rate counts only the new steps.
    """

    def __init__(self, total: int, description: str = "", initial: int = 0):
        self.offset = 0
        self.bar = tqdm(total=total, initial=initial, desc=description, unit="step", unit_scale=True, file=sys.stderr, dynamic_ncols=True)

    def __call__(self, simulation: Simulation) -> None:
        self.bar.update(self.offset + simulation.state.step - self.bar.n)

    def describe(self, description: str) -> None:
        self.bar.set_description(description)

    def close(self) -> None:
        self.bar.close()


class RunInterrupted(Exception):
    """Raised by :class:`StopOnInterrupt` at the first chunk boundary after SIGINT."""


class StopOnInterrupt:
    """While active (a context), the first SIGINT (Ctrl-C) only sets a flag, and this observer
    raises :class:`RunInterrupted` after the chunk in which it arrived; place it after the writers.
    A second SIGINT aborts at once (KeyboardInterrupt)."""

    def __init__(self):
        self.requested = False
        self._previous = None

    def _handle(self, signum, frame) -> None:
        self.requested = True
        signal.signal(signal.SIGINT, signal.default_int_handler)
        print("\nfricgen: stopping at the next chunk boundary (Ctrl-C again to abort at once)", file=sys.stderr, flush=True)

    def __enter__(self) -> StopOnInterrupt:
        self._previous = signal.signal(signal.SIGINT, self._handle)
        return self

    def __exit__(self, *exc) -> None:
        signal.signal(signal.SIGINT, self._previous)

    def __call__(self, simulation: Simulation) -> None:
        if self.requested:
            raise RunInterrupted(f"interrupted at step {simulation.state.step}")
