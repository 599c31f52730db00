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
import functools
import sys
import typing
import warnings

from fricgen.derive.calculus import CALCULI
from fricgen.derive.errors import DeriveError

from ... import __version__
from ...errors import ConfigError, FricgenError
from ..run.outputs import dumps, fail
from . import laws
from .arguments import Parser, UsageError, add_command, join_negative_values, named_by_flags
from .help import DESCRIPTION, EXAMPLES, ROD_HELP, T0
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
    from ...kernels import load_law_kernels
    from .noise import NoiseQuery, default_mobility, evaluate

    laws.check_law_names([args.law], args.search)
    laws.check_calculus(args.law, args.calculus, args.search)
    kernels = load_law_kernels(args.law, args.search)
    mu = default_mobility(kernels.mode) if args.mu is None else args.mu  # the mobility of the law's own mode
    query = NoiseQuery(tuple(args.u), args.r, args.w, mu, args.kT)
    with named_by_flags({}):
        result = evaluate(kernels, args.calculus, query, dict(args.param))
    if args.json:
        print(dumps(result))
    else:
        source = "--mu" if args.mu is not None else f"the {kernels.mode} mobility of two spheres m = 1, R = 1/2"
        print(f"{args.law} ({args.calculus}, {kernels.mode} mode), w = {result['w']:g}, mu = {mu:g} ({source}), kT = {args.kT:g}")
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
    from ...kernels import load_law_kernels
    from ..run.build import resolve_law
    from ..studies.thermostat_check import passive_check, passive_run

    named = [args.law, *(name for name in (args.rolling, args.spinning) if name is not None)]
    laws.check_law_names(named, args.search)
    for name in named:
        laws.check_calculus(name, args.calculus, args.search)
    own = load_law_kernels(args.law, args.search).mode
    for mode in ("rolling", "spinning"):
        if getattr(args, f"no_{mode}_noise") and getattr(args, mode) is None:
            fix = f"give the {mode} law with --{mode} NAME, or leave --no-{mode}-noise away"
            if own == mode:  # LAW is itself the mode's law: no --{mode} law to drop the noise of
                fix = f"LAW {args.law} is itself a {mode} law, the only law here: drop its noise with --no-contact-noise"
            raise ConfigError(f"--no-{mode}-noise", f"drops the noise of the law that --{mode} gives, and none is given", fix)
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
        result = passive_run(check, resolve_law(check.law, check.dim, args.search))[0]
    if args.json:
        print(dumps(result.as_dict()))
    else:
        r = result
        print(
            f"{r.laws} ({r.calculus}, {r.dim}-D, contact noise {'on' if r.contact_noise else 'off'}): "
            f"T_trans = {r.T_trans:.4f} +- {r.T_trans_err:.4f}, T_rot = {r.T_rot:.4f} +- {r.T_rot_err:.4f} (kT = {check.thermostat.kT:g}), "
            f"KL(velocities) = {r.kl_trans:.1e}, KL(spins) = {r.kl_rot:.1e}: {'passed' if r.passed else 'FAILED'} "
            f"(passed: both T within {check.z_limit:g} standard errors of kT and both KL below {check.kl_limit:g}; {r.seconds:.1f} s)"
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

    return execute(plan(args.config, args.set, args.steps, args.out, args.resume, args.search), args.json)


def _sweep(args: argparse.Namespace) -> int:
    """fricgen sweep SWEEP [--scheduler ADDRESS] [--workers N] [--out DIR] [--laws DIR] [--json]."""
    from ..sweep.runner import SweepRequest, run_sweep

    return run_sweep(SweepRequest(args.sweep, args.out, args.scheduler, args.workers, args.search, args.rerun_stale), args.json)


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
        rejected = f", {summary['rejected_fraction']:.1%} of the steps rejected" if "rejected_fraction" in summary else ""
        print(
            f"L1/rho_bar = {summary['l1_dev_over_rho']:.4f}, max |d rho| = {summary['max_abs_dev']:.4f}, "
            f"chi2/bin = {summary['chi2_per_dof']:.2f} ({summary['steps']} steps{rejected}, {summary['seconds']:.1f} s); wrote {args.out}/"
        )
    return 0


def _warning_line(prog: str, message, category, filename, lineno, file=None, line=None) -> None:
    """A warning of a command as one line on stderr, ``fricgen CMD: warning: ...`` (not Python's two,
    with the source line)."""
    print(f"{prog}: warning: {' '.join(str(message).split())}", file=sys.stderr)


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
        text = f"{ROD_HELP[name]} (default {'none' if default is None else default})"
        if typing.get_origin(hint) is dict:
            command.add_argument(
                flags[name], dest=name, type=_assignment, action="append", default=[], metavar="NAME=VALUE", help=ROD_HELP[name]
            )
        else:
            kind = next(t for t in (int, float, str) if t is hint or t in typing.get_args(hint))
            command.add_argument(flags[name], type=kind, default=default, help=text)


def _param_flag(command: argparse.ArgumentParser, flag: str, text: str) -> None:
    """A repeatable ``FLAG NAME=VALUE`` (law parameters)."""
    command.add_argument(flag, type=_assignment, action="append", default=[], metavar="NAME=VALUE", help=text)


def _command(commands, name: str, help: str) -> argparse.ArgumentParser:
    return add_command(commands, name, help, EXAMPLES[name])


def parser() -> argparse.ArgumentParser:
    from ...langevin.config import CONTACT_SCHEMES, Thermostat
    from ..studies.thermostat_check import PassiveCheck

    main = Parser(
        prog="fricgen", description=DESCRIPTION, epilog="examples:\n" + EXAMPLES[""], formatter_class=argparse.RawDescriptionHelpFormatter
    )
    main.add_argument("--version", action="version", version=f"%(prog)s {__version__}", help="print the version and exit")
    commands = main.add_subparsers(dest="command", required=True, metavar="COMMAND")
    law_names = "law names (default: the laws of your law folders, else the built-in catalogue)"
    verify = _command(commands, "verify", "derive D(u, r) for laws and verify zero probability current")
    verify.add_argument("laws", nargs="*", metavar="LAW", help=law_names)
    verify.add_argument("--calculus", choices=(*CALCULI, "all"), default="all", help="the calculus of D to verify (default all)")
    verify.add_argument("--json", action="store_true", help="print one JSON array, one object per law and calculus")
    laws.add_laws_flag(verify)
    verify.set_defaults(run=laws.verify)

    generate = _command(
        commands, "generate", "derive, verify and emit Numba kernels into generated/ (of the package, or beside your --laws folder)"
    )
    generate.add_argument("laws", nargs="*", metavar="LAW", help=law_names)
    generate.add_argument("--output", metavar="DIR", help="emit into DIR instead of the laws' generated/ (for inspection)")
    laws.add_laws_flag(generate)
    generate.set_defaults(run=laws.generate)

    noise = _command(commands, "noise", "evaluate D(u) of a law through its generated kernels")
    noise.add_argument("law", metavar="LAW", help="the law's name (fricgen generate made its kernels)")
    noise.add_argument("--calculus", choices=CALCULI, default="ito", help="the calculus of D (default ito)")
    noise.add_argument("--u", type=_floats, required=True, help="comma-separated tangential speeds u >= 0, in sigma/t0")
    where = noise.add_mutually_exclusive_group()
    where.add_argument("--r", type=float, help="centre distance, in sigma; w = w(r) from the law's weight")
    where.add_argument("--w", type=float, help="the weight w directly, in the unit of the law's weight (kT/sigma for -dU_WCA/dr)")
    _param_flag(noise, "--param", "a law parameter, repeatable (default: the law file's)")
    noise.add_argument(
        "--mu",
        type=float,
        help="mobility of the law's contact mode, in 1/m (default: that of two spheres m = 1, R = 1/2, I = (2/5) m R^2: 7 for a"
        " sliding law, 1.25 for a rolling or spinning one)",
    )
    noise.add_argument("--kT", type=float, default=1.0, help="thermal energy, in kT (default 1)")
    noise.add_argument("--json", action="store_true", help="print JSON with u, D, f, w, r, mu, kT, parameters and the law's mode")
    laws.add_laws_flag(noise)
    noise.set_defaults(run=_noise)

    check = _command(commands, "thermostat-check", "statistical test: does the law thermalise a passive system to kT?")
    check.add_argument("law", metavar="LAW", help="the law, on the contact mode its file names (sliding by default)")
    check.add_argument("--rolling", metavar="LAW", help='a law on the rolling mode besides LAW (its file says mode = "rolling")')
    check.add_argument("--spinning", metavar="LAW", help='a law on the spinning mode besides LAW (3-D only; mode = "spinning")')
    check.add_argument("--dim", type=int, choices=(2, 3), default=PassiveCheck.dim, help=f"dimension (default {PassiveCheck.dim})")
    check.add_argument("--calculus", choices=CALCULI, default="ito", help="the calculus of D (default ito)")
    check.add_argument("--no-contact-noise", action="store_true", help="drop the frictional noise (the inconsistent model)")
    check.add_argument("--no-solvent", action="store_true", help="friction thermostat alone (gamma = gamma_R = 0)")
    check.add_argument(
        "--contact-scheme",
        choices=CONTACT_SCHEMES,
        default="pairwise",
        help="pairwise: Metropolis-adjusted, kT at any dt, reports its rejection rate (default); explicit: the kick where a wrong D shows",
    )
    check.add_argument("--n", type=int, help="number of spheres (default 256 in 2-D, 216 in 3-D)")
    check.add_argument("--phi", type=float, help="packing fraction, area in 2-D, volume in 3-D (default 0.6 in 2-D, 0.3 in 3-D)")
    check.add_argument("--dt", type=float, default=Thermostat.dt, help=f"time step, in {T0} (default {Thermostat.dt})")
    check.add_argument("--kT", type=float, default=Thermostat.kT, help=f"thermal energy checked, in kT (default {Thermostat.kT})")
    time = PassiveCheck.total_time
    check.add_argument("--time", type=float, default=time, help=f"simulated time in t0, 10%% to equilibrate (default {time:g})")
    check.add_argument("--seed", type=int, default=PassiveCheck.seed, help=f"noise seed, an integer (default {PassiveCheck.seed})")
    _param_flag(check, "--param", "a parameter of LAW, repeatable (default: the law file's)")
    for mode in ("rolling", "spinning"):
        _param_flag(check, f"--{mode}-param", f"a parameter of the {mode} law, repeatable (default: its file's)")
        check.add_argument(f"--no-{mode}-noise", action="store_true", help=f"drop the {mode} law's noise alone (a negative control)")
    check.add_argument("--json", action="store_true", help="print the result as JSON (temperatures, errors, KL divergences, passed)")
    laws.add_laws_flag(check)
    check.set_defaults(run=_thermostat_check)

    demo = _command(commands, "demo", "the main job: 2-D passive Coulomb-Newton system with and without contact noise")
    demo.add_argument("--out", default="fricgen-demo", metavar="DIR", help="output folder (default fricgen-demo)")
    demo.add_argument("--json", action="store_true", help="print the summary as JSON")
    demo.set_defaults(run=_demo)

    run = _command(commands, "run", "a simulation from a TOML configuration (or a bundled example: passive, poiseuille, active)")
    run.add_argument("config", metavar="CONFIG", help="a TOML file or the name of a bundled example")
    run.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE", help="override a key (TOML value), repeatable")
    run.add_argument("--steps", type=int, help="override run.steps (default: the file's)")
    run.add_argument("--out", metavar="DIR", help="output folder (default fricgen-<config name>)")
    run.add_argument("--resume", metavar="CHECKPOINT", help="continue from DIR/checkpoint.npz of a stopped run")
    run.add_argument("--json", action="store_true", help="print the summary as JSON")
    laws.add_laws_flag(run)
    run.set_defaults(run=_run)

    sweep = _command(commands, "sweep", "a grid of runs over a base configuration, as Dask tasks (a local cluster or --scheduler)")
    sweep.add_argument("sweep", metavar="SWEEP", help="a sweep TOML file (docs/sweeps.md) or the name of a bundled sweep: mips")
    sweep.add_argument("--scheduler", metavar="ADDRESS", help="a running Dask scheduler, e.g. tcp://host:8786 (default: a local cluster)")
    sweep.add_argument("--workers", type=int, metavar="N", help="worker processes of the local cluster (default: one per CPU it may use)")
    sweep.add_argument("--out", metavar="DIR", help="output folder (default fricgen-sweep-<sweep name>)")
    sweep.add_argument(
        "--rerun-stale",
        action="store_true",
        help="run afresh the points whose checkpoints record other versions of their laws than this run's (default: refuse them)",
    )
    sweep.add_argument("--json", action="store_true", help="print the results as JSON")
    laws.add_laws_flag(sweep)
    sweep.set_defaults(run=_sweep)

    bcd = _command(commands, "bcd", "hard or sticky rods in a periodic field (cosine by default) by BCD, against the exact theory")
    _add_rod_flags(bcd)
    bcd.add_argument("--time", type=float, default=1.25, help="sampled time per replica, in wavelength^2/D (default 1.25)")
    bcd.add_argument("--equilibrate", type=float, default=0.25, help="time before sampling, in wavelength^2/D (default 0.25)")
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
        if hasattr(args, "law_folders"):  # a command that takes laws: its search, built here once
            args.search = laws.law_search(args)
        with warnings.catch_warnings():
            warnings.showwarning = functools.partial(_warning_line, prog)
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
