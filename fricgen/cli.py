"""The ``fricgen`` command line: one program, one subcommand per job."""

from __future__ import annotations

import argparse
import json
import sys

from derive.lawdata import CALCULI

DEFAULT_BCD_DT = 2.5e-6


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


def _generate(args: argparse.Namespace) -> int:
    """fricgen generate [LAW ...]: derive, verify and emit kernels (idempotent)."""
    from derive.emit import GENERATED, GenerationError, generate
    from derive.laws import LawError

    try:
        written, reports = generate(args.laws or None, output=args.output or GENERATED)
    except (GenerationError, LawError) as error:
        print(f"fricgen generate: {error}", file=sys.stderr)
        return 1
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

    from fricgen.kernels import KernelError, load_law_kernels

    try:
        kernels = load_law_kernels(args.law)
        params = kernels.parameters(**dict(args.param))
        kernels.noise_amplitude(args.calculus)
    except KernelError as error:
        print(f"fricgen noise: {error}", file=sys.stderr)
        return 2
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
    from fricgen.kernels import KernelError
    from fricgen.simulation import SimulationError
    from fricgen.thermostat_check import thermostat_check

    try:
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
    except (KernelError, SimulationError, ValueError) as error:
        print(f"fricgen thermostat-check: {error}", file=sys.stderr)
        return 2
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

    from fricgen.demo import describe, run_demo

    try:
        summary = run_demo(Path(args.out))
    except KeyboardInterrupt:
        print("fricgen demo: interrupted; nothing written", file=sys.stderr)
        return 130
    print(json.dumps(summary, indent=2) if args.json else describe(summary, Path(args.out)))
    return 0


def _run(args: argparse.Namespace) -> int:
    """fricgen run CONFIG [--set KEY=VALUE ...] [--steps N] [--out DIR] [--resume CHECKPOINT] [--json]."""
    from fricgen.runner import command

    try:
        return command(args.config, args.set, args.steps, args.out, args.resume, args.json)
    except KeyboardInterrupt:
        print("fricgen run: interrupted before the run started; nothing written", file=sys.stderr)
        return 130


def _bcd(args: argparse.Namespace) -> int:
    """fricgen bcd ...: hard or sticky rods by BCD against the exact theory; CSV, PNG, JSON summary."""
    from pathlib import Path

    from fricgen.rods import RodConfig
    from fricgen.rods_run import study

    names = ("n", "length", "sigma", "U0", "field", "gamma", "p", "eps", "dt", "seed", "replicas", "bins")
    try:
        pair = {"pair": args.pair, "pair_params": dict(args.pair_param), "pair_range": args.pair_range}
        config = RodConfig(**{name: getattr(args, name) for name in names}, field_params=dict(args.field_param), **pair)
        if not (args.time > 0 and args.equilibrate >= 0):
            raise ValueError("--time must be positive and --equilibrate >= 0")
        summary = study(config, args.time, args.equilibrate, Path(args.out), extrapolate=args.extrapolate)
    except (ValueError, RuntimeError, LookupError) as error:
        print(f"fricgen bcd: {error}", file=sys.stderr)
        return 2
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(
            f"L1/rho_bar = {summary['l1_dev_over_rho']:.4f}, max |d rho| = {summary['max_abs_dev']:.4f}, "
            f"chi2/bin = {summary['chi2_per_dof']:.2f} ({summary['steps']} steps, {summary['seconds']:.1f} s); wrote {args.out}/"
        )
    return 0


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
    bcd.add_argument("--n", type=int, default=50, help="rods per ring (default 50)")
    bcd.add_argument("--length", type=float, default=100.0, help="ring length L in wavelengths (default 100)")
    bcd.add_argument("--sigma", type=float, default=0.5, help="rod length (default 0.5)")
    bcd.add_argument("--U0", type=float, default=6.0, help="amplitude of the field in kT, U = (U0/2) cos(2 pi x) by default (default 6)")
    bcd.add_argument("--field", default="cosine", help="a generated external potential (default cosine; also ratchet)")
    bcd.add_argument("--field-param", type=_assignment, action="append", default=[], metavar="NAME=VALUE", help="other field parameters")
    bcd.add_argument("--gamma", type=float, default=0.0, help="Baxter stickiness (default 0: hard rods)")
    bcd.add_argument("--p", type=float, default=3.0, help="exponent of the delta_eps representation (B-31)")
    bcd.add_argument("--eps", type=float, default=0.05, help="range of the delta_eps representation (B-31)")
    bcd.add_argument("--pair", help="a generated pair potential V(r) between neighbours instead of the sticky contact (e.g. wca)")
    bcd.add_argument("--pair-param", type=_assignment, action="append", default=[], metavar="NAME=VALUE", help="its parameters")
    bcd.add_argument("--pair-range", type=float, default=0.0, help="gap beyond sigma where the pair potential ends (< sigma)")
    bcd.add_argument("--dt", type=float, default=DEFAULT_BCD_DT, help=f"time step (default {DEFAULT_BCD_DT:g}; bias O(sqrt(dt)))")
    bcd.add_argument("--time", type=float, default=1.25, help="sampled time per replica (default 1.25)")
    bcd.add_argument("--equilibrate", type=float, default=0.25, help="BCD time after the Monte Carlo start, before sampling (default 0.25)")
    bcd.add_argument("--seed", type=int, default=1)
    bcd.add_argument("--replicas", type=int, default=16, help="independent rings run in parallel, the samples of the errors (default 16)")
    bcd.add_argument("--bins", type=int, default=50, help="bins over one wavelength (default 50)")
    bcd.add_argument("--extrapolate", action="store_true", help="also run at dt/4 and extrapolate to dt = 0 in sqrt(dt)")
    bcd.add_argument("--out", default="fricgen-bcd", metavar="DIR", help="output folder (default fricgen-bcd)")
    bcd.add_argument("--json", action="store_true", help="print the summary as JSON")
    bcd.set_defaults(run=_bcd)
    return main


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    return args.run(args)


if __name__ == "__main__":
    sys.exit(main())
