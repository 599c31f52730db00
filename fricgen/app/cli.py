"""The ``fricgen`` command line: one program, one subcommand per job.

Exit status: 0 done, 1 a physical failure (a failed check, a run that blew up), 2 bad input
(one line on stderr naming the problem), 130 interrupted. Errors of fricgen's own family
(fricgen.errors) and of the symbolic layer (derive.errors) print one line; anything else is a bug
and keeps its traceback.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import typing

from derive.calculus import CALCULI
from derive.errors import DeriveError

from ..errors import FricgenError


def _verify(args: argparse.Namespace) -> int:
    """fricgen verify [LAW ...] [--calculus C|all] [--json]: derive and verify, exit 1 on failure."""
    from derive import catalogue, derive_noise, verify

    laws = catalogue()
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


def _generate(args: argparse.Namespace) -> int:
    """fricgen generate [LAW ...]: derive, verify and emit kernels (idempotent)."""
    from derive.emit import GENERATED, generate

    written, reports = generate(args.laws or None, output=args.output or GENERATED)
    for report in reports:
        print(f"verified {report.law}/{report.calculus} ({'closed form' if report.closed_form else 'integral (F-22)'})")
    for item in written:
        print(f"{item.status:9s} {item.path}")
    return 0


def _floats(text: str) -> list[float]:
    try:
        return [float(x) for x in text.split(",") if x.strip()]
    except ValueError as error:
        raise argparse.ArgumentTypeError(f"expected comma-separated numbers, got {text!r}") from error


def _assignment(text: str) -> tuple[str, float]:
    name, sep, value = text.partition("=")
    try:
        if not sep:
            raise ValueError
        return name.strip(), float(value)
    except ValueError as error:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}") from error


def _noise(args: argparse.Namespace) -> int:
    """fricgen noise LAW ...: D(u) through the generated kernels, as JSON."""
    import numpy as np

    from ..kernels import load_law_kernels

    kernels = load_law_kernels(args.law)
    params = kernels.parameters(**dict(args.param))
    kernels.noise_amplitude(args.calculus)
    problems = [f"--{k} must be positive" for k in ("mu", "kT") if not getattr(args, k) > 0]
    problems += ["--u values must be finite and >= 0"] if any(not (np.isfinite(x) and x >= 0) for x in args.u) else []
    if kernels.has_weight and args.r is None and args.w is None:
        problems.append(f"law {args.law} has a weight w(r): give --r R (centre distance) or --w W (weight value)")
    if args.w is not None and args.w < 0:
        problems.append("--w must be >= 0")
    if problems:
        print("fricgen noise: " + "; ".join(problems), file=sys.stderr)
        return 2
    r = 1.0 if args.r is None else args.r
    w = args.w if args.w is not None else (float(kernels.weight(r, params)) if kernels.has_weight else 1.0)
    amplitude = kernels.noise_amplitude(args.calculus)
    d = [float(amplitude(x, w, r, args.mu, args.kT, params)) for x in args.u]
    f = [float(kernels.friction(x, w, r, params)) for x in args.u]
    result = {
        "law": args.law,
        "calculus": args.calculus,
        "u": args.u,
        "D": d,
        "f": f,
        "w": w,
        "r": r,
        "mu": args.mu,
        "kT": args.kT,
        "parameters": dict(zip(kernels.parameter_names, params.tolist())),
    }
    if args.json:
        print(json.dumps(result, indent=2))
    else:
        print(f"{args.law} ({args.calculus}), w = {w:g}, mu = {args.mu:g}, kT = {args.kT:g}")
        for x, fx, dx in zip(args.u, f, d):
            print(f"u = {x:12.6g}   f = {fx:12.6g}   D = {dx:.12g}")
    return 0


def _thermostat_check(args: argparse.Namespace) -> int:
    """fricgen thermostat-check LAW ...: the statistical test of a law's thermostat, as JSON."""
    from ..langevin.thermostat_check import thermostat_check

    result = thermostat_check(
        args.law,
        dim=args.dim,
        calculus=args.calculus,
        contact_noise=not args.no_contact_noise,
        n=args.n,
        phi=args.phi,
        dt=args.dt,
        total_time=args.time,
        seed=args.seed,
        parameters=dict(args.param),
        solvent=not args.no_solvent,
    )
    if args.json:
        print(json.dumps(result.as_dict(), indent=2))
    else:
        r = result
        print(
            f"{r.law} ({r.calculus}, {r.dim}-D, contact noise {'on' if r.contact_noise else 'off'}): "
            f"T_trans = {r.T_trans:.4f} +- {r.T_trans_err:.4f}, T_rot = {r.T_rot:.4f} +- {r.T_rot_err:.4f}, "
            f"KL = {r.kl_trans:.1e} / {r.kl_rot:.1e}: {'passed' if r.passed else 'FAILED'} ({r.seconds:.1f} s)"
        )
    return 0 if result.passed else 1


def _demo(args: argparse.Namespace) -> int:
    """fricgen demo [--out DIR] [--json]: the passive check with and without contact noise; plots and JSON."""
    from pathlib import Path

    from .demo import describe, run_demo

    summary = run_demo(Path(args.out))
    print(json.dumps(summary, indent=2) if args.json else describe(summary, Path(args.out)))
    return 0


def _run(args: argparse.Namespace) -> int:
    """fricgen run CONFIG [--set KEY=VALUE ...] [--steps N] [--out DIR] [--resume CHECKPOINT] [--json]."""
    from .runner import execute, plan

    return execute(plan(args.config, args.set, args.steps, args.out, args.resume), args.json)


def _bcd(args: argparse.Namespace) -> int:
    """fricgen bcd ...: hard or sticky rods by BCD against the exact theory; CSV, PNG, JSON summary."""
    from pathlib import Path

    from ..rods.config import rod_config
    from .rods_study import study

    values = {name: getattr(args, name) for name in _rod_fields()}
    config = rod_config(**{name: dict(value) if isinstance(value, list) else value for name, value in values.items()})
    if not (args.time > 0 and args.equilibrate >= 0):
        raise FricgenError("--time must be positive and --equilibrate >= 0")
    summary = study(config, args.time, args.equilibrate, Path(args.out), extrapolate=args.extrapolate)
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(
            f"L1/rho_bar = {summary['l1_dev_over_rho']:.4f}, max |d rho| = {summary['max_abs_dev']:.4f}, "
            f"chi2/bin = {summary['chi2_per_dof']:.2f} ({summary['steps']} steps, {summary['seconds']:.1f} s); wrote {args.out}/"
        )
    return 0


#: What each flag of ``fricgen bcd`` sets (the defaults come from fricgen.rods.config).
ROD_HELP = {
    "n": "rods per ring",
    "length": "ring length L in wavelengths",
    "sigma": "rod length",
    "U0": "amplitude of the field in kT, U = (U0/2) cos(2 pi x) by default",
    "wavelength": "period of the field",
    "field": "a generated external potential (also ratchet)",
    "field_params": "other field parameters",
    "kT": "thermal energy",
    "mu": "mobility",
    "drive": "constant force on every rod",
    "gamma": "Baxter stickiness (0: hard rods)",
    "p": "exponent of the delta_eps representation (B-31)",
    "eps": "range of the delta_eps representation (B-31)",
    "pair": "a generated pair potential V(r) between neighbours instead of the sticky contact (e.g. wca)",
    "pair_params": "its parameters",
    "pair_range": "gap beyond sigma where the pair potential ends (< sigma)",
    "dt": "time step (bias O(sqrt(dt)))",
    "seed": "noise seed",
    "start_sweeps": "Monte Carlo sweeps of the equilibrium start",
    "replicas": "independent rings run in parallel, the samples of the errors",
    "bins": "bins over one wavelength",
    "gap_width": "bin width of the gap histogram (contact density)",
    "gap_bins": "bins of the gap histogram",
    "fit_bins": "gap bins fitted beyond the BCD layer",
}


def _rod_fields() -> dict:
    from ..rods.config import PARTS
    from ..schema import flat_fields

    return flat_fields(*PARTS)


def _add_rod_flags(command: argparse.ArgumentParser) -> None:
    """One flag per field of the rod configuration, with its type and default: ``--NAME`` (dashes for
    underscores), and ``--field-param NAME=VALUE`` (repeated) for the tables of parameters."""
    for name, (section, f) in _rod_fields().items():
        hint = typing.get_type_hints(section)[name]
        default = f.default if f.default is not dataclasses.MISSING else f.default_factory()
        text = f"{ROD_HELP[name]} (default {default})"
        if typing.get_origin(hint) is dict:
            flag = "--" + name.removesuffix("s").replace("_", "-")
            command.add_argument(flag, dest=name, type=_assignment, action="append", default=[], metavar="NAME=VALUE", help=ROD_HELP[name])
        else:
            kind = next(t for t in (int, float, str) if t is hint or t in typing.get_args(hint))
            command.add_argument("--" + name.replace("_", "-"), type=kind, default=default, help=text)


def parser() -> argparse.ArgumentParser:
    main = argparse.ArgumentParser(prog="fricgen", description=__doc__)
    commands = main.add_subparsers(dest="command", required=True)
    verify = commands.add_parser("verify", help="derive D(u, r) for catalogue laws and verify zero probability current")
    verify.add_argument("laws", nargs="*", metavar="LAW", help="law names (default: the whole catalogue)")
    verify.add_argument("--calculus", choices=(*CALCULI, "all"), default="all")
    verify.add_argument("--json", action="store_true", help="print one JSON array, one object per law and calculus")
    verify.set_defaults(run=_verify)

    generate = commands.add_parser("generate", help="derive, verify and emit Numba kernels into generated/")
    generate.add_argument("laws", nargs="*", metavar="LAW", help="law names (default: the whole catalogue)")
    generate.add_argument("--output", metavar="DIR", help="emit into DIR instead of the package's generated/ (for inspection)")
    generate.set_defaults(run=_generate)

    noise = commands.add_parser("noise", help="evaluate D(u) of a law through its generated kernels")
    noise.add_argument("law", metavar="LAW")
    noise.add_argument("--calculus", choices=CALCULI, default="ito")
    noise.add_argument("--u", type=_floats, required=True, help="comma-separated tangential speeds u >= 0")
    where = noise.add_mutually_exclusive_group()
    where.add_argument("--r", type=float, help="centre distance; w = w(r) from the law's weight")
    where.add_argument("--w", type=float, help="weight value w directly")
    noise.add_argument("--param", type=_assignment, action="append", default=[], metavar="NAME=VALUE")
    noise.add_argument("--mu", type=float, default=7.0, help="contact mobility (default 7: equal spheres m = 1, R = 1/2)")
    noise.add_argument("--kT", type=float, default=1.0, help="thermal energy (default 1)")
    noise.add_argument("--json", action="store_true", help="print JSON with u, D, f, w, r, mu, kT, parameters")
    noise.set_defaults(run=_noise)

    check = commands.add_parser("thermostat-check", help="statistical test: does the law thermalise a passive system to kT?")
    check.add_argument("law", metavar="LAW")
    check.add_argument("--dim", type=int, choices=(2, 3), default=2)
    check.add_argument("--calculus", choices=CALCULI, default="ito")
    check.add_argument("--no-contact-noise", action="store_true", help="drop the frictional noise (the inconsistent model)")
    check.add_argument("--no-solvent", action="store_true", help="friction thermostat alone (gamma = gamma_R = 0)")
    check.add_argument("--n", type=int, help="particles (default 256 in 2-D, 216 in 3-D)")
    check.add_argument("--phi", type=float, help="packing fraction (default 0.6 in 2-D, 0.3 in 3-D)")
    check.add_argument("--dt", type=float, default=1e-3)
    check.add_argument("--time", type=float, default=40.0, help="simulated time (the first 10%% equilibrates)")
    check.add_argument("--seed", type=int, default=1)
    check.add_argument("--param", type=_assignment, action="append", default=[], metavar="NAME=VALUE")
    check.add_argument("--json", action="store_true")
    check.set_defaults(run=_thermostat_check)

    demo = commands.add_parser("demo", help="the main job: 2-D passive Coulomb-Newton system with and without contact noise")
    demo.add_argument("--out", default="fricgen-demo", metavar="DIR", help="output folder (default fricgen-demo)")
    demo.add_argument("--json", action="store_true", help="print the summary as JSON")
    demo.set_defaults(run=_demo)

    run = commands.add_parser("run", help="a simulation from a TOML configuration (or a bundled example: passive, poiseuille, active)")
    run.add_argument("config", metavar="CONFIG", help="a TOML file or the name of a bundled example")
    run.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE", help="override a key (TOML value)")
    run.add_argument("--steps", type=int, help="override run.steps")
    run.add_argument("--out", metavar="DIR", help="output folder (default fricgen-<config name>)")
    run.add_argument("--resume", metavar="CHECKPOINT", help="continue from DIR/checkpoint.npz of a stopped run")
    run.add_argument("--json", action="store_true", help="print the summary as JSON")
    run.set_defaults(run=_run)

    bcd = commands.add_parser("bcd", help="hard or sticky rods in a periodic field (cosine by default) by BCD, against the exact theory")
    _add_rod_flags(bcd)
    bcd.add_argument("--time", type=float, default=1.25, help="sampled time per replica (default 1.25)")
    bcd.add_argument("--equilibrate", type=float, default=0.25, help="BCD time after the Monte Carlo start, before sampling (default 0.25)")
    bcd.add_argument("--extrapolate", action="store_true", help="also run at dt/4 and extrapolate to dt = 0 in sqrt(dt)")
    bcd.add_argument("--out", default="fricgen-bcd", metavar="DIR", help="output folder (default fricgen-bcd)")
    bcd.add_argument("--json", action="store_true", help="print the summary as JSON")
    bcd.set_defaults(run=_bcd)
    return main


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        return args.run(args)
    except (FricgenError, DeriveError) as error:
        print(f"fricgen {args.command}: {error}", file=sys.stderr)
        return getattr(error, "exit_status", 2)
    except KeyboardInterrupt:
        print(f"fricgen {args.command}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
