"""What every command does with its outputs: check the folder before anything runs, write valid JSON,
report an error on one line.

:func:`check_folder` finds an output folder that cannot be written (a file in the way, no
permission, a read-only file system) before a simulation starts, not after it; it creates nothing.
:func:`dumps` writes JSON as RFC 8259 defines it: a number that is not finite (a chi^2 over a zero
error, say) becomes null, never ``NaN`` or ``Infinity``. :func:`fail` prints ``prog: error``.
"""

from __future__ import annotations

import json
import math
import os
import stat
import sys
import tempfile
from pathlib import Path

from ...errors import ConfigError

#: The files of a run's folder that are not tables (fricgen.app.run.runner writes them).
CHECKPOINT, TRAJECTORY, SUMMARY, CONFIG = "checkpoint.npz", "trajectory.gsd", "summary.json", "config.json"


def check_folder(folder: Path, key: str) -> None:
    """``folder`` is a writable folder or can be created as one; ConfigError at ``key`` (a flag such
    as ``--out``) otherwise. Nothing is created: an unnamed file is opened and dropped in the nearest
    folder that exists, the one the command will write into or create its folder in."""
    try:
        target = Path(folder).absolute()
        if target.exists() and not target.is_dir():
            raise ConfigError(key, f"{folder} is a file, not a folder", "give a folder")
        existing = target
        while not existing.exists():
            existing = existing.parent
        if not existing.is_dir():
            raise ConfigError(key, f"cannot create {folder}: {existing} is a file, not a folder", "give another folder")
        if not os.access(existing, os.W_OK | os.X_OK):
            raise ConfigError(key, f"cannot write into {existing}: permission denied", "give a folder you can write into")
        with tempfile.TemporaryFile(dir=existing):
            pass
    except OSError as error:
        raise ConfigError(key, f"cannot write into {folder}: {error.strerror or error}", "give a folder you can write into") from error


#: The temporary files a run writes and renames into place (a checkpoint, the summary, a truncated trajectory).
TEMPORARIES = (f"{CHECKPOINT}.tmp", f".{SUMMARY}.tmp", f"{TRAJECTORY}.tmp")


def check_temporaries(folder: Path, key: str) -> None:
    """No temporary file of a run (:data:`TEMPORARIES`) in ``folder`` is anything but a regular file:
    a folder there would end the run in an error after its last step, a symbolic link would have the
    run write through it into another file. ConfigError at ``key`` otherwise, before anything runs."""
    for name in TEMPORARIES:
        try:
            mode = os.lstat(Path(folder) / name).st_mode
        except FileNotFoundError:
            continue
        except OSError as error:
            raise ConfigError(key, f"cannot read {Path(folder) / name}: {error.strerror or error}", "give another folder") from error
        if not stat.S_ISREG(mode):
            kind = "a symbolic link" if stat.S_ISLNK(mode) else "a folder" if stat.S_ISDIR(mode) else "not a regular file"
            raise ConfigError(key, f"{Path(folder) / name} is {kind}, in the way of a file the run writes there", "move it away")


def finite(data):
    """``data`` with every float that is not finite replaced by None (in dicts, lists and tuples)."""
    if isinstance(data, float):
        return data if math.isfinite(data) else None
    if isinstance(data, dict):
        return {key: finite(value) for key, value in data.items()}
    if isinstance(data, list | tuple):
        return [finite(value) for value in data]
    return data


def dumps(data) -> str:
    """Valid JSON of ``data`` (indented), with null for numbers that are not finite."""
    return json.dumps(finite(data), indent=2, allow_nan=False)


def fail(prog: str, error: Exception | str, status: int) -> int:
    """Print ``prog: error`` on one line of stderr and return the exit status ``status``."""
    print(f"{prog}: {' '.join(str(error).split())}", file=sys.stderr)
    return status
