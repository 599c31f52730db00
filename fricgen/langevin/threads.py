"""How many threads the engine uses: measured as it runs, since a busy machine changes the answer.

The engine's results do not depend on the thread count or on how a run is cut into chunks
(docs/physics.md#counter-based-noise), so the count can change between chunks at no cost to the
physics. :class:`ThreadChoice` runs chunks of about ``CHUNK_SECONDS`` on one thread and on all
threads the process may use, keeps the faster, and measures the other again after ``PROBE_EVERY``
chunks, twice as many each time it is still the slower (at most ``PROBE_MOST``). On a quiet
machine a large system takes all threads; a small one, or any system while another process
competes for the cores (where threads that wait at the step's barriers for a descheduled partner
cost more than they give), runs on one.
"""

from __future__ import annotations

import math

#: Wall time of one measured chunk (s); chunks between measurements of the slower thread count. Each
#: chunk is a call into the engine, which costs a force pass beyond its steps (1.4 ms at N = 10^4, 2-D):
#: 0.4 s chunks measured 0.97-0.99 of one thread beside a busy process, 0.1 s chunks 0.96-0.98.
CHUNK_SECONDS, PROBE_EVERY, PROBE_MOST = 0.4, 4, 64


class ThreadChoice:
    """Chooses between 1 and ``most`` threads from measured rates (steps per second)."""

    def __init__(self, most: int):
        self.candidates = (1, most) if most > 1 else (1,)
        self.rates: dict[int, float] = {}
        self.interval, self.waited = PROBE_EVERY, 0

    def best(self) -> int:
        return max(self.candidates, key=lambda n: self.rates.get(n, math.inf))

    def next(self) -> int:
        """The thread count of the next chunk: each candidate once, then the fastest, the other after ``interval`` chunks."""
        unmeasured = [n for n in self.candidates if n not in self.rates]
        if unmeasured:
            return unmeasured[0]
        self.waited += 1
        if len(self.candidates) > 1 and self.waited > self.interval:
            self.waited = 0
            return min(self.candidates, key=lambda n: self.rates[n])
        return self.best()

    def steps(self, threads: int, left: int) -> int:
        """Steps of the next chunk: about CHUNK_SECONDS at the rate measured so far (10 before any measurement)."""
        rate = self.rates.get(threads) or max(self.rates.values(), default=0.0)
        return min(left, max(10, math.ceil(rate * CHUNK_SECONDS)) if rate else 10)

    def record(self, threads: int, steps: int, seconds: float) -> None:
        """A measured chunk; a probe that finds the slower count still slower doubles the interval."""
        if seconds <= 0:
            return
        probe = threads != self.best() and threads in self.rates
        self.rates[threads] = steps / seconds
        if probe:
            self.interval = PROBE_EVERY if self.best() == threads else min(2 * self.interval, PROBE_MOST)
