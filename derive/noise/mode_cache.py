"""On-disk cache of the law-independent facts of the contact modes (:mod:`.mode_proofs`).

The same folder, entry format and integrity rules as :mod:`fricgen.derive.noise.lemma_cache` (read
that module first): an entry is an optimisation, never a source of truth; it is read only as a
small regular file whose sha256 holds, and used only when it states exactly what the proof
establishes, anything else being proven again and rewritten. The entries here:

- ``mode_facts_<mode>_<dim>d``: exactly the facts of :func:`.mode_proofs.mode_facts`, each true;
- ``mode_zero_current_<mode>_<dim>d_<calculus>``: the lemma holds with nu/mu = 1 - theta;
- ``mode_combined_<modes>_<dim>d_<calculus>`` (modes joined by ``+`` in the order given): the
  current of the sum holds, with nu/mu = 1 - theta for every mode.

Their key is a sha256 over :func:`.lemma_cache.cache_key` (phase_space.py, symbols.py,
lemma_cache.py, the generator and SymPy versions) and the bytes of modes.py, mode_proofs.py and
this module. A refuted fact (a lemma that fails) is not stored: it is proven again next time.
"""

from __future__ import annotations

import hashlib
from fractions import Fraction
from functools import cache
from pathlib import Path

import sympy as sp

from ..calculus import Calculus
from . import lemma_cache, mode_proofs, modes
from .phase_space import Lemma

#: The sources whose bytes key the entries, besides those of lemma_cache's key.
SOURCES = (Path(modes.__file__), Path(mode_proofs.__file__), Path(__file__))
#: The facts of mode_proofs.mode_facts, by name (an entry must hold exactly these).
FACTS = ("velocity_is_C_v", "forces_from_C_transpose", "dissipation", "noise_covariance", "isotropic", "mobility_formula")


@cache
def cache_key() -> str:
    """sha256 over lemma_cache's key and the bytes (line ends normalized) of :data:`SOURCES`; "" (no
    cache) where a source cannot be read."""
    base = lemma_cache.cache_key()
    if not base:
        return ""
    digest = hashlib.sha256(base.encode())
    for path in SOURCES:
        try:
            digest.update(path.read_bytes().replace(b"\r\n", b"\n"))
        except OSError:
            return ""
        digest.update(b"\0")
    return digest.hexdigest()


def _ratio_is(text: object, calculus: str) -> bool:
    """``text`` is the string of 1 - theta of ``calculus`` (parsed as a fraction, never evaluated)."""
    try:
        return isinstance(text, str) and Fraction(text) == 1 - Calculus(calculus).theta
    except (ValueError, ZeroDivisionError):
        return False


def _one_minus_theta(calculus: str) -> sp.Rational:
    value = 1 - Calculus(calculus).theta
    return sp.Rational(value.numerator, value.denominator)


def dimensions(mode: str) -> tuple[int, ...]:
    """The dimensions in which ``mode`` exists, 3-D first (the order of the proof's checks)."""
    modes.check_mode(mode, None)
    return tuple(sorted(modes.CONTACT_MODES[mode], reverse=True))


def lemma(mode: str, dim: int, calculus: str) -> Lemma:
    """The zero-current lemma of ``mode``: sliding's from :mod:`.lemma_cache` (the paper's noise, as
    before), the others' from :func:`zero_current`."""
    if mode == modes.DEFAULT_MODE:
        return lemma_cache.zero_current(dim, calculus)
    return zero_current(mode, dim, calculus)


@cache
def facts(mode: str, dim: int) -> dict[str, bool]:
    """:func:`.mode_proofs.mode_facts`, from the cache (exactly :data:`FACTS`, each true) or proven."""
    modes.check_mode(mode, dim)
    name = f"mode_facts_{mode}_{dim}d"
    found = lemma_cache.read_entry(name, cache_key())
    if isinstance(found, dict) and sorted(found) == sorted(FACTS) and all(v is True for v in found.values()):
        return dict(found)
    proven = mode_proofs.mode_facts(mode, dim)
    if all(proven.values()):
        lemma_cache.write_entry(name, dict(proven), cache_key())
    return proven


@cache
def zero_current(mode: str, dim: int, calculus: str) -> Lemma:
    """:func:`.mode_proofs.zero_current`, from the cache (only: holds, with nu/mu = 1 - theta) or proven."""
    modes.check_mode(mode, dim)
    name = f"mode_zero_current_{mode}_{dim}d_{calculus}"
    found = lemma_cache.read_entry(name, cache_key())
    if isinstance(found, dict) and found.get("holds") is True and _ratio_is(found.get("nu_over_mu"), calculus):
        return Lemma(True, _one_minus_theta(calculus))
    lemma = mode_proofs.zero_current(mode, dim, calculus)
    if lemma.holds:
        lemma_cache.write_entry(name, {"holds": True, "nu_over_mu": str(lemma.nu_over_mu)}, cache_key())
    return lemma


@cache
def combined(mode_set: tuple[str, ...], dim: int, calculus: str) -> dict[str, object]:
    """:func:`.mode_proofs.combined_current` of the distinct modes ``mode_set``, from the cache (only:
    holds, with nu/mu = 1 - theta for each of these modes) or proven."""
    name = f"mode_combined_{'+'.join(mode_set)}_{dim}d_{calculus}"
    for mode in mode_set:
        modes.check_mode(mode, dim)
    found = lemma_cache.read_entry(name, cache_key())
    ratios = found.get("nu_over_mu") if isinstance(found, dict) else None
    if found and found.get("holds") is True and isinstance(ratios, dict) and sorted(ratios) == sorted(mode_set):
        if all(_ratio_is(ratios[m], calculus) for m in mode_set):
            return {"holds": True, "nu_over_mu": dict.fromkeys(mode_set, _one_minus_theta(calculus))}
    result = mode_proofs.combined_current(mode_set, dim, calculus)
    if result["holds"]:
        stored = {m: str(r) for m, r in result["nu_over_mu"].items()}
        lemma_cache.write_entry(name, {"holds": True, "nu_over_mu": stored}, cache_key())
    return result


def clear_memory() -> None:
    """Forget the facts held in this process, cached or proven (the next call reads the disk again or
    proves again; for tests)."""
    for function in (facts, zero_current, combined, cache_key):
        function.cache_clear()
    for function in (mode_proofs.mode_facts, mode_proofs.read_mobility, mode_proofs.zero_current, mode_proofs.combined_current):
        function.cache_clear()
