"""A checkpoint file checked in full before anything uses it (``fricgen run --resume``, a sweep's
point, ``[system] initial``).

:func:`check_checkpoint` reads the ``.npz`` without unpickling anything and refuses, as one
ConfigError naming the key, a file that is no zip archive, lacks an array, holds an array of the
wrong kind or shape (a truncated or reshaped one), a number that is not finite (NaN or inf
positions, velocities, spins, orientations, radii, masses, box), a negative step, a dimension other
than 2 or 3, or a configuration that is not a JSON table with a ``law`` table. What it cannot see,
whether the checkpoint continues *this* configuration (every field of the model, the particles, the
box, the walls' spheres), the runner checks against a fresh build
(fricgen.app.run.runner._check_resume).
"""

from __future__ import annotations

import json
import zipfile
from pathlib import Path

import numpy as np

from ...errors import ConfigError

#: The arrays of a checkpoint (fricgen.langevin.trajectory.save_checkpoint): name -> (kind, shape);
#: ``n`` stands for the number of particles, ``()`` for a scalar.
ARRAYS = {
    "position": ("f", ("n", 3)),
    "velocity": ("f", ("n", 3)),
    "omega": ("f", ("n", 3)),
    "orientation": ("f", ("n", 4)),
    "box": ("f", (3,)),
    "dim": ("iu", ()),
    "step": ("iu", ()),
    "radius": ("f", ("n",)),
    "mass": ("f", ("n",)),
    "inertia": ("f", ("n",)),
    "mobile": ("b", ("n",)),
    "config": ("U", ()),
}


def check_checkpoint(path: Path, key: str = "--resume") -> None:
    """``path`` is a whole, finite checkpoint of fricgen run; ConfigError at ``key`` otherwise.

    Args:
        path: the ``.npz`` file.
        key: the flag or key that named it (``--resume``, ``system.initial``).

    Raises:
        ConfigError: one line naming the file, the array and what is wrong with it.
    """

    def refuse(problem: str) -> ConfigError:
        return ConfigError(key, f"the checkpoint {path} {problem}", "give a checkpoint.npz written by fricgen run, or start a new run")

    unreadable = f"cannot read the checkpoint {path}:"
    try:
        if not zipfile.is_zipfile(path):
            raise ConfigError(key, f"{unreadable} not an .npz archive", "give a checkpoint.npz written by fricgen run")
        with np.load(Path(path), allow_pickle=False) as data:
            missing = [name for name in ARRAYS if name not in data.files]
            if missing:
                raise refuse(f"lacks {', '.join(missing)}")
            arrays = {name: data[name] for name in ARRAYS}
    except ConfigError:
        raise
    except (OSError, ValueError, EOFError, zipfile.BadZipFile, zipfile.LargeZipFile) as error:
        raise ConfigError(
            key, f"{unreadable} {' '.join(str(error).split()) or type(error).__name__}", "give a checkpoint.npz written by fricgen run"
        ) from error
    n = arrays["radius"].shape[0] if arrays["radius"].ndim == 1 else -1
    for name, (kinds, shape) in ARRAYS.items():
        array, wanted = arrays[name], tuple(n if size == "n" else size for size in shape)
        if array.dtype.kind not in kinds or array.shape != wanted:
            raise refuse(f"holds {name} of {array.dtype} {array.shape}, not of shape {wanted}")
        if kinds == "f" and not np.all(np.isfinite(array)):
            raise refuse(f"holds {name} that is not finite (NaN or inf)")
    if n < 1:
        raise refuse("holds no particles")
    if int(arrays["dim"]) not in (2, 3):
        raise refuse(f"has dimension {int(arrays['dim'])}, not 2 or 3")
    if int(arrays["step"]) < 0:
        raise refuse(f"is at a negative step, {int(arrays['step'])}")
    if np.any(arrays["radius"] <= 0) or np.any(arrays["mass"] <= 0) or np.any(arrays["box"][: int(arrays["dim"])] <= 0):
        raise refuse("holds a radius, a mass or a box length that is not positive")
    try:
        config = json.loads(str(arrays["config"]))
    except ValueError as error:
        raise refuse("holds a configuration that is not JSON") from error
    if not isinstance(config, dict) or not isinstance(config.get("law"), dict):
        raise refuse("holds a configuration that is not a table with a law table")


def recorded_laws(path: Path) -> list[list[str]] | None:
    """The laws a checkpoint ran, ``[[name, source hash], ...]`` in the order of ``[law]`` (``name``,
    then ``rolling`` and ``spinning`` where given: fricgen.langevin.trajectory.save_checkpoint records
    them), or None where it records none (no checkpoint, not one of fricgen run, or written before
    the hashes were recorded). A sweep's point is finished with this run's laws only if they match."""
    try:
        with np.load(Path(path), allow_pickle=False) as data:
            if "law_hash" not in data.files:
                return None
            name = json.loads(str(data["config"]))["law"]["name"]
            modes = json.loads(str(data["mode_laws"])) if "mode_laws" in data.files else []
            return [[str(name), str(data["law_hash"])], *([str(mode), str(digest)] for mode, _, digest in modes)]
    except (OSError, ValueError, KeyError, TypeError, EOFError, zipfile.BadZipFile):
        return None
