"""On-disk cache of the law-independent facts of :mod:`fricgen.derive.noise.mode_proofs`.

Proving the zero-current lemma of a mode and calculus on the pair phase space takes up to 40 s and
does not depend on the law (D and f are arbitrary there), so every ``verify``/``generate`` process
would otherwise prove it again. The facts (booleans, and the rational nu/mu that the lemma reads off
the current) are stored as small JSON files in a user cache folder:

- ``$FRICGEN_CACHE`` if set (``off`` disables the cache: every process proves again),
- else ``$XDG_CACHE_HOME/fricgen``, else ``~/.cache/fricgen``.

One entry per fact, named by what it is about, for every mode alike (sliding is one of three):

- ``zero_current_<mode>_<dim>d_<calculus>``: :func:`lemma`, the lemma holds with nu/mu = 1 - theta;
- ``facts_<mode>_<dim>d``: :func:`facts`, exactly the facts of :func:`.mode_proofs.mode_facts`, each true;
- ``combined_<modes>_<dim>d_<calculus>`` (modes joined by ``+`` in the order given): :func:`combined`,
  the current of the sum holds, with nu/mu = 1 - theta for every mode.

The file of an entry is ``<name>-<key>.json``, its key (:func:`cache_key`) a hash of the sources the
proofs depend on (:data:`SOURCES`), the generator version (fricgen.derive.law.lawdata.GENERATOR_VERSION)
and the SymPy version. No law enters a key: the facts hold for every f and D. An entry is written
atomically (a temporary file renamed into place), and only for a fact that the proof established (a
refuted fact is proven again next time).

The cache is an optimisation, never a source of truth: an entry is used only if it is a regular file
(opened without blocking: a FIFO, a folder or a device in its place is a miss, never waited on), of
at most :data:`MAX_ENTRY` bytes, whose ``sha256`` (over its own key, name and facts, canonical JSON)
holds, with this key and name, and whose facts are what a proof establishes. Anything else (damaged,
foreign, a negative or vacuous fact such as an empty set of facts or an nu/mu of another calculus)
is ignored: the fact is proven again and the entry rewritten. A folder that cannot be written is not
an error: the fact is just not kept. No code is ever evaluated from the cache (a rational is parsed
by ``fractions.Fraction``).
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
from fractions import Fraction
from functools import cache
from pathlib import Path

import sympy as sp

from ..calculus import Calculus
from ..law import manifests, symbols
from ..law.lawdata import GENERATOR_VERSION, read_regular
from . import mode_proofs, modes, phase_space
from .mode_proofs import FACTS, Lemma

CACHE_ENV = manifests.CACHE_ENV
#: The sources whose bytes key the cache (besides the generator and SymPy versions).
SOURCES = tuple(Path(m.__file__) for m in (phase_space, modes, mode_proofs, symbols)) + (Path(__file__),)
#: Largest entry read, in bytes (an entry is about 200).
MAX_ENTRY = 64 * 1024


def cache_folder() -> Path | None:
    """The folder of the cache entries; None when the cache is switched off (FRICGEN_CACHE=off)."""
    if os.environ.get(CACHE_ENV, "").strip().lower() == "off":
        return None
    return manifests.cache_root()


@cache
def cache_key() -> str:
    """sha256 over the proof's sources (line ends normalized), GENERATOR_VERSION and SymPy's version.

    Taken once per process (the facts proven in a process are those of the code it imported)."""
    digest = hashlib.sha256()
    for path in SOURCES:
        try:
            digest.update(path.read_bytes().replace(b"\r\n", b"\n"))
        except OSError:
            return ""  # no source to key on (an installation without .py files): no cache
        digest.update(b"\0")
    digest.update(f"generator={GENERATOR_VERSION}\0sympy={sp.__version__}".encode())
    return digest.hexdigest()


def _entry(name: str, key: str) -> Path | None:
    folder = cache_folder()
    return None if folder is None or not key else folder / f"{name}-{key[:16]}.json"


def _digest(key: str, name: str, facts: dict) -> str:
    payload = json.dumps({"key": key, "name": name, "facts": facts}, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(payload.encode()).hexdigest()


def read_entry(name: str) -> dict | None:
    """The cached facts of ``name``, or None (no cache, no entry, not a regular file, unreadable,
    another key or name, or a payload that does not match its sha256)."""
    key = cache_key()
    path = _entry(name, key)
    if path is None:
        return None
    try:
        raw = read_regular(path, MAX_ENTRY)
        data = json.loads(raw) if len(raw) <= MAX_ENTRY else None
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("key") != key or data.get("name") != name or not isinstance(data.get("facts"), dict):
        return None
    if data.get("sha256") != _digest(data["key"], name, data["facts"]):
        return None
    return data["facts"]


def write_entry(name: str, facts: dict) -> Path | None:
    """Store ``facts`` (JSON-able) under ``name`` atomically; the path, or None if not written."""
    key = cache_key()
    path = _entry(name, key)
    if path is None:
        return None
    text = json.dumps({"key": key, "name": name, "facts": facts, "sha256": _digest(key, name, facts)}, indent=1, sort_keys=True)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{name}-", suffix=".tmp")
        try:
            with os.fdopen(handle, "w") as stream:
                stream.write(text)
            os.replace(temporary, path)
        except BaseException:
            Path(temporary).unlink(missing_ok=True)
            raise
    except OSError:
        return None
    return path


def _ratio_is(text: object, calculus: str) -> bool:
    """``text`` is the string of 1 - theta of ``calculus`` (parsed as a fraction, never evaluated)."""
    try:
        return isinstance(text, str) and Fraction(text) == 1 - Calculus(calculus).theta
    except (ValueError, ZeroDivisionError):
        return False


def _one_minus_theta(calculus: str) -> sp.Rational:
    value = 1 - Calculus(calculus).theta
    return sp.Rational(value.numerator, value.denominator)


@cache
def lemma(mode: str, dim: int, calculus: str) -> Lemma:
    """:func:`.mode_proofs.zero_current`, from the cache (only: holds, with nu/mu = 1 - theta) or proven."""
    modes.check_mode(mode, dim)
    name = f"zero_current_{mode}_{dim}d_{calculus}"
    found = read_entry(name)
    if isinstance(found, dict) and found.get("holds") is True and _ratio_is(found.get("nu_over_mu"), calculus):
        return Lemma(True, _one_minus_theta(calculus))
    proven = mode_proofs.zero_current(mode, dim, calculus)
    if proven.holds:
        write_entry(name, {"holds": True, "nu_over_mu": str(proven.nu_over_mu)})
    return proven


@cache
def facts(mode: str, dim: int) -> dict[str, bool]:
    """:func:`.mode_proofs.mode_facts`, from the cache (exactly :data:`.mode_proofs.FACTS`, each true) or proven."""
    modes.check_mode(mode, dim)
    name = f"facts_{mode}_{dim}d"
    found = read_entry(name)
    if isinstance(found, dict) and sorted(found) == sorted(FACTS) and all(v is True for v in found.values()):
        return {k: found[k] for k in FACTS}
    proven = mode_proofs.mode_facts(mode, dim)
    if all(proven.values()):
        write_entry(name, dict(proven))
    return proven


@cache
def combined(mode_set: tuple[str, ...], dim: int, calculus: str) -> dict[str, object]:
    """:func:`.mode_proofs.combined_current` of the distinct modes ``mode_set``, from the cache (only:
    holds, with nu/mu = 1 - theta for each of these modes) or proven."""
    for mode in mode_set:
        modes.check_mode(mode, dim)
    name = f"combined_{'+'.join(mode_set)}_{dim}d_{calculus}"
    found = read_entry(name)
    ratios = found.get("nu_over_mu") if isinstance(found, dict) else None
    if found and found.get("holds") is True and isinstance(ratios, dict) and sorted(ratios) == sorted(mode_set):
        if all(_ratio_is(ratios[m], calculus) for m in mode_set):
            return {"holds": True, "nu_over_mu": dict.fromkeys(mode_set, _one_minus_theta(calculus))}
    result = mode_proofs.combined_current(mode_set, dim, calculus)
    if result["holds"]:
        write_entry(name, {"holds": True, "nu_over_mu": {m: str(r) for m, r in result["nu_over_mu"].items()}})
    return result


def clear_memory() -> None:
    """Forget the facts read or proven through this cache in this process (the next call reads the
    disk again; for tests)."""
    for function in (lemma, facts, combined, cache_key):
        function.cache_clear()
