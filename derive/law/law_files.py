"""Law files: a law read from its TOML file, written back as one, and a catalogue folder's laws.

The format is that of :mod:`fricgen.derive.law.laws` (``derive/law/catalogue/`` holds the built-in
laws); a law read here is validated by :func:`~fricgen.derive.law.laws.make_law` and carries the hash
of the bytes it was read from, which its generated kernels carry too.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

from ..calculus import CALCULI
from . import lawdata, potentials
from .expressions import LawError, snippet
from .lawdata import CATALOGUE, POSITIVE, LawFileError, check_law_data, read_law_data, source_hash, write_text_atomic
from .laws import FrictionLaw, make_law


def load_law(path: str | Path) -> FrictionLaw:
    """Read, check and validate a law file (TOML).

    Parameters
    ----------
    path : str or pathlib.Path
        The law file, ``<name>.toml``.

    Returns
    -------
    FrictionLaw
        The law; its ``source_hash`` is that of the bytes read.

    Raises
    ------
    LawError
        If the file is not a valid law (naming the key and the problem).

    Examples
    --------
    >>> from fricgen.derive import CATALOGUE, load_law
    >>> load_law(CATALOGUE / "stribeck.toml").source
    'w*(kappa_d + (kappa_s - kappa_d)*exp(-u/u_s))'
    """
    path = Path(path)
    try:
        data = read_law_data(path)
        check_law_data(data, path)
    except LawFileError as error:
        raise LawError(str(error)) from error
    if data["name"] != path.stem:
        raise LawError(f"{path}: name {snippet(repr(data['name']))} must equal the file name {path.stem!r}")
    digest = source_hash(data, potentials.SOURCE)  # now, not after the derivation: the file may change meanwhile
    law = make_law(
        name=data["name"],
        friction=data["friction"],
        parameters=data.get("parameters", {}),
        weight=data.get("weight"),
        calculi=tuple(data.get("calculi", CALCULI)),
        description=data.get("description", ""),
        reference=data.get("reference", ""),
        mode=data.get("mode", lawdata.DEFAULT_MODE),
    )
    return dataclasses.replace(law, source_hash=digest)


def _quote(text: str) -> str:
    """A TOML basic string (JSON escapes, UTF-8 kept as is; DEL is a control character in TOML)."""
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def law_text(law: FrictionLaw) -> str:
    """The law as TOML text (the inverse of :func:`load_law`); weight parameters are implied."""
    quote = _quote
    implied = set(potentials.PAIR_POTENTIALS[law.weight_source].defaults) if law.weight_source in potentials.PAIR_POTENTIALS else set()
    lines = [f"name = {quote(law.name)}"]
    if law.reference:
        lines.append(f"reference = {quote(law.reference)}")
    if law.description:
        lines.append(f"description = {quote(law.description)}")
    lines.append(f"friction = {quote(law.source or str(law.friction))}")
    if law.weight_source:
        lines.append(f"weight = {quote(law.weight_source)}")
    lines.append(f"calculi = [{', '.join(quote(c) for c in law.calculi)}]")
    lines += [f"mode = {quote(law.mode)}"] if law.mode != lawdata.DEFAULT_MODE else []  # a sliding law's text as before
    for p in law.parameters:
        if p.name in implied:
            continue
        lines += ["", f"[parameters.{p.name}]", f"default = {float(p.default)!r}", f"unit = {quote(p.unit)}"]
        if p.description:
            lines.append(f"description = {quote(p.description)}")
        if p.range != POSITIVE:
            lines.append(f"range = {quote(str(p.range))}")
    return "\n".join(lines) + "\n"


def save_law(law: FrictionLaw, folder: str | Path = CATALOGUE, overwrite: bool = False) -> Path:
    """Write a law to ``folder/<name>.toml`` (atomically).

    An existing file with other content is replaced only with ``overwrite=True``; one holding
    exactly this text is left as it is.

    Parameters
    ----------
    law : FrictionLaw
        The law to write.
    folder : str or pathlib.Path
        The law folder; the built-in catalogue by default.
    overwrite : bool
        Whether to replace a different law file of the same name.

    Returns
    -------
    pathlib.Path
        The written law file.
    """
    path = Path(folder) / f"{law.name}.toml"
    text = law_text(law)
    refused = LawError(f"{path} exists and holds another law file: save_law(law, overwrite=True) replaces it")
    if path.exists() and not overwrite:
        if path.read_bytes() == text.encode():
            return path
        raise refused
    try:
        write_text_atomic(path, text, overwrite=overwrite)
    except FileExistsError:
        raise refused from None
    return path


def catalogue(folder: str | Path = CATALOGUE) -> dict[str, FrictionLaw]:
    """All laws of a catalogue folder.

    Parameters
    ----------
    folder : str or pathlib.Path
        The law folder; the built-in catalogue by default.

    Returns
    -------
    dict of str to FrictionLaw
        The laws by name, in sorted order.

    Examples
    --------
    >>> from fricgen.derive import catalogue
    >>> "coulomb" in catalogue()
    True
    """
    return {p.stem: load_law(p) for p in sorted(Path(folder).glob("*.toml"))}
