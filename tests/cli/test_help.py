"""The command line explains itself: every argument of every command has a help text that shows its
default, the time-like options name their unit, each command has examples whose flags exist, the help
prints no reST markup, and ``fricgen --version`` answers."""

import argparse
import importlib
import re
import subprocess
import sys

import pytest

from fricgen import __version__
from fricgen.app.cli.commands import main, parser

from ..test_layers import COMPILING

SKIPPED = (argparse._HelpAction, argparse._VersionAction, argparse._SubParsersAction)
#: Options in a time unit: t0 for the spheres, wavelength^2/D for the rods.
TIMES = {("thermostat-check", "dt"), ("thermostat-check", "time"), ("bcd", "dt"), ("bcd", "time"), ("bcd", "equilibrate")}


def _commands() -> dict[str, argparse.ArgumentParser]:
    top = parser()
    (sub,) = [action for action in top._actions if isinstance(action, argparse._SubParsersAction)]
    return {"": top, **sub.choices}


COMMANDS = _commands()


def _problems(name: str, command: argparse.ArgumentParser) -> list[str]:
    """Arguments of ``fricgen NAME`` without help, without their default, or without their time unit."""
    problems = []
    for action in command._actions:
        if isinstance(action, SKIPPED):
            continue
        flag = "/".join(action.option_strings) or action.metavar or action.dest
        if not action.help or len(action.help.split()) < 2:
            problems.append(f"fricgen {name} {flag} has no help text")
        elif action.default not in (None, [], argparse.SUPPRESS) and not isinstance(action.default, bool) and "default" not in action.help:
            problems.append(f"fricgen {name} {flag}: the help does not show the default {action.default!r}")
        elif (name, action.dest) in TIMES and not re.search(r"\bt0\b|wavelength\^2/D", action.help):
            problems.append(f"fricgen {name} {flag}: the help names no time unit")
    return problems


@pytest.mark.parametrize("name", COMMANDS, ids=lambda name: name or "fricgen")
def test_every_argument_has_help_with_its_default(name):
    assert not _problems(name, COMMANDS[name])


@pytest.mark.parametrize("name", COMMANDS, ids=lambda name: name or "fricgen")
def test_help_has_examples_and_no_markup(name):
    command = COMMANDS[name]
    text = command.format_help()
    assert "``" not in text and ":func:" not in text, text
    assert command.epilog and command.epilog.startswith("examples:\n"), f"fricgen {name} has no examples"
    for line in command.epilog.splitlines()[1:]:
        words = line.split("#")[0].split()
        assert words[0] == "fricgen", line
        target = COMMANDS[words[1]] if words[1] in COMMANDS else COMMANDS[name]
        assert name == "" or words[1] == name, f"an example of fricgen {name} runs another command: {line}"
        known = {flag for action in target._actions for flag in action.option_strings}
        for flag in (word for word in words if word.startswith("--")):
            assert flag in known, f"example {line!r}: no flag {flag}"


def test_version(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0 and capsys.readouterr().out.strip() == f"fricgen {__version__}"


def test_a_negative_control_catches_an_option_without_help():
    """The walk sees an option without help, one hiding its default and a time without its unit."""
    command = _commands()["thermostat-check"]
    command.add_argument("--bare", type=float, default=2.0)
    command.add_argument("--hidden", type=float, default=2.0, help="a value shown bare")
    next(action for action in command._actions if action.dest == "time").help = "simulated time (default 40)"
    assert _problems("thermostat-check", command) == [
        "fricgen thermostat-check --time: the help names no time unit",
        "fricgen thermostat-check --bare has no help text",
        "fricgen thermostat-check --hidden: the help does not show the default 2.0",
    ]


def test_thermostat_check_line_says_what_passed_means(monkeypatch, capsys):
    """The text result names each KL and the criterion (the check's z_limit and kl_limit), without a run."""
    module = importlib.import_module("fricgen.app.studies.thermostat_check")  # fricgen.app exports a function of that name
    result = module.CheckResult("linear", "ito", "baoacb", "pairwise", 2, True, 1.01, 0.01, 0.98, 0.02, 3e-4, 5e-4, True, 100, 1.0, None)
    monkeypatch.setattr(module, "passive_run", lambda *args, **kwargs: (result, None))
    assert main(["thermostat-check", "linear"]) == 0
    line = capsys.readouterr().out
    assert "KL(velocities) = 3.0e-04, KL(spins) = 5.0e-04: passed" in line
    assert "both T within 4 standard errors of kT and both KL below 0.002" in line, line


@pytest.mark.parametrize(
    "command", [["--help"], ["noise", "linear", "--u", "0,1", "--w", "1", "--json"], ["lammps", "linear", "--out", "{tmp}"]], ids=" ".join
)
def test_commands_that_run_no_engine_compile_none(command, tmp_path):
    """The parser's flags (fricgen.rods.config, the thermostat check's defaults), `fricgen noise` (the contact
    mobilities) and `fricgen lammps` read light modules only: none of the engines is loaded, so a fresh install answers
    them in seconds."""
    code = "import sys\nfrom fricgen.app.cli.commands import main\ntry:\n    main(sys.argv[1:])\nfinally:\n    print(*sys.modules)"
    argv = [word.format(tmp=tmp_path / "plugin") for word in command]
    done = subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True, check=True, cwd=tmp_path)
    loaded = set(done.stdout.split())
    assert "fricgen.app.cli.commands" in loaded and not loaded & set(COMPILING), sorted(loaded & set(COMPILING))


def test_the_engines_load_where_they_run():
    """The control of the test above: reading the engines' lazy names loads the modules it watches."""
    check = "import sys, fricgen.langevin, fricgen.rods\nfricgen.langevin.Simulation, fricgen.rods.RodSimulation\nprint(*sys.modules)"
    loaded = subprocess.run([sys.executable, "-c", check], capture_output=True, text=True, check=True).stdout.split()
    assert set(COMPILING) <= set(loaded)
