"""The names that a law's name becomes in code, and the rule that two laws never share one.

A law's name (an ASCII identifier, :func:`fricgen.derive.law.laws.make_law`) is printed into

- the files of its kernel module (``generated/laws/<name>.py``) and of its LAMMPS plugin
  (``generated/lammps/<name>/``, ``pair_fricgen_<name>.cpp``, ``fricgen_<name>.so``): one file on
  a file system that folds case (macOS, Windows), so ``name.lower()``;
- the C++ classes of its plugin, ``PairFricgen`` / ``FixFricgen`` + :func:`camel` (``coulomb_newton``
  -> ``CoulombNewton``: the parts between underscores capitalised and joined), and their header
  guards (``name.upper()``);
- the pair style ``fricgen/<name>`` (LAMMPS's style names are case-sensitive: distinct for distinct names).

Two laws whose names differ but become one of these would run each other's code: a LAMMPS that
loads both plugins resolves the class they both define to the first plugin's, so one style runs
the other law. :func:`clash` finds such a pair; the catalogues refuse it wherever two laws can meet
(fricgen.derive.law.catalogues: a folder, the search path of several folders and the built-in
catalogue), and each plugin checks at load time that its class is its own (templates.PLUGIN).
Plain data, no SymPy.
"""

from __future__ import annotations

from collections.abc import Iterable


def camel(law: str) -> str:
    """The law's name in the C++ classes of its plugin: ``coulomb_newton`` -> ``CoulombNewton``."""
    return "".join(part[:1].upper() + part[1:] for part in law.split("_"))


def mangled(law: str) -> dict[str, str]:
    """What the law's name becomes, by target (the keys say which, as an error names them)."""
    return {
        "file name on a case-insensitive file system (kernel module, plugin)": law.lower(),
        "C++ class name": camel(law),
        "C++ header guard": law.upper(),
    }


def clash(laws: Iterable[tuple[str, str]], name: str | None = None) -> str | None:
    """One line naming the first two laws, given as (name, where: a printable path), whose distinct
    names become the same name in code, and what they share; None if there are none. With ``name``:
    only a pair that includes the law ``name``."""
    seen: dict[tuple[str, str], tuple[str, str]] = {}
    for law, where in laws:
        for target, text in mangled(law).items():
            other, there = seen.setdefault((target, text), (law, where))
            if other != law and name in (None, law, other):
                return (
                    f"laws {other!r} ({there}) and {law!r} ({where}) have names that become the same {target}, {text!r}:"
                    " loaded together, one would run the other's code; rename one"
                )
    return None


__all__ = ["camel", "clash", "mangled"]
