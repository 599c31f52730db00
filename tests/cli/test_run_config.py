"""`fricgen run CONFIG`: the bundled examples (shrunk), one clear message per bad configuration with
nothing written, Ctrl-C at a chunk boundary with a valid trajectory, and a bit-exact resume."""

import json
import math
import shlex
import shutil
import signal
import subprocess
import sys
import time

import gsd.hoomd
import numpy as np
import pytest

from fricgen.app.cli import main
from fricgen.app.run.config import example_names, load_config, resolve_source

#: Overrides that shrink an example to a run of seconds.
SMALL = {
    "passive": ["--set", "system.n=64", "--set", "run.equilibrate=200"],
    "poiseuille": ["--set", "system.n=150", "--set", "system.box=[12.0, 18.1694, 6.0]", "--set", "run.equilibrate=200"],
    "active": ["--set", "system.n=100", "--set", "run.equilibrate=200"],
}
EVERY = [
    "--set",
    "run.chunk=100",
    "--set",
    "output.period=100",
    "--set",
    "output.trajectory_period=200",
    "--set",
    "output.checkpoint_period=0",
]


def fricgen(*args, **options):
    return subprocess.run([sys.executable, "-m", "fricgen", *args], capture_output=True, text=True, timeout=600, **options)


def frames(path):
    with gsd.hoomd.open(str(path), "r") as trajectory:
        return [int(frame.configuration.step) for frame in trajectory]


def test_examples_carry_the_papers_parameters():
    assert example_names() == ["active", "passive", "poiseuille"]
    passive, slit, active = (load_config(resolve_source(name)) for name in ("passive", "poiseuille", "active"))
    assert (passive.system.dimension, passive.system.packing_fraction, passive.thermostat.dt) == (2, 0.6, 1e-3)
    assert passive.thermostat.gamma == pytest.approx(3 * math.pi) and passive.thermostat.gamma_rot == pytest.approx(math.pi)
    assert slit.walls.half_width == 8.5847 and slit.thermostat.gamma == 0 and slit.bulk.force == (0.01, 0.0, 0.0)
    accessible = slit.system.box[0] * 2 * (slit.walls.half_width - 2 * slit.system.radius) * slit.system.box[2]
    assert slit.system.n * math.pi / 6 / accessible == pytest.approx(0.15, abs=1e-4)  # volume fraction 0.15 (F sec. II B 2)
    assert (active.system.mass, active.system.epsilon, active.thermostat.dt, active.law.parameters) == (
        0.05,
        10.0,
        1e-5,
        {"gamma_f": 1.0, "kappa_f": 1.0},
    )


@pytest.mark.parametrize("name", ["passive", "poiseuille", "active"])
def test_bundled_examples_run_shrunk(name, tmp_path):
    out = tmp_path / name
    done = fricgen("run", name, "--out", str(out), "--steps", "600", *SMALL[name], *EVERY, "--json")
    assert done.returncode == 0, done.stderr
    summary = json.loads(done.stdout)
    assert summary["steps"] == 600 and json.loads((out / "summary.json").read_text()) == summary
    assert frames(out / "trajectory.gsd") == [0, 200, 400, 600]
    assert "step/s" in done.stderr  # the progress bar
    rows = np.loadtxt(out / "temperatures.csv", delimiter=",", skiprows=1)
    assert rows[:, 0].tolist() == list(range(0, 601, 100)) and np.all(rows[:, 2:] > 0)
    assert summary["T_trans"]["samples"] == 4 and summary["T_trans"]["mean"] > 0
    if name == "poiseuille":
        profile = summary["velocity_profile"]
        inside = np.abs(profile["y"]) < 8.5847 - 1.5
        assert summary["walls"] > 0 and all(v is not None for v, i in zip(profile["v_x"], inside) if i)
        assert all(v is None for v, y in zip(profile["v_x"], profile["y"]) if abs(y) > 8.5847)  # beyond the walls


def test_a_config_file_by_path(tmp_path):
    config = tmp_path / "mine.toml"
    config.write_text('[system]\nn = 36\npacking_fraction = 0.4\n[law]\nname = "linear"\n[run]\nsteps = 200\nchunk = 100\n'
                      "[output]\nperiod = 100\ntrajectory_period = 0\n")  # fmt: skip
    assert main(["run", str(config), "--out", str(tmp_path / "out")]) == 0
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["checkpoint.npz", "config.json", "summary.json", "temperatures.csv"]


#: Bad settings (space-separated --set overrides) | the key the message must name | a piece of the message.
BAD = [
    row.split(" | ")
    for row in """
system.nn=64 | system.nn | did you mean 'n'
sytem.n=64 | [sytem] | did you mean 'system'
system.n="64" | system.n | must be an integer
law.contact_noise=1 | law.contact_noise | true or false
system.packing_fraction=0.95 | system.packing_fraction | close packing is 0.9069
system.packing_fraction=0.85 | system.packing_fraction | too high for a lattice start
system.packing_fraction=0.6 system.start=random | system.packing_fraction | start = "lattice"
thermostat.dt=-0.001 | thermostat.dt | must be positive
law.name=no_such_law | law.name | coulomb_newton
law.name=coulomb law.calculus=hk | law.calculus | 'ito'
law.parameters.beta_f=1.0 | law.parameters.beta_f | gamma_f
law.parameters.gamma_f=-1.0 | law.parameters.gamma_f | positive
law.parameters.sigma=1.2 | law.parameters.sigma | set by the radii
output.period=150 | output.period | multiple of run.chunk
output.observables=["pressure"] | output.observables | velocity_profile
walls.half_width=5.0 | system.box | slab walls need an explicit box
run.equilibrate=5000 | run.equilibrate | lower it
""".strip().splitlines()
]


@pytest.mark.parametrize(("settings", "key", "fix"), BAD, ids=[row[0] for row in BAD])
def test_bad_configs_name_the_key_and_write_nothing(settings, key, fix, tmp_path, capsys):
    out = tmp_path / "out"
    overrides = [arg for setting in settings.split() for arg in ("--set", setting)]
    assert main(["run", "passive", "--out", str(out), "--steps", "1000", "--set", "run.equilibrate=0", *overrides]) == 2
    error = capsys.readouterr().err.strip()
    assert error.startswith(f"fricgen run: {key}: ") and fix in error and "\n" not in error, error
    assert not out.exists()


def test_bad_toml_and_unknown_config_are_clear(tmp_path, capsys):
    broken = tmp_path / "broken.toml"
    broken.write_text("[system\nn = 4\n")
    assert main(["run", str(broken), "--out", str(tmp_path / "a")]) == 2
    assert "not valid TOML" in capsys.readouterr().err
    assert main(["run", "no_such_example", "--out", str(tmp_path / "b")]) == 2
    assert "passive" in capsys.readouterr().err and not any(tmp_path.glob("[ab]"))


def test_stale_kernels_are_refused_with_the_command_that_fixes_them(tmp_path, capsys, monkeypatch):
    import fricgen.kernels

    monkeypatch.setattr(fricgen.kernels, "source_hash", lambda data: "0" * 64)
    assert main(["run", "passive", "--out", str(tmp_path / "out")]) == 2
    error = capsys.readouterr().err
    assert "law.name" in error and "stale" in error and "fricgen generate coulomb_newton" in error
    assert not (tmp_path / "out").exists()


def test_the_exit_status_and_an_existing_run_is_not_overwritten(tmp_path, capsys):
    done = fricgen("run", "passive", "--set", "system.packing_fraction=1.2", "--out", str(tmp_path / "x"))
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and "system.packing_fraction" in done.stderr
    out = tmp_path / "run"
    args = ["run", "passive", "--out", str(out), "--steps", "200", *SMALL["passive"][:2], *EVERY, "--set", "run.equilibrate=0"]
    assert main(args) == 0
    before = (out / "checkpoint.npz").read_bytes()
    capsys.readouterr()
    assert main(args) == 2
    assert "--out: " in capsys.readouterr().err and (out / "checkpoint.npz").read_bytes() == before


def _checkpoint(path):
    with np.load(path) as data:
        return {key: data[key] for key in ("position", "velocity", "omega", "orientation", "step")}


def test_ctrl_c_stops_cleanly_and_resume_continues_bit_for_bit(tmp_path):
    out = tmp_path / "stopped"
    args = ["run", "passive", *SMALL["passive"][:2], "--set", "run.equilibrate=0", *EVERY, "--steps", "200000"]
    process = subprocess.Popen([sys.executable, "-m", "fricgen", *args, "--out", str(out)], stderr=subprocess.PIPE, text=True)
    table = out / "temperatures.csv"
    deadline = time.monotonic() + 300
    while not (table.exists() and table.read_text().count("\n") >= 4) and time.monotonic() < deadline:
        time.sleep(0.1)
    process.send_signal(signal.SIGINT)
    _, stderr = process.communicate(timeout=300)
    assert process.returncode == 130, stderr
    state = _checkpoint(out / "checkpoint.npz")
    step = int(state["step"])
    assert 0 < step < 200_000 and step % 100 == 0
    assert frames(out / "trajectory.gsd") == list(range(0, step + 1, 200))  # valid, every frame up to the stop
    resume = shlex.split(stderr.strip().splitlines()[-1])
    assert resume[:3] == ["fricgen", "run", "passive"] and resume[-2:] == ["--resume", str(out / "checkpoint.npz")]
    target = str(step + 1000)
    resume[resume.index("--steps") + 1] = target
    assert main(resume[1:]) == 0
    straight = tmp_path / "straight"
    assert main([*args[:-1], target, "--out", str(straight)]) == 0
    for key, value in _checkpoint(straight / "checkpoint.npz").items():
        assert np.array_equal(value, _checkpoint(out / "checkpoint.npz")[key]), key
    rows = np.loadtxt(table, delimiter=",", skiprows=1)
    assert np.array_equal(rows, np.loadtxt(straight / "temperatures.csv", delimiter=",", skiprows=1))
    assert frames(out / "trajectory.gsd") == frames(straight / "trajectory.gsd")


def test_resume_from_an_older_checkpoint_drops_the_later_outputs(tmp_path, capsys):
    out = tmp_path / "run"
    base = ["run", "passive", *SMALL["passive"][:2], "--set", "run.equilibrate=0", *EVERY, "--out", str(out)]
    assert main([*base, "--steps", "400"]) == 0
    shutil.copy(out / "checkpoint.npz", out / "at400.npz")
    assert main([*base[:-2], "--steps", "800", "--resume", str(out / "checkpoint.npz")]) == 0
    final = _checkpoint(out / "checkpoint.npz")
    assert main([*base[:-2], "--steps", "800", "--resume", str(out / "at400.npz")]) == 0
    assert all(np.array_equal(v, _checkpoint(out / "checkpoint.npz")[k]) for k, v in final.items())
    assert frames(out / "trajectory.gsd") == list(range(0, 801, 200))
    assert np.loadtxt(out / "temperatures.csv", delimiter=",", skiprows=1)[:, 0].tolist() == list(range(0, 801, 100))
    capsys.readouterr()
    assert main([*base[:-2], "--steps", "800", "--set", "law.contact_noise=false", "--resume", str(out / "at400.npz")]) == 2
    assert "law.contact_noise" in capsys.readouterr().err
    assert main([*base[:-2], "--steps", "800", "--resume", str(out / "checkpoint.npz")]) == 2
    assert "run.steps" in capsys.readouterr().err
