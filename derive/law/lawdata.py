"""Law files as plain data, without SymPy: reading, the schema, and the source hashes of laws and potentials.

The runtime's kernel loader uses this module to detect stale kernels (a law file or
derive/law/potentials.py edited after the kernels were generated) without importing SymPy, so it must
stay free of SymPy imports: a potential's hash is taken over the bytes of derive/law/potentials.py (a
file read, not an import).
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import re
import stat
import tempfile
import tomllib
from dataclasses import dataclass
from pathlib import Path

from ..calculus import CALCULI
from ..errors import DeriveError

#: Version of the code generator; part of every source hash, bump when emitted code changes.
#: 2: RANGES (the parameters' admissible ranges) in law modules; quadrature cut at branch points.
#: 3: friction_slope (df/du) in law modules, for the Itô drift of the pairwise contact step.
#: 4: contact_<c> returns (f/u, D), not (f/u, sqrt D); every kernel inlined into its callers.
GENERATOR_VERSION = 4

CATALOGUE = Path(__file__).with_name("catalogue")
#: The source of the potentials (fricgen.derive.law.potentials), hashed as bytes by potential_source_hash.
POTENTIALS = Path(__file__).with_name("potentials.py")
#: Largest law file read, in bytes (a law is a few hundred bytes; its expressions at most 2000 characters).
MAX_LAW_FILE = 64 * 1024

#: The keys of a law file and their TOML types; name and friction are required.
LAW_KEYS = {
    "name": str,
    "friction": str,
    "weight": str,
    "calculi": list,
    "mode": str,
    "description": str,
    "reference": str,
    "parameters": dict,
}
REQUIRED_KEYS = ("name", "friction")
#: The keys of a parameter's table; default is required.
PARAMETER_KEYS = {"default": (int, float), "unit": str, "description": str, "range": str}
_KINDS = {str: "a string", list: "a list of strings", dict: "a table", (int, float): "a number"}
#: How to write a range, for error messages.
RANGE_EXAMPLE = 'an interval such as "[0, 2]", "(0, inf)" or "[1, 3)" (brackets closed, parentheses open)'


class LawFileError(DeriveError, ValueError):
    """A law file that cannot be read."""


# --- contact modes (docs/physics-modes.md) --------------------------------------------------------

#: The relative motions at a contact that a law can act on, and the dimensions in which each exists:
#: sliding (the paper's u_perp), rolling (R_eff (omega_i - omega_k) x n) and spinning
#: (R_eff (omega_i - omega_k) . n, about the normal: a disc in the plane has no such rotation).
CONTACT_MODES: dict[str, tuple[int, ...]] = {"sliding": (2, 3), "rolling": (2, 3), "spinning": (3,)}
#: The mode of a law file without ``mode``.
DEFAULT_MODE = "sliding"


class ModeError(DeriveError, ValueError):
    """A contact mode that does not exist, or not in the dimension asked for."""


def mode_refusal(mode: object, dim: int | None = None) -> str:
    """Why ``mode`` cannot be used (in ``dim`` dimensions when given), on one line; "" if it can."""
    if not isinstance(mode, str) or mode not in CONTACT_MODES:
        shown = repr(mode) if isinstance(mode, str) and len(mode) <= 40 else _describe(mode)
        return f"unknown contact mode {shown}; allowed: {list(CONTACT_MODES)}"
    if dim is not None and dim not in CONTACT_MODES[mode]:
        where = " and ".join(f"{d}-D" for d in CONTACT_MODES[mode])
        return f"the {mode} mode exists in {where} only, not in {dim}-D" + _WHY_NOT.get((mode, dim), "")
    return ""


_WHY_NOT = {("spinning", 2): ": discs in the plane spin about z, perpendicular to the normal, so (omega_i - omega_k) . n = 0"}


@dataclass(frozen=True)
class Interval:
    """The admissible values of a parameter: from ``lower`` to ``upper`` (``math.inf``: no bound), each
    end closed (included) or open. Parameters are real numbers >= 0, so ``lower`` >= 0."""

    lower: float = 0.0
    upper: float = math.inf
    lower_closed: bool = False
    upper_closed: bool = False

    def __contains__(self, value: float) -> bool:
        above = value > self.lower or (self.lower_closed and value == self.lower)
        return above and (value < self.upper or (self.upper_closed and value == self.upper))

    def __str__(self) -> str:
        def end(x: float) -> str:
            x = float(x)
            return "inf" if x == math.inf else str(int(x)) if x.is_integer() and abs(x) < 1e15 else repr(x)

        return f"{'[' if self.lower_closed else '('}{end(self.lower)}, {end(self.upper)}{']' if self.upper_closed else ')'}"


#: The default range of a parameter: the positive reals.
POSITIVE = Interval()
_NUMBER = r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?"
_INTERVAL = re.compile(rf"\s*([\[(])\s*({_NUMBER})\s*,\s*({_NUMBER}|\+?inf)\s*([\])])\s*")


def parse_range(text: str, what: str) -> Interval:
    """The Interval of a range as a law file writes it (``"[0, 2]"``, ``"(0, inf)"``); LawFileError
    starting with ``what`` for anything else, an empty range, or one reaching below 0."""
    match = _INTERVAL.fullmatch(text) if isinstance(text, str) else None
    if match is None:
        shown = repr(text) if isinstance(text, str) and len(text) <= 40 else _describe(text)
        raise LawFileError(f"{what}: cannot read {shown}: write {RANGE_EXAMPLE}")
    opening, lower, upper, closing = match.groups()
    interval = Interval(float(lower), float(upper.lstrip("+")), opening == "[", closing == "]")
    if not math.isfinite(interval.lower):
        raise LawFileError(f"{what}: the lower end of {text.strip()} must be a finite number")
    if interval.lower < 0:
        raise LawFileError(f"{what}: {text.strip()} reaches below 0: parameters are real numbers >= 0")
    if interval.upper == math.inf and interval.upper_closed:
        raise LawFileError(f"{what}: an infinite end is open: write {str(Interval(interval.lower, math.inf, interval.lower_closed))}")
    if not interval.lower < interval.upper:
        raise LawFileError(f"{what}: {text.strip()} is empty: the lower end must be below the upper end")
    return interval


def read_law_data(path: str | Path) -> dict:
    """The TOML table of a law file: its bytes read once, as UTF-8 text (LawFileError otherwise, also
    for a FIFO, a folder or a device: never waited on)."""
    path = Path(path)
    try:
        raw = read_regular(path, MAX_LAW_FILE)
    except FileNotFoundError as error:
        raise LawFileError(f"{path}: no such law file") from error
    except NotAFile as error:
        raise LawFileError(f"{path}: is {error.kind}, not a law file (a law file is a TOML text file, NAME.toml)") from error
    except OSError as error:
        raise LawFileError(f"{path}: cannot read the law file: {error.strerror or error}") from error
    if len(raw) > MAX_LAW_FILE:
        raise LawFileError(f"{path}: too large for a law file (over {MAX_LAW_FILE // 1024} KiB)")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as error:
        raise LawFileError(f"{path}: not a text law file: byte {error.start} is not UTF-8") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise LawFileError(f"{path}: not valid TOML: {error}") from error


# --- files that are read as data: regular files only, never waited on ----------------------------


class NotAFile(OSError):
    """A path that exists but is no regular file (``kind``: "a FIFO", "a folder", ...)."""

    def __init__(self, path: Path, kind: str):
        super().__init__(f"{path} is {kind}")
        self.kind = kind


_KIND_NAMES = ((stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISSOCK, "a socket"))


def file_kind(path: str | Path) -> str:
    """What ``path`` is, in words: "a regular file", "a folder", "a FIFO (named pipe)", "a socket",
    "a device", "a dangling symbolic link" or "missing" (symbolic links followed)."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        return "a dangling symbolic link" if os.path.lexists(path) else "missing"
    except OSError as error:
        return f"unreadable ({error.strerror or error})"
    if stat.S_ISREG(mode):
        return "a regular file"
    return next((name for test, name in _KIND_NAMES if test(mode)), "a device")


def read_regular(path: str | Path, limit: int) -> bytes:
    """At most ``limit`` + 1 bytes of the regular file ``path`` (symbolic links followed), opened
    without blocking so that a FIFO or a device is refused (:class:`NotAFile`), never waited on.
    FileNotFoundError (also for a dangling link) or OSError otherwise."""
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        descriptor = os.open(path, flags)
    except FileNotFoundError:
        if os.path.lexists(path):
            raise NotAFile(Path(path), "a dangling symbolic link") from None
        raise
    except IsADirectoryError:
        raise NotAFile(Path(path), "a folder") from None
    try:
        mode = os.fstat(descriptor).st_mode
        if not stat.S_ISREG(mode):
            raise NotAFile(Path(path), next((name for test, name in _KIND_NAMES if test(mode)), "a device"))
        chunks, left = [], limit + 1
        while left > 0:
            chunk = os.read(descriptor, min(left, 1 << 20))
            if not chunk:
                break
            chunks.append(chunk)
            left -= len(chunk)
        return b"".join(chunks)
    finally:
        os.close(descriptor)


def _describe(value: object) -> str:
    text = repr(value)
    return f"{type(value).__name__} {text if len(text) <= 40 else text[:37] + '...'}"


def check_law_data(data: dict, path: str | Path) -> None:
    """The schema of a law file: known keys, required keys, and the type of every value.

    Raises LawFileError naming the first problem, on one line. A parameter's ``range`` is read here
    (:func:`parse_range`) and must hold its default; the other values (an expression, a parameter's
    name or default, the law's name) are checked by fricgen.derive.law.laws.make_law.
    """
    unknown = sorted(set(data) - set(LAW_KEYS))
    if unknown:
        raise LawFileError(f"{path}: unknown key(s) {unknown}; allowed: {sorted(LAW_KEYS)}")
    for key in REQUIRED_KEYS:
        if key not in data:
            raise LawFileError(f"{path}: missing key {key!r}")
    for key, kind in LAW_KEYS.items():
        if key in data and not isinstance(data[key], kind):
            example = ' (e.g. calculi = ["ito", "hk"])' if key == "calculi" else ""
            raise LawFileError(f"{path}: {key} must be {_KINDS[kind]}{example}, got {_describe(data[key])}")
    for calculus in data.get("calculi", []):
        if calculus not in CALCULI:
            raise LawFileError(f"{path}: calculi: unknown calculus {_describe(calculus)}; allowed: {list(CALCULI)}")
    if "calculi" in data and not data["calculi"]:
        raise LawFileError(f"{path}: calculi must not be empty; allowed: {list(CALCULI)}")
    if "mode" in data and mode_refusal(data["mode"]):
        raise LawFileError(f"{path}: mode: {mode_refusal(data['mode'])}")
    for key, spec in data.get("parameters", {}).items():
        name = key if key.isidentifier() else repr(key)
        if not isinstance(spec, dict):
            raise LawFileError(f"{path}: parameters.{name} must be a table with a default ([parameters.{name}]), got {_describe(spec)}")
        extra = sorted(set(spec) - set(PARAMETER_KEYS))
        if extra:
            raise LawFileError(f"{path}: parameters.{name} has unknown key(s) {extra}; allowed: {sorted(PARAMETER_KEYS)}")
        if "default" not in spec:
            raise LawFileError(f"{path}: parameters.{name} needs a default")
        for key, kind in PARAMETER_KEYS.items():
            if key in spec and (not isinstance(spec[key], kind) or isinstance(spec[key], bool)):
                example = f" ({RANGE_EXAMPLE})" if key == "range" else ""
                raise LawFileError(f"{path}: parameters.{name}.{key} must be {_KINDS[kind]}{example}, got {_describe(spec[key])}")
        if "range" in spec:
            interval = parse_range(spec["range"], f"{path}: parameters.{name}.range")
            if spec["default"] not in interval:
                raise LawFileError(f"{path}: parameters.{name}: the default {spec['default']!r} is outside its range {interval}")


def write_text_atomic(path: Path, text: str, overwrite: bool = True) -> None:
    """Write ``text`` to ``path`` through a temporary file in the same folder: a reader sees the old
    file or the new one, never a part. With ``overwrite`` False, FileExistsError if ``path`` exists."""
    path = Path(path)
    mode = path.stat().st_mode & 0o777 if path.exists() else 0o644
    descriptor, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8", newline="\n") as file:
            file.write(text)
        os.chmod(temporary, mode)
        if overwrite:
            os.replace(temporary, path)
            return
        try:
            os.link(temporary, path)  # atomic, and fails if path exists
        except FileExistsError:
            raise
        except OSError:  # a file system without hard links: exclusive creation instead
            with path.open("x", encoding="utf-8", newline="\n") as file:
                file.write(text)
    finally:
        Path(temporary).unlink(missing_ok=True)


def potential_source_hash(name: str, source: Path | bytes | None = None) -> str:
    """sha256 of the exact bytes of derive/law/potentials.py, the potential's name and the generator version.

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
    derive/law/potentials.py needlessly, which costs a regeneration, never a stale kernel.
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
    canonical = json.dumps(content, sort_keys=True, separators=(",", ":"), default=repr)  # repr: a TOML date, in an invalid file
    return hashlib.sha256(canonical.encode()).hexdigest()


def hashed_sources(path: str | Path, data: dict) -> str:
    """What a law's source hash covers, for a stale refusal: the law file ``path``, and derive/law/potentials.py
    when its weight (of ``data``) names a potential."""
    weight = weight_potential(data)
    return str(path) if weight is None else f"{path} or derive/law/potentials.py (its weight {weight})"
