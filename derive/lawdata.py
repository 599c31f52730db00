"""Law files as plain data, without SymPy: reading and the source hash.

The runtime's kernel loader uses this module to detect stale kernels (a law file edited after its
kernels were generated) without importing SymPy, so it must stay free of SymPy imports.
"""

from __future__ import annotations

import hashlib
import json
import tomllib
from pathlib import Path

#: Version of the code generator; part of every source hash, bump when emitted code changes.
GENERATOR_VERSION = 1

CATALOGUE = Path(__file__).with_name("catalogue")

#: The stochastic calculi a law file may list (theta = 0, 1/2, 1).
CALCULI = ("ito", "stratonovich", "hk")


class LawFileError(ValueError):
    """A law file that cannot be read."""


def read_law_data(path: str | Path) -> dict:
    """The TOML table of a law file."""
    path = Path(path)
    try:
        return tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as error:
        raise LawFileError(f"{path}: not valid TOML: {error}") from error
    except FileNotFoundError as error:
        raise LawFileError(f"{path}: no such law file") from error


def source_hash(data: dict) -> str:
    """sha256 of a law's data (canonical JSON) and the generator version."""
    canonical = json.dumps({"law": data, "generator": GENERATOR_VERSION}, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(canonical.encode()).hexdigest()
