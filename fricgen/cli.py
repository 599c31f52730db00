"""The ``fricgen`` command line: one program, one subcommand per job."""

from __future__ import annotations

import argparse
import json
import sys

CALCULI = ("ito", "stratonovich", "hk")


def _verify(args: argparse.Namespace) -> int:
    """fricgen verify [LAW ...] [--calculus C|all] [--json]: derive and verify, exit 1 on failure."""
    from derive import LawError, catalogue, derive_noise, verify

    try:
        laws = catalogue()
    except LawError as error:
        print(f"fricgen verify: invalid law in the catalogue: {error}", file=sys.stderr)
        return 2
    unknown = [name for name in args.laws if name not in laws]
    if unknown:
        print(f"fricgen verify: unknown law(s) {', '.join(unknown)}; the catalogue has: {', '.join(laws)}", file=sys.stderr)
        return 2
    named = set(args.laws)
    calculi = CALCULI if args.calculus == "all" else (args.calculus,)
    reports = []
    for name in args.laws or laws:
        law = laws[name]
        for calculus in calculi:
            if calculus not in law.calculi and name not in named:
                print(
                    f"skipped {name}/{calculus}: not among the law's calculi {list(law.calculi)} (name the law to verify it anyway)",
                    file=sys.stderr,
                )
                continue
            report = verify(derive_noise(law, calculus))
            reports.append(report)
            if not args.json:
                status = "verified" if report.verified else "FAILED"
                form = "closed form" if report.closed_form else "integral (F-22)"
                failed = [k for k, v in report.checks.items() if not v]
                extra = f"  failed: {failed} {report.details}" if failed else ""
                print(f"{name:20s} {calculus:13s} {form:16s} {status:9s} {report.seconds:6.2f} s{extra}", flush=True)
    if args.json:
        print(json.dumps([r.as_dict() for r in reports], indent=2))
    return 0 if all(r.verified for r in reports) else 1


def parser() -> argparse.ArgumentParser:
    main = argparse.ArgumentParser(prog="fricgen", description=__doc__)
    commands = main.add_subparsers(dest="command", required=True)
    verify = commands.add_parser("verify", help="derive D(u, r) for catalogue laws and verify zero probability current")
    verify.add_argument("laws", nargs="*", metavar="LAW", help="law names (default: the whole catalogue)")
    verify.add_argument("--calculus", choices=(*CALCULI, "all"), default="all")
    verify.add_argument("--json", action="store_true", help="print one JSON array, one object per law and calculus")
    verify.set_defaults(run=_verify)
    return main


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    return args.run(args)


if __name__ == "__main__":
    sys.exit(main())
