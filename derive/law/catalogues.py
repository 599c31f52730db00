"""Where laws come from: the catalogues (folders of law files) that a law's name is looked up in.

The search path (:class:`LawSearch`) is the user's law folders, then the built-in catalogue
derive/law/catalogue/. It is a value built at the edge from what the user named: ``fricgen ...
--laws DIR``, the environment variable ``FRICGEN_LAWS`` (one folder, or several joined by
os.pathsep; read by the command line and by ``fricgen.load_law``, never here), a run
configuration's ``law.folder``, a notebook's folder. A name is unique on the path: a user law may
not take the name of a built-in law or of a law in another user folder (:class:`CatalogueError`
names both files).

The kernels of a catalogue's laws live beside it (:func:`kernel_folder`): the built-in catalogue's
in the package's generated/, those of a user folder DIR in DIR/generated/, a package of the same
layout (__init__.py, special.py, laws/<law>.py). Potentials are built-in only. Plain data, no SymPy:
the runtime's kernel loader uses this module.
"""

from __future__ import annotations

import importlib.resources
import json
import os
import re
import shlex
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from ..errors import DeriveError
from .lawdata import CATALOGUE, file_kind
from .names import clash

#: The environment variable that names user law folders (os.pathsep-separated).
LAWS_ENV = "FRICGEN_LAWS"
#: The package of the built-in catalogue's kernels (and of the potentials), fricgen.generated: the
#: repository's generated/ in a source checkout (an editable install), or the installed package's.
GENERATED = Path(str(importlib.resources.files("fricgen.generated")))
_BUILT_IN = CATALOGUE.resolve()


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
    """The command that (re)generates the kernels of the law ``name`` of ``catalogue``, on one line
    (a folder with a newline or another unprintable character in its path is quoted $'...')."""
    folder = "" if is_built_in(catalogue) else f"--laws {shell_word(str(Path(catalogue).resolve()))} "
    return f"fricgen generate {folder}{name}"


def shell_word(text: str) -> str:
    """``text`` as one word of a POSIX shell command line, on one line: shlex.quote's form when
    ``text`` is printable, else bash's ANSI-C quoting $'...' (bytes that are not UTF-8, kept by
    Python as surrogates, as their \\xHH)."""
    if text.isprintable():
        return shlex.quote(text)

    def escape(char: str) -> str:
        code = ord(char)
        if char in "\\'":
            return "\\" + char
        if char.isprintable():
            return char
        if 0xDC80 <= code <= 0xDCFF:  # an undecodable byte of a file name (surrogateescape)
            return f"\\x{code - 0xDC00:02x}"
        return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}"

    return "$'" + "".join(escape(char) for char in text) + "'"


#: Characters that a path or a name may hold to be printed as it is into a comment of generated code.
_INERT = re.compile(r"[A-Za-z0-9 _.,+=@%:~/'-]*")


def inert(text: str) -> str:
    """``text`` to print into a comment of generated code (Python, C++, CMake, a LAMMPS input), where
    it must stay a comment: as it is when it holds only letters, digits, spaces and ``_.,+=@%:~/'-``
    (so no line end, backslash, ``*/``, ``??`` or ``&``), else as a JSON string of ASCII characters
    with ``/`` and ``?`` escaped too (``"a\\nb"``), which ends in a quote, never a backslash."""
    if _INERT.fullmatch(text):
        return text
    quoted = json.dumps(text, ensure_ascii=True)
    return quoted.replace("/", "\\/").replace("?", "\\u003f").replace("\x7f", "\\u007f")


def law_names(catalogue: str | Path) -> list[str]:
    """The names of the laws in a catalogue folder (its LAW.toml files), sorted."""
    return sorted(path.stem for path in Path(catalogue).glob("*.toml") if path.stem.isidentifier())


def check_law_files(catalogue: str | Path) -> list[str]:
    """The names of the laws of a user's law folder, every NAME.toml a regular file with an identifier
    as NAME; CatalogueError naming the first that is not, or saying that the folder holds none."""
    folder = Path(catalogue)
    for path in sorted(p for p in folder.glob("*.toml") if not p.name.startswith(".")):  # not hidden files (editors' locks)
        if not path.stem.isidentifier():
            better = re.sub(r"\W", "_", path.stem, flags=re.ASCII)
            better = better if better.isidentifier() else f"law_{better}"
            raise CatalogueError(
                f"{inert(str(path))}: a law file's name must be an identifier (letters, digits, underscores, not starting with a"
                f" digit), as it names the law and its kernel module: rename it {better}.toml"
            )
        kind = file_kind(path)
        if kind != "a regular file":
            raise CatalogueError(f"{inert(str(path))} is {kind}, not a law file: a law file is a TOML text file, NAME.toml")
    names = law_names(folder)
    if not names:
        raise CatalogueError(f"the law folder {inert(str(folder))} holds no law files (NAME.toml): there is nothing to verify or generate")
    refusal = clash((name, inert(str(folder / f"{name}.toml"))) for name in names)
    if refusal:
        raise CatalogueError(refusal)
    return names


@dataclass(frozen=True)
class LawSearch:
    """Where law names are looked up: the user's law folders in order, then the built-in catalogue.

    One value, built at the edge (the command line's ``--laws`` and ``FRICGEN_LAWS``, a notebook's
    folder, a run file's ``law.folder``) and handed to whatever resolves a name; no look-up reads
    the environment. A name is unique on the path: a user law may not take the name of a built-in
    law or of a law in another user folder.

    Attributes
    ----------
    folders : tuple of pathlib.Path
        Absolute paths of existing folders (use :meth:`of`, which checks them).
    built_in : bool
        Whether the built-in catalogue ends the path (False: the folders alone, as
        ``load_law_kernels(name, LawSearch.only(folder))``).

    Examples
    --------
    >>> from fricgen.derive.law.catalogues import BUILT_IN
    >>> BUILT_IN.find("coulomb").name
    'coulomb.toml'
    """

    folders: tuple[Path, ...] = ()
    built_in: bool = True

    @classmethod
    def of(cls, *folders: str | Path, named_by: str = "") -> LawSearch:
        """The search of some folders, then the built-in catalogue.

        Parameters
        ----------
        *folders : str or pathlib.Path
            The user's law folders, in order; each must exist.
        named_by : str
            Who named them, for the error (e.g. "--laws").

        Returns
        -------
        LawSearch
            The search.

        Raises
        ------
        CatalogueError
            For a folder that does not exist, saying who named it.
        """
        found = (law_folder(folder, named_by) for folder in folders)
        return cls(tuple(folder for folder in dict.fromkeys(found) if folder != _BUILT_IN))

    @classmethod
    def parse(cls, text: str, named_by: str = LAWS_ENV) -> LawSearch:
        """The search of the folders of a ``FRICGEN_LAWS``-style text, then the built-in catalogue.

        Parameters
        ----------
        text : str
            Folders joined by os.pathsep; empty entries, and line ends and tabs around an entry (as a
            shell's ``$(...)`` or an editor leaves them), are ignored.
        named_by : str
            Who named them, for the error.

        Returns
        -------
        LawSearch
            The search.
        """
        return cls.of(*(part.strip("\r\n\t") for part in text.split(os.pathsep) if part.strip()), named_by=named_by)

    @classmethod
    def only(cls, catalogue: str | Path) -> LawSearch:
        """The search of one catalogue folder alone (the built-in catalogue if it is that one).

        Parameters
        ----------
        catalogue : str or pathlib.Path
            The law folder.

        Returns
        -------
        LawSearch
            The search, without the built-in catalogue behind the folder.
        """
        return cls() if is_built_in(catalogue) else cls((law_folder(catalogue),), built_in=False)

    def then(self, other: LawSearch) -> LawSearch:
        """This search's folders first, then another's (duplicates dropped).

        Parameters
        ----------
        other : LawSearch
            The search to append.

        Returns
        -------
        LawSearch
            The joined search.
        """
        folders = tuple(dict.fromkeys((*self.folders, *other.folders)))
        return LawSearch(folders, self.built_in and other.built_in)

    @property
    def catalogues(self) -> tuple[Path, ...]:
        """The folders searched, in order, the built-in catalogue last where it is searched."""
        return (*self.folders, CATALOGUE) if self.built_in else self.folders

    def find(self, name: str) -> Path:
        """The law file of a name.

        Parameters
        ----------
        name : str
            The law's name.

        Returns
        -------
        pathlib.Path
            Its ``<name>.toml``.

        Raises
        ------
        CatalogueError
            If no catalogue has it, or two do, or its ``<name>.toml`` is not a regular file (a FIFO, a
            folder, a dangling symbolic link: said as such).
        """
        folders = self.catalogues
        candidates = [folder / f"{name}.toml" for folder in folders if name.isidentifier()]
        for path in candidates:
            kind = file_kind(path)
            if kind not in ("a regular file", "missing"):
                problem = f"law {name!r}: {inert(str(path))} is {kind}, not a law file"
                raise CatalogueError(f"{problem}: a law file is a TOML text file, NAME.toml")
        found = [path for path in candidates if path.is_file()]
        if len(found) > 1:
            raise CatalogueError(
                f"law {name!r} is in two catalogues, {found[0]} and {found[1]}: a name must be unique "
                "(a user law may not take the name of a built-in law or of a law in another user folder); rename one"
            )
        if not found and not name.isidentifier():
            better = re.sub(r"\W", "_", name, flags=re.ASCII)
            raise CatalogueError(
                f"unknown law {inert(name)}: a law's name is an identifier (letters, digits, underscores), and so is the name of its"
                f" file NAME.toml; a file {inert(name)}.toml is not read as a law: rename it {inert(better)}.toml (and its name)"
            )
        if not found:
            available = sorted({law for folder in folders for law in law_names(folder)})
            raise CatalogueError(
                f"unknown law {name!r}: no law {name!r} in {' or '.join(map(str, folders))}; choose from {available}, or add the folder"
                f" of your law files with --laws DIR (or {LAWS_ENV})"
            )
        refusal = clash(((law, inert(str(folder / f"{law}.toml"))) for folder in folders for law in law_names(folder)), name)
        if refusal:  # names that differ only in case or underscores: one law would run the other's code
            raise CatalogueError(refusal)
        return found[0]

    def by_catalogue(self, names: Sequence[str] = ()) -> dict[Path, list[str]]:
        """The named laws, each found on this path, grouped by catalogue.

        Parameters
        ----------
        names : sequence of str
            The laws; none: every law of the user folders, or of the built-in catalogue when there are
            none.

        Returns
        -------
        dict of pathlib.Path to list of str
            The law names by catalogue folder.

        Raises
        ------
        CatalogueError
            For an unknown name or a clash.
        """
        if not names:
            names = [law for folder in self.folders for law in check_law_files(folder)] if self.folders else law_names(CATALOGUE)
        grouped: dict[Path, list[str]] = {}
        for name in dict.fromkeys(names):
            grouped.setdefault(self.find(name).parent, []).append(name)
        return grouped


#: The search of the built-in catalogue alone (no user folder).
BUILT_IN = LawSearch()

__all__ = [
    "BUILT_IN",
    "GENERATED",
    "LAWS_ENV",
    "CatalogueError",
    "LawSearch",
    "check_law_files",
    "generate_command",
    "inert",
    "is_built_in",
    "kernel_folder",
    "law_folder",
    "law_names",
    "shell_word",
    "source_checkout",
]
