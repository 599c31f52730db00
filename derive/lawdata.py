"""Law files as plain data, without SymPy: reading, and the source hashes of laws and potentials.

The runtime's kernel loader uses this module to detect stale kernels (a law file or
derive/potentials.py edited after the kernels were generated) without importing SymPy, so it must
stay free of SymPy imports: a potential's hash is taken over the bytes of derive/potentials.py (a
file read, not an import).
"""

from __future__ import annotations

import hashlib
import json
import tomllib
from pathlib import Path

from .errors import DeriveError

#: Version of the code generator; part of every source hash, bump when emitted code changes.
GENERATOR_VERSION = 1

CATALOGUE = Path(__file__).with_name("catalogue")
#: The source of the potentials (derive.potentials), hashed as bytes by potential_source_hash.
POTENTIALS = Path(__file__).with_name("potentials.py")


class LawFileError(DeriveError, ValueError):
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


def potential_source_hash(name: str, source: Path | bytes | None = None) -> str:
    """sha256 of the exact bytes of derive/potentials.py, the potential's name and the generator version.

    ``source``: the text of the potentials module as bytes, or the path of a file holding it;
    :data:`POTENTIALS` by default (looked up at call time). Any edit of the file, even a comment,
    makes every potential's kernels stale: without SymPy the expressions cannot be compared. Line
    ends are normalized to LF (a checkout with CRLF ends is not stale).
    """
    text = source if isinstance(source, bytes) else Path(POTENTIALS if source is None else source).read_bytes()
    digest = hashlib.sha256(text.replace(b"\r\n", b"\n"))
    digest.update(f"\0potential={name}\0generator={GENERATOR_VERSION}".encode())
    return digest.hexdigest()


def weight_potential(data: dict) -> str | None:
    """The potential a law's weight may name (w = -dU/dr): the weight if it is a bare name, else None.

    A bare name that is an expression (``weight = "r"``) counts too: its law's hash then covers
    derive/potentials.py needlessly, which costs a regeneration, never a stale kernel.
    """
    weight = data.get("weight")
    return weight if isinstance(weight, str) and weight.isidentifier() else None


def source_hash(data: dict, potentials: Path | bytes | None = None) -> str:
    """sha256 of a law's data (canonical JSON), the generator version and, when its weight names a
    potential, that potential's source hash (``potentials`` as in :func:`potential_source_hash`)."""
    content = {"law": data, "generator": GENERATOR_VERSION}
    weight = weight_potential(data)
    if weight is not None:
        content["weight"] = potential_source_hash(weight, potentials)
    canonical = json.dumps(content, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(canonical.encode()).hexdigest()
