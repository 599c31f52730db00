"""Where laws come from: the catalogues (folders of law files) that a law's name is looked up in.

The search path is the user's law folders, then the built-in catalogue derive/law/catalogue/. User
folders come from :func:`user_laws` blocks (``fricgen ... --laws DIR``, a run configuration's
``law.folder``) and from the environment variable ``FRICGEN_LAWS`` (one folder, or several joined
by os.pathsep), read at every look-up. A name is unique on the path: a user law may not take the
name of a built-in law or of a law in another user folder (:class:`CatalogueError` names both files).

The kernels of a catalogue's laws live beside it (:func:`kernel_folder`): the built-in catalogue's
in the package's generated/, those of a user folder DIR in DIR/generated/, a package of the same
layout (__init__.py, special.py, laws/<law>.py). Potentials are built-in only. Plain data, no SymPy:
the runtime's kernel loader uses this module.
"""

from __future__ import annotations

import contextlib
import importlib.resources
import os
import shlex
from collections.abc import Iterator, Sequence
from contextvars import ContextVar
from pathlib import Path

from ..errors import DeriveError
from .lawdata import CATALOGUE

#: The environment variable that names user law folders (os.pathsep-separated).
LAWS_ENV = "FRICGEN_LAWS"
#: The package of the built-in catalogue's kernels (and of the potentials), fricgen.generated: the
#: repository's generated/ in a source checkout (an editable install), or the installed package's.
GENERATED = Path(str(importlib.resources.files("fricgen.generated")))
_BUILT_IN = CATALOGUE.resolve()
_ACTIVE: ContextVar[tuple[Path, ...]] = ContextVar("fricgen_user_laws", default=())


class CatalogueError(DeriveError, LookupError):
    """An unknown law, a law name in two catalogues, or a law folder that is not there."""


def law_folder(folder: str | Path, named_by: str = "") -> Path:
    """The absolute path of an existing folder of law files; CatalogueError (saying who named it) otherwise."""
    path = Path(folder).expanduser()
    if not path.is_dir():
        state = "is a file, not a folder" if path.exists() else "does not exist"
        named_by = f" ({named_by})" if named_by else ""
        raise CatalogueError(f"the law folder {folder}{named_by} {state}: give the folder that holds your law files (LAW.toml)")
    return path.resolve()


def is_built_in(catalogue: str | Path) -> bool:
    return Path(catalogue).resolve() == _BUILT_IN


def kernel_folder(catalogue: str | Path) -> Path:
    """Where the kernels of a catalogue's laws are generated: the package's generated/ for the built-in
    catalogue, DIR/generated for a user folder DIR."""
    return GENERATED if is_built_in(catalogue) else Path(catalogue).resolve() / "generated"


def source_checkout() -> bool:
    """Whether fricgen runs from a source checkout (generated/ beside derive/ and pyproject.toml, as in
    the repository), where the built-in catalogue's kernels may be regenerated; an installed package
    is never written to."""
    root = GENERATED.parent
    return (root / "pyproject.toml").is_file() and (root / "derive" / "law" / "catalogue").is_dir()


def generate_command(name: str, catalogue: str | Path = CATALOGUE) -> str:
    """The command that (re)generates the kernels of the law ``name`` of ``catalogue``."""
    folder = "" if is_built_in(catalogue) else f"--laws {shlex.quote(str(Path(catalogue).resolve()))} "
    return f"fricgen generate {folder}{name}"


def user_laws(*folders: str | Path) -> contextlib.AbstractContextManager[tuple[Path, ...]]:
    """A ``with`` block in which the law folders ``folders`` are searched first (then those of outer
    blocks, FRICGEN_LAWS's and the built-in catalogue). The folders are checked now: CatalogueError
    if one is not there."""
    return _searched(tuple(law_folder(folder) for folder in folders))


@contextlib.contextmanager
def _searched(folders: tuple[Path, ...]) -> Iterator[tuple[Path, ...]]:
    token = _ACTIVE.set(folders + _ACTIVE.get())
    try:
        yield folders
    finally:
        _ACTIVE.reset(token)


def user_folders() -> tuple[Path, ...]:
    """The user law folders in search order: those of :func:`user_laws` blocks, then FRICGEN_LAWS's."""
    named = os.environ.get(LAWS_ENV, "").split(os.pathsep)
    found = [*_ACTIVE.get(), *(law_folder(text, LAWS_ENV) for text in named if text.strip())]
    return tuple(folder for folder in dict.fromkeys(found) if folder != _BUILT_IN)


def law_names(catalogue: str | Path) -> list[str]:
    """The names of the laws in a catalogue folder (its LAW.toml files), sorted."""
    return sorted(path.stem for path in Path(catalogue).glob("*.toml") if path.stem.isidentifier())


def find_law(name: str, catalogue: str | Path | None = None) -> Path:
    """The law file of ``name``: in ``catalogue`` if given, else on the search path. CatalogueError if
    no catalogue has it, or two do."""
    if catalogue is None:
        folders = (*user_folders(), CATALOGUE)
    else:
        folders = (CATALOGUE if is_built_in(catalogue) else law_folder(catalogue),)
    found = [folder / f"{name}.toml" for folder in folders if name.isidentifier() and (folder / f"{name}.toml").is_file()]
    if len(found) > 1:
        raise CatalogueError(
            f"law {name!r} is in two catalogues, {found[0]} and {found[1]}: a name must be unique "
            "(a user law may not take the name of a built-in law or of a law in another user folder); rename one"
        )
    if not found:
        available = sorted({law for folder in folders for law in law_names(folder)})
        raise CatalogueError(f"unknown law {name!r}: no law {name!r} in {' or '.join(map(str, folders))}; choose from {available}")
    return found[0]


def laws_by_catalogue(names: Sequence[str] = ()) -> dict[Path, list[str]]:
    """The named laws, each found on the search path, by catalogue. Without names: every law of the
    user folders, or of the built-in catalogue when there are none (CatalogueError for a clash)."""
    if not names:
        names = [law for folder in user_folders() or (CATALOGUE,) for law in law_names(folder)]
    grouped: dict[Path, list[str]] = {}
    for name in dict.fromkeys(names):
        grouped.setdefault(find_law(name).parent, []).append(name)
    return grouped


__all__ = [
    "GENERATED",
    "LAWS_ENV",
    "CatalogueError",
    "find_law",
    "generate_command",
    "is_built_in",
    "kernel_folder",
    "law_folder",
    "law_names",
    "source_checkout",
    "laws_by_catalogue",
    "user_folders",
    "user_laws",
]
