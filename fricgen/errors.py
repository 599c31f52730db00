"""One family of errors for everything a user can get wrong or a run can hit.

Every error that fricgen raises on purpose derives from :class:`FricgenError`; the command line
catches this family only and prints its message on one line (exit status 2 for bad input, 1 for a
physical failure such as a blow-up). Anything else is a bug and keeps its traceback.
"""

from __future__ import annotations


class FricgenError(Exception):
    """Base of fricgen's own errors; ``exit_status`` is what the command line exits with."""

    exit_status = 2


class ConfigError(FricgenError, ValueError):
    """A configuration or argument that cannot run: names the key, the problem and the fix."""

    def __init__(self, key: str, problem: str, fix: str = ""):
        self.key, self.problem, self.fix = key, problem, fix
        super().__init__(f"{key}: {problem}" + (f"; {fix}" if fix else ""))


class KernelError(FricgenError, LookupError):
    """Generated kernels missing or stale, or asked for a calculus or parameter the law lacks."""


class SimulationError(FricgenError, RuntimeError):
    """A run that failed physically (blew up, overlapped, jammed); the state holds the last good step."""

    exit_status = 1
