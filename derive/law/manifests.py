"""What fricgen wrote: the records that authenticate generated code before anything runs it.

A law folder is data that anyone may hand over; the code generated beside it (DIR/generated/, a
LAMMPS plugin's sources) is code, and fricgen runs or compiles it only if this machine's fricgen
wrote exactly those bytes. Every writer of generated code records the sha256 of each file it wrote
(or found unchanged) in a *manifest* of that folder, kept in the user's own cache, which a law folder
cannot reach:

    <cache>/written/<key>/manifest.json   {"format", "folder", "files": {relative path: sha256}, "sha256"}
    <cache>/written/<key>/files/...       trusted copies: the verified bytes that are run or compiled

with ``<cache>`` = ``$FRICGEN_CACHE`` (unless ``off``, which switches off the lemma cache only: these
records are no cache of results), else ``$XDG_CACHE_HOME/fricgen``, else ``~/.cache/fricgen``, and
``<key>`` the sha256 of the folder's absolute path. ``"sha256"`` is taken over the manifest's own
payload (canonical JSON): a damaged manifest authenticates nothing. Before use, :func:`verified`
reads each file once (a regular file only: never a FIFO or a device, never waited on) and compares
its sha256 with the manifest (or with those fricgen recorded for other folders, or those of the
installed package's own generated code: a copied folder of generated code holds the same code); a
file whose bytes fricgen never wrote, or that is not a file, is refused with one line that names it
and the command that regenerates it. The bytes that passed are
what runs: :func:`trusted_copy` puts them in the cache, where Python compiles them and Numba keeps its
compiled code (never in the law folder's __pycache__, which a folder from elsewhere could fill).
Manifests are written atomically under a lock; records of folders that no longer exist are removed.
Plain data, no SymPy: the runtime's kernel loader uses this module.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import re
import shutil
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path

from ..errors import DeriveError
from .catalogues import GENERATED
from .lawdata import NotAFile, read_regular

CACHE_ENV = "FRICGEN_CACHE"
#: The format of a manifest; another format is no record.
FORMAT = 1
#: Largest manifest and largest generated file read, in bytes.
MAX_MANIFEST = 1 << 20
MAX_FILE = 64 << 20
_SHA256 = re.compile(r"[0-9a-f]{64}")

try:
    import fcntl
except ImportError:  # not POSIX: writers are not serialized (a lost record costs a regeneration)
    fcntl = None


class UntrustedFile(DeriveError):
    """Generated code that fricgen did not write (or cannot record): refused, on one line."""


def cache_root() -> Path | None:
    """The user's fricgen cache folder: $FRICGEN_CACHE (unless ``off``), else $XDG_CACHE_HOME/fricgen,
    else ~/.cache/fricgen; None without a home folder."""
    chosen = os.environ.get(CACHE_ENV, "").strip()
    if chosen and chosen.lower() != "off":
        return Path(chosen).expanduser()
    base = os.environ.get("XDG_CACHE_HOME")
    if not base:
        try:
            base = Path.home() / ".cache"
        except RuntimeError:
            return None
    return Path(base) / "fricgen"


def store() -> Path:
    """<cache>/written, the folder of the manifests; UntrustedFile when there is no cache folder."""
    root = cache_root()
    if root is None:
        raise UntrustedFile(f"no folder to record generated files in: set {CACHE_ENV} (or HOME) to a folder you can write")
    return root.absolute() / "written"


def sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _entry(folder: Path) -> Path:
    return store() / sha256(os.fsencode(str(Path(folder).absolute())))[:32]


def _payload_digest(payload: dict) -> str:
    return sha256(json.dumps(payload, sort_keys=True, separators=(",", ":"), ensure_ascii=True).encode())


def _load(entry: Path) -> dict | None:
    """The payload of a manifest file if it is whole and well formed, else None."""
    try:
        data = json.loads(read_regular(entry / "manifest.json", MAX_MANIFEST))
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("format") != FORMAT or not isinstance(data.get("folder"), str):
        return None
    files = data.get("files")
    if not isinstance(files, dict) or not all(isinstance(k, str) and isinstance(v, str) and _SHA256.fullmatch(v) for k, v in files.items()):
        return None
    payload = {"format": FORMAT, "folder": data["folder"], "files": files}
    return payload if data.get("sha256") == _payload_digest(payload) else None


def manifest(folder: str | Path) -> dict[str, str]:
    """The recorded sha256 of each file fricgen wrote into ``folder``, by relative path ({} if none)."""
    folder = Path(folder).absolute()
    try:
        payload = _load(_entry(folder))
    except UntrustedFile:
        return {}
    return dict(payload["files"]) if payload and payload["folder"] == str(folder) else {}


@contextlib.contextmanager
def _locked(entry: Path) -> Iterator[None]:
    entry.mkdir(parents=True, exist_ok=True)
    flags = os.O_RDWR | os.O_CREAT | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    descriptor = os.open(entry / ".lock", flags, 0o600)
    try:
        if not stat.S_ISREG(os.fstat(descriptor).st_mode):
            raise NotAFile(entry / ".lock", "no regular file")
        if fcntl is not None:
            fcntl.flock(descriptor, fcntl.LOCK_EX)
        yield
    finally:
        os.close(descriptor)


def _write_atomic(path: Path, data: bytes) -> None:
    descriptor, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(descriptor, "wb") as file:
            file.write(data)
        os.replace(temporary, path)
    finally:
        Path(temporary).unlink(missing_ok=True)


def record(folder: str | Path, digests: dict[str, str], removed: tuple[str, ...] = ()) -> Path:
    """Add the sha256 ``digests`` of files fricgen wrote into ``folder`` (by path relative to it) to its
    manifest, and drop ``removed``; returns the manifest's path. UntrustedFile (one line) if the
    record cannot be written: then the files cannot be used."""
    folder = Path(folder).absolute()
    entry = _entry(folder)
    try:
        with _locked(entry):
            payload = _load(entry)
            files = dict(payload["files"]) if payload and payload["folder"] == str(folder) else {}
            files.update(digests)
            for name in removed:
                files.pop(name, None)
            payload = {"format": FORMAT, "folder": str(folder), "files": dict(sorted(files.items()))}
            text = json.dumps({**payload, "sha256": _payload_digest(payload)}, indent=1, ensure_ascii=True) + "\n"
            _write_atomic(entry / "manifest.json", text.encode())
    except OSError as error:
        raise UntrustedFile(
            f"cannot record what fricgen wrote into {folder} in {entry.parent} ({error.strerror or error}): without the record the"
            f" files cannot be used; set {CACHE_ENV} to a folder you can write"
        ) from None
    _prune(entry)
    return entry / "manifest.json"


def _prune(keep: Path) -> None:
    """Remove the records (and trusted copies) of folders that no longer exist."""
    with contextlib.suppress(OSError):
        for entry in keep.parent.iterdir():
            payload = _load(entry) if entry != keep and entry.is_dir() and not entry.is_symlink() else None
            if payload is not None and not os.path.lexists(payload["folder"]):
                shutil.rmtree(entry, ignore_errors=True)


def known_digests() -> set[str]:
    """The sha256 of every file that any manifest of the store records (fricgen wrote it somewhere),
    and of the installed package's own generated code (fricgen.generated: trusted as installed code)."""
    found = {sha256(path.read_bytes()) for path in GENERATED.rglob("*.py") if "__pycache__" not in path.parts}
    with contextlib.suppress(OSError, UntrustedFile):
        for entry in store().iterdir():
            payload = _load(entry) if entry.is_dir() and not entry.is_symlink() else None
            found.update(payload["files"].values() if payload else ())
    return found


def verified(folder: str | Path, names: list[str], command: str) -> dict[str, bytes]:
    """The bytes of each file ``names`` (relative paths) of ``folder``, each checked before any is used:
    its sha256 must be the one the folder's manifest records, or one that fricgen recorded for a file it
    wrote elsewhere, or that of a file of the installed package's generated code (a copy of a folder of
    generated code is that code; such files are then recorded for this folder too). UntrustedFile
    naming the first that fails and ``command``, which regenerates them: a file edited by hand,
    dropped in, or not a regular file."""
    folder = Path(folder).absolute()
    files, known, adopted = manifest(folder), None, {}
    sources = {}
    for name in names:
        path = folder / name
        shown = _shown(path)
        try:
            data = read_regular(path, MAX_FILE)
        except FileNotFoundError:
            raise UntrustedFile(f"{shown} is missing: run `{command}`") from None
        except NotAFile as error:
            raise UntrustedFile(f"{shown} is {error.kind}, not a file that fricgen wrote: run `{command}`") from None
        except OSError as error:
            raise UntrustedFile(f"cannot read {shown}: {error.strerror or error}") from None
        digest = sha256(data)
        if len(data) <= MAX_FILE and files.get(name) != digest:
            known = known_digests() if known is None else known
            if digest not in known:
                if name in files:
                    raise UntrustedFile(f"{shown} is not the file that fricgen wrote (it was edited or replaced since): run `{command}`")
                where = _shown(_entry(folder).parent)
                raise UntrustedFile(
                    f"{shown} was not written by fricgen on this machine (no record of it in {where}), and fricgen runs only code it"
                    f" wrote itself: run `{command}`"
                )
            adopted[name] = digest
        sources[name] = data
    if adopted:
        with contextlib.suppress(UntrustedFile):
            record(folder, adopted)
    return sources


def trusted_copy(folder: str | Path, name: str, data: bytes) -> Path:
    """The trusted copy of the verified bytes ``data`` of ``folder``/``name`` in the cache, written
    (atomically) only when it differs, so that Numba's cache of it stays valid; UntrustedFile if it
    cannot be written."""
    copy = _entry(Path(folder).absolute()) / "files" / name
    try:
        with contextlib.suppress(OSError):
            if read_regular(copy, MAX_FILE) == data:
                return copy
        copy.parent.mkdir(parents=True, exist_ok=True)
        _write_atomic(copy, data)
    except OSError as error:
        raise UntrustedFile(
            f"cannot write the trusted copy {copy} ({error.strerror or error}): set {CACHE_ENV} to a folder you can write"
        ) from None
    return copy


def _shown(path: Path) -> str:
    """A path on one line: as it is when printable, else as a JSON string."""
    text = str(path)
    return text if text.isprintable() else json.dumps(text)


__all__ = ["CACHE_ENV", "UntrustedFile", "cache_root", "known_digests", "manifest", "record", "sha256", "store", "trusted_copy", "verified"]
