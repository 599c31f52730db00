"""Laws on the command line: the user's law folders (``--laws DIR``, ``FRICGEN_LAWS``), the look-up
of law names, and the commands on law files, ``fricgen verify`` and ``fricgen generate``.

A law name is looked up in the user's law folders, then in the built-in catalogue
(fricgen.derive.law.catalogues); the kernels of a folder DIR are generated into DIR/generated/.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from fricgen.derive.calculus import CALCULI
from fricgen.derive.law.catalogues import LAWS_ENV, CatalogueError, LawSearch

from ...errors import ConfigError
from ..run.outputs import check_folder, dumps

LAWS_HELP = (
    "a folder of your own law files (LAW.toml), searched before the built-in catalogue; its kernels live in DIR/generated/ "
    f"(repeatable; also ${LAWS_ENV}, folders joined by '{os.pathsep}')"
)


def add_laws_flag(command: argparse.ArgumentParser) -> None:
    """``--laws DIR`` (repeatable) on a command that takes laws."""
    command.add_argument("--laws", dest="law_folders", action="append", default=[], metavar="DIR", help=LAWS_HELP)


def law_search(args: argparse.Namespace) -> LawSearch:
    """The command line's law search: the ``--laws`` folders, then FRICGEN_LAWS's, then the built-in
    catalogue; each folder checked (ConfigError at --laws or FRICGEN_LAWS). The one place the command
    line reads FRICGEN_LAWS: the search is handed on from here (``args.search``)."""
    try:
        flags = LawSearch.of(*getattr(args, "law_folders", ()))
    except CatalogueError as error:
        raise ConfigError("--laws", str(error)) from error
    try:
        return flags.then(LawSearch.parse(os.environ.get(LAWS_ENV, "")))
    except CatalogueError as error:
        raise ConfigError(LAWS_ENV, str(error)) from error


def check_law_names(names: list[str], search: LawSearch) -> None:
    """Every name is a law on the search path, and in one catalogue only (ConfigError at LAW otherwise);
    the files are found, not read."""
    for name in names:
        try:
            search.find(name)
        except CatalogueError as error:
            raise ConfigError("LAW", str(error)) from error


def check_calculus(law: str, calculus: str, search: LawSearch) -> None:
    """The law's generated kernels exist, are fresh and have the calculus (ConfigError at --calculus)."""
    from ...kernels import load_law_kernels

    calculi = load_law_kernels(law, search).calculi
    if calculus not in calculi:
        raise ConfigError("--calculus", f"law {law} has no kernels for the {calculus!r} calculus", f"choose one of {list(calculi)}")


def verify(args: argparse.Namespace) -> int:
    """fricgen verify [LAW ...] [--calculus C|all] [--laws DIR] [--json]: derive and verify, exit 1 on failure."""
    check_law_names(args.laws, args.search)
    from fricgen.derive import derive_noise, load_law, verify

    named = set(args.laws)
    calculi = CALCULI if args.calculus == "all" else (args.calculus,)
    laws = [load_law(folder / f"{name}.toml") for folder, names in args.search.by_catalogue(args.laws).items() for name in names]
    jobs = [(law, c) for law in laws for c in calculi if c in law.calculi or law.name in named]  # every law read before any proof
    if not jobs:  # every law skipped: exit 0 would say that something was verified
        raise ConfigError("--calculus", f"no law here has the {args.calculus} calculus: nothing was verified", "name a law to verify it")
    for law in laws:
        for calculus in (c for c in calculi if c not in law.calculi and law.name not in named):
            why = f"not among the law's calculi {list(law.calculi)} (name the law to verify it anyway)"
            print(f"skipped {law.name}/{calculus}: {why}", file=sys.stderr)
    reports = []
    for law, calculus in jobs:
        report = verify(derive_noise(law, calculus))
        reports.append(report)
        if not args.json:
            status = "verified" if report.verified else "FAILED"
            form = "closed form" if report.closed_form else "integral (F-22)"
            failed = [k for k, v in report.checks.items() if not v]
            extra = f"  failed: {failed} {report.details}" if failed else ""
            print(f"{law.name:20s} {calculus:13s} {form:16s} {status:9s} {report.seconds:6.2f} s{extra}", flush=True)
    if args.json:
        print(dumps([r.as_dict() for r in reports]))
    return 0 if all(r.verified for r in reports) else 1


def generate(args: argparse.Namespace) -> int:
    """fricgen generate [LAW ...] [--laws DIR] [--output DIR]: derive, verify and emit kernels (idempotent),
    each law's into the kernel folder of its catalogue."""
    check_law_names(args.laws, args.search)
    if args.output:
        check_folder(Path(args.output), "--output")
    from fricgen.derive.driver import generate

    groups = args.search.by_catalogue(args.laws)
    if args.output and len(groups) > 1:
        raise ConfigError("--output", f"the laws come from {len(groups)} catalogues ({', '.join(map(str, groups))})", "name one's laws")
    for folder, names in groups.items():
        written, reports = generate(names if args.laws else None, catalogue=folder, output=args.output or None)
        for report in reports:
            print(f"verified {report.law}/{report.calculus} ({'closed form' if report.closed_form else 'integral (F-22)'})")
        for item in written:
            print(f"{item.status:9s} {item.path}")
    return 0
