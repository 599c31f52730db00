"""The bad-input corpus (tests/inputs/cases.py): every row exits with status 2 and one line on stderr
that names the flag or key, writes no file, and starts no simulation and no derivation.

The cases run in-process through ``fricgen.app.cli.main``. Simulations and derivations are replaced
by a trap that raises: a check that went missing makes its case fail at once (instead of running a
simulation), and :func:`test_the_trap_catches_valid_input` shows that valid input does reach it.
"""

import json
import os
import re
import subprocess
import sys
import types
from pathlib import Path

import pytest

from fricgen.app.cli import main

from .cases import FILES, argv, cases
from .traps import Started, stop, trap_simulations

CASES = cases()


@pytest.fixture(autouse=True)
def trap(monkeypatch):
    """Simulations (Langevin runs, the run command's execution, the rods' Monte Carlo start) and the
    symbolic layer's derivations raise Started."""
    trap_simulations(monkeypatch)
    fakes = {
        "fricgen.derive.driver": {"generate": stop, "verify": stop, "GENERATED": Path("generated")},
        "fricgen.derive.noise.derivation": {"derive_noise": stop},
        "fricgen.derive.noise.verification": {"prove": stop},
        "fricgen.derive.law.law_files": {"catalogue": stop, "load_law": stop},
    }
    for name, attributes in fakes.items():
        monkeypatch.setitem(sys.modules, name, types.SimpleNamespace(**attributes))


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    """The folder of the files the rows refer to as {in}."""
    folder = tmp_path_factory.mktemp("inputs")
    for name, content in FILES.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_bytes(content)
    return folder


def snapshot(*folders: Path) -> dict:
    """Every file and folder under ``folders`` with its size and modification time."""
    found = {}
    for folder in folders:
        for root, dirs, files in os.walk(folder):
            for name in dirs + files:
                path = Path(root, name)
                found[path] = (path.is_dir(), path.stat().st_size if path.is_file() else 0, path.stat().st_mtime_ns)
    return found


@pytest.mark.parametrize(("args", "key", "piece"), CASES, ids=[row[0] or "(nothing)" for row in CASES])
def test_bad_input(args, key, piece, inputs, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    before = snapshot(inputs, tmp_path)
    status = main(argv(args, str(inputs)))
    out, err = capsys.readouterr()
    assert status == 2, (status, err)
    lines = err.splitlines()
    assert len(lines) == 1 and err.endswith("\n"), err
    line = lines[0]
    assert line.startswith("fricgen") and "Traceback" not in line, line
    assert re.search(rf"(?<![\w.-]){re.escape(key)}(?!\w)", line) and piece in line, line
    assert out == ""
    assert snapshot(inputs, tmp_path) == before, "files were written"


def test_the_corpus_is_large_and_covers_every_command():
    commands = {args.split()[0] if args else "" for args, _, _ in CASES}
    assert len(CASES) >= 150 and {"noise", "thermostat-check", "run", "demo", "bcd", "verify", "generate"} <= commands
    assert len({args for args, _, _ in CASES}) == len(CASES), "a row is repeated"


@pytest.mark.parametrize(
    "args",
    [
        "bcd --n 20",
        "thermostat-check linear --n 16 --kT 2",
        "run {in}/good.toml",
        "demo --out fresh",
        "verify linear",
        "generate linear --output fresh",
    ],
)
def test_the_trap_catches_valid_input(args, tmp_path, monkeypatch):
    """The rows fail before the trap: valid input runs into it (so a missing check cannot go unseen)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "good.toml").write_text('[system]\nn = 64\npacking_fraction = 0.6\n[law]\nname = "linear"\n')
    with pytest.raises(Started):
        main(argv(args, str(tmp_path)))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["good.toml"]


def test_noise_json_is_json_and_refuses_what_is_not_finite(capsys):
    assert main(["noise", "linear", "--u", "0,1,1e300", "--r", "1.05", "--json"]) == 0
    result = json.loads(capsys.readouterr().out, parse_constant=lambda word: pytest.fail(f"{word} is not JSON"))
    assert result["D"][0] == result["D"][2] > 0
    assert main(["noise", "viscous_cubic", "--u", "1e300", "--r", "1.05", "--json"]) == 2
    assert "D: is inf at u = 1e+300" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("args", "piece"),
    [
        (["bcd", "--dt", "-1e-3"], "fricgen bcd: --dt: must be positive and finite, got -0.001"),
        (["run", "{in}/latin1.toml"], "latin1.toml: not UTF-8 text"),
    ],
)
def test_in_a_fresh_process(args, piece, inputs, tmp_path):
    """Through ``python -m fricgen``: sys.argv, the exit status of the process, no traceback."""
    command = [sys.executable, "-m", "fricgen", *(word.replace("{in}", str(inputs)) for word in args)]
    done = subprocess.run(command, capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert done.returncode == 2 and done.stdout == "" and not any(tmp_path.iterdir())
    assert done.stderr.count("\n") == 1 and piece in done.stderr, done.stderr
