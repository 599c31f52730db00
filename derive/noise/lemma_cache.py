"""On-disk cache of the law-independent facts of :mod:`fricgen.derive.noise.phase_space`.

Proving the zero-current lemma and the covariance identities (F-50) on the pair phase space takes
30-40 s and does not depend on the law, so every ``verify``/``generate`` process would otherwise
prove them again. The facts (booleans, and the rational nu/mu that the lemma reads off the current)
are stored as small JSON files in a user cache folder:

- ``$FRICGEN_CACHE`` if set (``off`` disables the cache: every process proves again),
- else ``$XDG_CACHE_HOME/fricgen``, else ``~/.cache/fricgen``.

Entries are keyed on a hash of the sources the proof depends on (derive/noise/phase_space.py,
derive/law/symbols.py and this module), the generator version (fricgen.derive.law.lawdata.GENERATOR_VERSION) and
the SymPy version. An entry is written atomically (a temporary file renamed into place).

The cache is an optimisation, never a source of truth: an entry is used only if it is a regular file
(opened without blocking: a FIFO, a folder or a device in its place is a miss, never waited on), of
at most :data:`MAX_ENTRY` bytes, whose ``sha256`` (over its own key, name and facts, canonical JSON)
holds, with this key and name, and whose facts are what a proof establishes: the lemma holds with
nu/mu = 1 - theta of the calculus (fricgen.derive.calculus; the value the proof reads off the
current), and every covariance identity of the dimension is there and true. Anything else (damaged,
foreign, a negative or vacuous fact such as an empty set of identities or an nu/mu of another
calculus) is ignored: the fact is proven again and the entry rewritten. A folder that cannot be
written is not an error: the fact is just not kept. No code is ever evaluated from the cache (the
rational is parsed by ``fractions.Fraction``).
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
from . import phase_space

CACHE_ENV = manifests.CACHE_ENV
#: The sources whose bytes key the cache (besides the generator and SymPy versions).
SOURCES = (Path(phase_space.__file__), Path(symbols.__file__), Path(__file__))
#: Largest entry read, in bytes (an entry is about 200).
MAX_ENTRY = 64 * 1024
#: The identities that :func:`fricgen.derive.noise.phase_space.covariance_identities` proves, by dimension.
IDENTITIES = {2: ("sigma_hat",), 3: ("sigma_hat", "random_force")}


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


def read_entry(name: str, key: str | None = None) -> dict | None:
    """The cached facts of ``name``, or None (no cache, no entry, not a regular file, unreadable,
    another key or name, or a payload that does not match its sha256). ``key``: :func:`cache_key`
    unless given (fricgen.derive.noise.mode_cache keys its entries on its own sources too)."""
    key = cache_key() if key is None else key
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


def write_entry(name: str, facts: dict, key: str | None = None) -> Path | None:
    """Store ``facts`` (JSON-able) under ``name`` atomically (with ``key`` as in :func:`read_entry`);
    the path, or None if not written."""
    key = cache_key() if key is None else key
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


def _rational(text) -> sp.Rational | None:
    if text is None:
        return None
    if not isinstance(text, str):
        raise ValueError(f"not a rational: {text!r}")
    value = Fraction(text)
    return sp.Rational(value.numerator, value.denominator)


def _lemma_from(facts: dict, calculus: str) -> phase_space.Lemma:
    """The Lemma of a cached entry if it states what the proof establishes (the lemma holds, with
    nu/mu = 1 - theta of ``calculus``); ValueError for anything else, a negative fact included."""
    holds, ratio = facts["holds"], _rational(facts["nu_over_mu"])
    expected = 1 - Calculus(calculus).theta
    if holds is not True or ratio is None or ratio != sp.Rational(expected.numerator, expected.denominator):
        raise ValueError(f"not the proven lemma of the {calculus} calculus: holds = {holds!r}, nu/mu = {ratio}")
    return phase_space.Lemma(True, ratio)


@cache
def zero_current(dim: int, calculus: str) -> phase_space.Lemma:
    """:func:`fricgen.derive.noise.phase_space.zero_current_lemma`, read from the cache or proven and stored."""
    name = f"zero_current_{dim}d_{calculus}"
    facts = read_entry(name)
    if facts is not None:
        try:
            return _lemma_from(facts, calculus)
        except (KeyError, TypeError, ValueError, ZeroDivisionError):
            pass  # a damaged or vacuous entry: prove again
    lemma = phase_space.zero_current_lemma(dim, calculus)
    ratio = None if lemma.nu_over_mu is None else str(lemma.nu_over_mu)
    write_entry(name, {"holds": lemma.holds, "nu_over_mu": ratio})
    return lemma


@cache
def covariance(dim: int) -> dict[str, bool]:
    """:func:`fricgen.derive.noise.phase_space.covariance_identities`, read from the cache (only an entry
    with exactly the identities of the dimension, each true) or proven and stored."""
    name = f"covariance_{dim}d"
    facts = read_entry(name)
    if facts is not None and sorted(facts) == sorted(IDENTITIES.get(dim, ())) and all(v is True for v in facts.values()):
        return dict(facts)
    facts = phase_space.covariance_identities(dim)
    write_entry(name, dict(facts))
    return facts


def clear_memory() -> None:
    """Forget the facts held in this process (the next call reads the disk again; for tests)."""
    zero_current.cache_clear()
    covariance.cache_clear()
    cache_key.cache_clear()
