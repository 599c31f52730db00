"""Typed configuration sections: frozen dataclasses that check their own values once, on creation.

A section is what a TOML table, a command-line flag group and an engine's configuration have in
common: :class:`Section` gives it one key prefix for error messages (``thermostat.dt``),
:func:`structure` builds it (and nested sections) from plain data such as a TOML table or a JSON
checkpoint with one-line errors for unknown keys and wrong types, and :func:`flat_fields` lists
its fields for command-line flags, so flags, files and engines cannot disagree on a default.
It also holds the two limits that no number checks by itself: the memory of the machine (an
estimate is refused before anything is allocated) and the 64-bit step counters.
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import os
import typing
from types import UnionType
from typing import Any, ClassVar

from .errors import ConfigError

STEP_LIMIT = 2**62
"""Most steps a run may take: step counters and noise keys are 64-bit integers."""


SCALES = (1e-6, 1e6)
"""The magnitudes a scale of a run may take (a radius, a mass, kT, a mobility), in fricgen's units
(sigma = 1, kT = 1, m = 1, t0): verify checks the kernels at scales of order one, the built-in laws'
noise kernels are checked at the four corners of kT and mu (tests/codegen/test_scales.py: within
KERNEL_TOLERANCE), and six decades either way keep every product and quotient the engines form
(r^2 / dt, kT / mu, a force times a radius) far from overflow, underflow and subnormal numbers. A force may be 0 or up to
``SCALES[1]`` in magnitude. Beyond this, results could not be stood behind: refused, one line."""


def machine_memory() -> float:
    """Physical memory of this machine in bytes (inf where the system does not tell)."""
    try:
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (AttributeError, ValueError, OSError):
        return math.inf


def size_text(nbytes: float) -> str:
    """A number of bytes for people: ``1.5 GiB``."""
    for unit in ("B", "KiB", "MiB", "GiB", "TiB"):
        if nbytes < 1024:
            return f"{nbytes:.3g} {unit}"
        nbytes /= 1024
    return f"{nbytes:.3g} PiB"


class Section:
    """Mixin of a frozen dataclass section; ``SECTION`` is its key prefix (``""`` at the top)."""

    SECTION: ClassVar[str] = ""

    def key(self, name: str) -> str:
        """The full key of field ``name``: a field's ``key`` metadata, else ``SECTION.name``."""
        fields = {f.name: f for f in dataclasses.fields(self)}
        if name in fields and "key" in fields[name].metadata:
            return fields[name].metadata["key"]
        return f"{self.SECTION}.{name}" if self.SECTION else name

    def require(self, condition: bool, name: str, problem: str, fix: str) -> None:
        """Raise ConfigError(key of ``name``, problem, fix) unless ``condition``."""
        if not condition:
            raise ConfigError(self.key(name), problem, fix)

    def require_positive(self, *names: str) -> None:
        """Each named field is a finite number > 0."""
        for name in names:
            value = getattr(self, name)
            self.require(math.isfinite(value) and value > 0, name, f"must be positive and finite, got {value}", "give a positive value")

    def require_nonnegative(self, *names: str) -> None:
        """Each named field is a finite number >= 0."""
        for name in names:
            value = getattr(self, name)
            self.require(math.isfinite(value) and value >= 0, name, f"must be >= 0 and finite, got {value}", "give 0 or more")

    def require_scale(self, *names: str) -> None:
        """Each named field is a finite number within :data:`SCALES` (1e-6 to 1e6)."""
        low, high = SCALES
        for name in names:
            value = getattr(self, name)
            self.require(
                math.isfinite(value) and low <= value <= high,
                name,
                f"must be within [{low:g}, {high:g}] (the scales fricgen is checked on), got {value}",
                "give a value within that range (change units if needed)",
            )

    def require_bounded(self, name: str, values: tuple[float, ...] | float) -> None:
        """Each of ``values`` (field ``name``, e.g. a force's components) is finite and at most
        ``SCALES[1]`` (1e6) in magnitude."""
        high = SCALES[1]
        for value in values if isinstance(values, tuple) else (values,):
            self.require(
                math.isfinite(value) and abs(value) <= high,
                name,
                f"must be finite and at most {high:g} in magnitude (the scales fricgen is checked on), got {value}",
                "give a smaller value (change units if needed)",
            )

    def require_memory(self, name: str, needed: float, what: str) -> None:
        """``what`` (e.g. "100 particles") fits this machine's memory with ``needed`` bytes (an estimate made
        before anything is allocated); else ConfigError at field ``name`` with the estimate and the memory."""
        total = machine_memory()
        amount = f"about {size_text(needed)}" if math.isfinite(needed) else "an unbounded amount"
        self.require(
            needed <= total,
            name,
            f"{what} need {amount} of memory, more than this machine has ({size_text(total)})",
            "give a smaller value",
        )

    def require_steps(self, name: str, steps: float) -> None:
        """A run of ``steps`` steps (set by field ``name``) fits the 64-bit step counters."""
        self.require(steps <= STEP_LIMIT, name, f"gives {steps:.3g} steps, more than a run can count (2^62)", "give a shorter run")


def _describe(hint) -> tuple[str, str]:
    """What a value of type ``hint`` is, and how TOML writes one."""
    if typing.get_origin(hint) is tuple:
        return ("a list of numbers", "[1.0, 2.0]") if typing.get_args(hint)[0] is float else ("a list of strings", '["temperatures"]')
    if typing.get_origin(hint) is dict:
        return "a table of numbers", "a table with NAME = 1.0 lines"
    return {int: ("an integer", "64"), float: ("a number", "0.6"), bool: ("true or false", "true"), str: ("a string", '"ito" (quoted)')}[
        hint
    ]


def _strip_optional(hint):
    """X for ``X | None`` (None is a default that TOML cannot write), else the hint itself."""
    if typing.get_origin(hint) is UnionType:
        return next(arg for arg in typing.get_args(hint) if arg is not type(None))
    return hint


def coerce(key: str, value: Any, hint) -> Any:
    """``value`` as the type ``hint`` (int, float, bool, str, tuple[float|str, ...], dict[str, float],
    or a Section dataclass built from a table) or ConfigError naming ``key``."""
    if value is None and _strip_optional(hint) is not hint:
        return None  # an optional field left at None (JSON null)
    hint = _strip_optional(hint)
    origin = typing.get_origin(hint)
    if dataclasses.is_dataclass(hint) and isinstance(value, dict):
        return structure(hint, value, key)
    if origin is tuple and isinstance(value, list | tuple):
        item = typing.get_args(hint)[0]
        return tuple(coerce(f"{key}[{i}]", v, item) for i, v in enumerate(value))
    if origin is dict and isinstance(value, dict):
        return {name: coerce(f"{key}.{name}", v, float) for name, v in value.items()}
    if hint is float and isinstance(value, int | float) and not isinstance(value, bool):
        return float(value)
    if origin is None and not dataclasses.is_dataclass(hint) and isinstance(value, hint) and (hint is bool or not isinstance(value, bool)):
        return value
    shown = f"{value!r} ({type(value).__name__})" if not isinstance(value, dict) else "a table"
    if dataclasses.is_dataclass(hint):
        raise ConfigError(key, f"must be a table, got {shown}", f"write it as a section [{key}] with key = value lines")
    what, example = _describe(hint)
    raise ConfigError(key, f"must be {what}, got {shown}", f"write it like {example}")


def unknown_key(key: str, name: str, known: list[str]) -> ConfigError:
    """The error of an unknown key, with the likely one."""
    close = difflib.get_close_matches(name, known, n=1)
    hint = f"did you mean {close[0]!r}? " if close else ""
    return ConfigError(key, "unknown key", f"{hint}known keys here: {', '.join(known)}")


def structure(cls: type, data: dict, prefix: str = "") -> Any:
    """An instance of the dataclass ``cls`` from the table ``data`` (missing keys take defaults)."""
    hints = typing.get_type_hints(cls)
    names = [f.name for f in dataclasses.fields(cls)]
    for name in data:
        if name not in names:
            raise unknown_key(f"{prefix}.{name}" if prefix else f"[{name}]", name, names)
    for f in dataclasses.fields(cls):
        if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING and f.name not in data:
            raise ConfigError(f"{prefix}.{f.name}", "missing", f"[{prefix}] needs {f.name} = ...")
    return cls(**{name: coerce(f"{prefix}.{name}" if prefix else name, value, hints[name]) for name, value in data.items()})


def flat_fields(*classes: type) -> dict[str, tuple[type, dataclasses.Field]]:
    """The fields of several sections by name (for command-line flags): name -> (section, field)."""
    fields: dict[str, tuple[type, dataclasses.Field]] = {}
    for cls in classes:
        for f in dataclasses.fields(cls):
            if f.name in fields:
                raise TypeError(f"field {f.name!r} of {cls.__name__} is also in {fields[f.name][0].__name__}")
            fields[f.name] = (cls, f)
    return fields


def differences(wanted: Section, stored: Section) -> list[tuple[str, Any, Any]]:
    """(key, wanted value, stored value) of every field that differs, nested sections by their keys."""
    found = []
    for f in dataclasses.fields(wanted):
        a, b = getattr(wanted, f.name), getattr(stored, f.name)
        if isinstance(a, Section) and type(a) is type(b):
            found += differences(a, b)
        elif a != b:
            found.append((wanted.key(f.name), a, b))
    return found
