"""The ``fricgen`` command line: one program, one subcommand per job.

Exit status: 0 done, 1 a physical failure (a failed check, a run that blew up), 2 bad input
(one line on stderr naming the flag or key, the problem and the fix), 130 interrupted. Errors of
fricgen's own family (fricgen.errors), of the symbolic layer (fricgen.derive.errors) and of the argument
parser print one line; anything else is a bug and keeps its traceback. A negative number after a
flag is its value (``--dt -1e-3`` reads as ``--dt=-1e-3``, and the range check answers).
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import typing

from fricgen.derive.calculus import CALCULI
from fricgen.derive.errors import DeriveError

from ...errors import FricgenError
from ..run.outputs import dumps, fail
from . import laws
from .arguments import Parser, UsageError, join_negative_values, named_by_flags
from .lammps import add_lammps_command


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
    from .noise import NoiseQuery, evaluate

    laws.check_law_names([args.law])
    laws.check_calculus(args.law, args.calculus)
    query = NoiseQuery(tuple(args.u), args.r, args.w, args.mu, args.kT)
    with named_by_flags({}):
        result = evaluate(args.law, args.calculus, query, dict(args.param))
    if args.json:
        print(dumps(result))
    else:
        print(f"{args.law} ({args.calculus}), w = {result['w']:g}, mu = {args.mu:g}, kT = {args.kT:g}")
        for x, fx, dx in zip(result["u"], result["f"], result["D"]):
            print(f"u = {x:12.6g}   f = {fx:12.6g}   D = {dx:.12g}")
    return 0


#: The keys of the thermostat check's sections and the flags that set them.
CHECK_FLAGS = {
    "n": "--n",
    "phi": "--phi",
    "dim": "--dim",
    "total_time": "--time",
    "seed": "--seed",
    "run.seed": "--seed",
    "thermostat.dt": "--dt",
    "thermostat.kT": "--kT",
    "law.calculus": "--calculus",
    "law.contact_scheme": "--contact-scheme",
    "law.rolling": "--rolling",
    "law.spinning": "--spinning",
    "law.rolling_parameters": "--rolling-param",
    "law.spinning_parameters": "--spinning-param",
    "law.rolling_noise": "--no-rolling-noise",
    "law.spinning_noise": "--no-spinning-noise",
}


def _thermostat_check(args: argparse.Namespace) -> int:
    """fricgen thermostat-check LAW ...: the statistical test of a law's thermostat, as JSON."""
    from ..studies.thermostat_check import passive_check, passive_run

    named = [args.law, *(name for name in (args.rolling, args.spinning) if name is not None)]
    laws.check_law_names(named)
    for name in named:
        laws.check_calculus(name, args.calculus)
    options = {"dim": args.dim, "calculus": args.calculus, "contact_scheme": args.contact_scheme, "n": args.n, "phi": args.phi}
    options |= {"dt": args.dt, "kT": args.kT, "rolling": args.rolling, "spinning": args.spinning}
    for mode in ("rolling", "spinning"):
        options |= {f"{mode}_parameters": dict(getattr(args, f"{mode}_param")), f"{mode}_noise": not getattr(args, f"no_{mode}_noise")}
    with named_by_flags(CHECK_FLAGS):
        check = passive_check(
            args.law,
            **options,
            contact_noise=not args.no_contact_noise,
            total_time=args.time,
            seed=args.seed,
            parameters=dict(args.param),
            solvent=not args.no_solvent,
        )
        result = passive_run(check)[0]
    if args.json:
        print(dumps(result.as_dict()))
    else:
        r = result
        print(
            f"{r.laws} ({r.calculus}, {r.dim}-D, contact noise {'on' if r.contact_noise else 'off'}): "
            f"T_trans = {r.T_trans:.4f} +- {r.T_trans_err:.4f}, T_rot = {r.T_rot:.4f} +- {r.T_rot_err:.4f}, "
            f"KL = {r.kl_trans:.1e} / {r.kl_rot:.1e}: {'passed' if r.passed else 'FAILED'} ({r.seconds:.1f} s)"
            + ("" if r.rejection_rate is None else f"; {r.contact_scheme} contact step, rejection rate {r.rejection_rate:.2e}")
        )
    return 0 if result.passed else 1


def _demo(args: argparse.Namespace) -> int:
    """fricgen demo [--out DIR] [--json]: the passive check with and without contact noise; plots and JSON.
    Exit status 1 if the run with the contact noise fails the check (the one without is meant to)."""
    from pathlib import Path

    from ..studies.demo import describe, run_demo

    summary = run_demo(Path(args.out))
    print(dumps(summary) if args.json else describe(summary, Path(args.out)))
    return 0 if summary["runs"]["with_contact_noise"]["passed"] else 1  # the consistent thermostat failed its check


def _run(args: argparse.Namespace) -> int:
    """fricgen run CONFIG [--set KEY=VALUE ...] [--steps N] [--out DIR] [--resume CHECKPOINT] [--laws DIR] [--json]."""
    from ..run.runner import execute, plan

    return execute(plan(args.config, args.set, args.steps, args.out, args.resume, args.law_folders), args.json)


def _sweep(args: argparse.Namespace) -> int:
    """fricgen sweep SWEEP [--scheduler ADDRESS] [--workers N] [--out DIR] [--laws DIR] [--json]."""
    from ..sweep.runner import SweepRequest, run_sweep

    return run_sweep(SweepRequest(args.sweep, args.out, args.scheduler, args.workers, tuple(args.law_folders)), args.json)


def _bcd(args: argparse.Namespace) -> int:
    """fricgen bcd ...: hard or sticky rods by BCD against the exact theory; CSV, PNG, JSON summary."""
    from pathlib import Path

    from ...rods.config import rod_config
    from ..studies.rods import Study, study

    values = {name: getattr(args, name) for name in _rod_fields()}
    with named_by_flags(_rod_flags()):
        config = rod_config(**{name: dict(value) if isinstance(value, list) else value for name, value in values.items()})
        summary = study(Study(config, args.time, args.equilibrate, args.extrapolate), Path(args.out), args.force)
    if args.json:
        print(dumps(summary))
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
    "dt": "time step (bias O(dt) with the bridge layer, O(sqrt(dt)) with merge)",
    "seed": "noise seed",
    "start_sweeps": "Monte Carlo sweeps of the equilibrium start",
    "contact_layer": "how a step ends collisions: bridge (Brownian-bridge push, O(dt)), reflect (elastic) or merge (BCD's, O(sqrt(dt)))",
    "replicas": "independent rings run in parallel, the samples of the errors",
    "bins": "bins over one wavelength",
    "gap_width": "bin width of the gap histogram (contact density)",
    "gap_bins": "bins of the gap histogram",
    "fit_bins": "gap bins fitted beyond the BCD layer",
}


def _rod_fields() -> dict:
    from ...rods.config import PARTS
    from ...schema import flat_fields

    return flat_fields(*PARTS)


def _rod_flags() -> dict[str, str]:
    """The flag of each field of the rod configuration, by its key (``numerics.dt``) and by its name
    (``--NAME`` with dashes; ``--field-param`` for the table ``field_params``)."""
    flags = {}
    for name, (section, _) in _rod_fields().items():
        hint = typing.get_type_hints(section)[name]
        flag = "--" + (name.removesuffix("s") if typing.get_origin(hint) is dict else name).replace("_", "-")
        flags[name] = flags[f"{section.SECTION}.{name}"] = flag
    return flags


def _add_rod_flags(command: argparse.ArgumentParser) -> None:
    """One flag per field of the rod configuration, with its type and default: ``--NAME`` (dashes for
    underscores), and ``--field-param NAME=VALUE`` (repeated) for the tables of parameters."""
    flags = _rod_flags()
    for name, (section, f) in _rod_fields().items():
        hint = typing.get_type_hints(section)[name]
        default = f.default if f.default is not dataclasses.MISSING else f.default_factory()
        text = f"{ROD_HELP[name]} (default {default})"
        if typing.get_origin(hint) is dict:
            command.add_argument(
                flags[name], dest=name, type=_assignment, action="append", default=[], metavar="NAME=VALUE", help=ROD_HELP[name]
            )
        else:
            kind = next(t for t in (int, float, str) if t is hint or t in typing.get_args(hint))
            command.add_argument(flags[name], type=kind, default=default, help=text)


def parser() -> argparse.ArgumentParser:
    from ...langevin.config import CONTACT_SCHEMES, Thermostat

    main = Parser(prog="fricgen", description=__doc__)
    commands = main.add_subparsers(dest="command", required=True)
    verify = commands.add_parser("verify", help="derive D(u, r) for catalogue laws and verify zero probability current")
    verify.add_argument("laws", nargs="*", metavar="LAW", help="law names (default: the laws of your law folders, else the catalogue)")
    verify.add_argument("--calculus", choices=(*CALCULI, "all"), default="all")
    verify.add_argument("--json", action="store_true", help="print one JSON array, one object per law and calculus")
    laws.add_laws_flag(verify)
    verify.set_defaults(run=laws.verify)

    generate = commands.add_parser(
        "generate", help="derive, verify and emit Numba kernels into generated/ (of the package, or beside your --laws folder)"
    )
    generate.add_argument("laws", nargs="*", metavar="LAW", help="law names (default: the laws of your law folders, else the catalogue)")
    generate.add_argument("--output", metavar="DIR", help="emit into DIR instead of the laws' generated/ (for inspection)")
    laws.add_laws_flag(generate)
    generate.set_defaults(run=laws.generate)

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
    laws.add_laws_flag(noise)
    noise.set_defaults(run=_noise)

    check = commands.add_parser("thermostat-check", help="statistical test: does the law thermalise a passive system to kT?")
    check.add_argument("law", metavar="LAW", help="the law, on the contact mode its file names (sliding by default)")
    check.add_argument("--rolling", metavar="LAW", help='a law on the rolling mode besides LAW (its file says mode = "rolling")')
    check.add_argument("--spinning", metavar="LAW", help='a law on the spinning mode besides LAW (3-D only; mode = "spinning")')
    check.add_argument("--dim", type=int, choices=(2, 3), default=2)
    check.add_argument("--calculus", choices=CALCULI, default="ito")
    check.add_argument("--no-contact-noise", action="store_true", help="drop the frictional noise (the inconsistent model)")
    check.add_argument("--no-solvent", action="store_true", help="friction thermostat alone (gamma = gamma_R = 0)")
    check.add_argument(
        "--contact-scheme",
        choices=CONTACT_SCHEMES,
        default="pairwise",
        help="pairwise: Metropolis-adjusted, kT at any dt, reports its rejection rate (default); explicit: the kick where a wrong D shows",
    )
    check.add_argument("--n", type=int, help="particles (default 256 in 2-D, 216 in 3-D)")
    check.add_argument("--phi", type=float, help="packing fraction (default 0.6 in 2-D, 0.3 in 3-D)")
    check.add_argument("--dt", type=float, default=Thermostat.dt, help=f"time step (default {Thermostat.dt})")
    check.add_argument("--kT", type=float, default=Thermostat.kT, help=f"thermal energy, the temperature checked (default {Thermostat.kT})")
    check.add_argument("--time", type=float, default=40.0, help="simulated time (the first 10%% equilibrates)")
    check.add_argument("--seed", type=int, default=1)
    check.add_argument("--param", type=_assignment, action="append", default=[], metavar="NAME=VALUE")
    for mode in ("rolling", "spinning"):
        check.add_argument(
            f"--{mode}-param", type=_assignment, action="append", default=[], metavar="NAME=VALUE", help=f"of the {mode} law"
        )
        check.add_argument(f"--no-{mode}-noise", action="store_true", help=f"drop the {mode} law's noise alone (a negative control)")
    check.add_argument("--json", action="store_true")
    laws.add_laws_flag(check)
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
    laws.add_laws_flag(run)
    run.set_defaults(run=_run)

    sweep = commands.add_parser("sweep", help="a grid of runs over a base configuration, as Dask tasks (a local cluster or --scheduler)")
    sweep.add_argument("sweep", metavar="SWEEP", help="a sweep TOML file (docs/sweeps.md) or the name of a bundled sweep: mips")
    sweep.add_argument("--scheduler", metavar="ADDRESS", help="a running Dask scheduler, e.g. tcp://host:8786 (default: a local cluster)")
    sweep.add_argument("--workers", type=int, metavar="N", help="worker processes of the local cluster (default: one per CPU it may use)")
    sweep.add_argument("--out", metavar="DIR", help="output folder (default fricgen-sweep-<sweep name>)")
    sweep.add_argument("--json", action="store_true", help="print the results as JSON")
    laws.add_laws_flag(sweep)
    sweep.set_defaults(run=_sweep)

    bcd = commands.add_parser("bcd", help="hard or sticky rods in a periodic field (cosine by default) by BCD, against the exact theory")
    _add_rod_flags(bcd)
    bcd.add_argument("--time", type=float, default=1.25, help="sampled time per replica (default 1.25)")
    bcd.add_argument("--equilibrate", type=float, default=0.25, help="BCD time after the Monte Carlo start, before sampling (default 0.25)")
    bcd.add_argument("--extrapolate", action="store_true", help="also run at dt/4 and extrapolate to dt = 0 (in dt; in sqrt(dt) for merge)")
    bcd.add_argument("--out", default="fricgen-bcd", metavar="DIR", help="output folder (default fricgen-bcd)")
    bcd.add_argument("--force", action="store_true", help="replace the result that --out holds already")
    bcd.add_argument("--json", action="store_true", help="print the summary as JSON")
    bcd.set_defaults(run=_bcd)
    add_lammps_command(commands)
    return main


def main(argv: list[str] | None = None) -> int:
    words = join_negative_values(list(sys.argv[1:] if argv is None else argv))
    prog = "fricgen"
    try:
        args = parser().parse_args(words)
        prog = f"fricgen {args.command}"
        with laws.law_search(args):
            status = args.run(args)
        sys.stdout.flush()  # a closed stdout shows here, not in the interpreter's exit
        return status
    except UsageError as error:
        return fail(error.prog, error, 2)
    except (FricgenError, DeriveError) as error:
        return fail(prog, error, getattr(error, "exit_status", 2))
    except KeyboardInterrupt:
        return fail(prog, "interrupted", 130)
    except BrokenPipeError:
        return _closed_stdout(prog)


def _closed_stdout(prog: str) -> int:
    """The reader of stdout went away (``fricgen ... --json | head -c0``): what was computed is
    lost to it, which is its choice; say so on one line, exit 2, and point stdout at /dev/null so
    that the interpreter's final flush does not raise BrokenPipeError again."""
    import os

    try:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except (OSError, ValueError):  # no real file behind sys.stdout (captured output)
        pass
    return fail(prog, "stdout was closed before the output was written", 2)


if __name__ == "__main__":
    sys.exit(main())
