"""The symbolic layer's error family (derive never imports the runtime, so it has its own base).

The command line prints these, as fricgen's own errors, on one line; ``exit_status`` is 2 for bad
input (a law file that cannot be read or used) and 1 for a law that fails its proof.
"""

from __future__ import annotations


class DeriveError(Exception):
    """Base of the symbolic layer's errors."""

    exit_status = 2
