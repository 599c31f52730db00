"""The command line ``fricgen``: ``commands`` (the parser, main and the commands), ``arguments``,
``laws`` (law folders, ``verify``, ``generate``), ``noise`` and ``lammps``."""

from .commands import main

__all__ = ["main"]
