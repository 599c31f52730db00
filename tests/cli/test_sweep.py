"""`fricgen sweep SWEEP`: one-line errors before anything is written, a grid on a local Dask cluster,
no finished point run twice, an interrupted point resumed bit for bit, and a killed worker survived."""

import json
import logging
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import psutil
import pytest

from fricgen.app.cli import main
from fricgen.app.run.config import parse_override
from fricgen.app.run.runner import check_run
from fricgen.app.sweep.config import load_sweep, setting, sweep_names

ROOT = Path(__file__).resolve().parents[2]

#: Overrides that make a passive point a run of a second (N = 64); STEPS is added per test.
SMALL = """
base = "passive"

[set]
"system.n" = 64
"run.equilibrate" = 200
"run.chunk" = 100
"output.period" = 100
"output.trajectory_period" = 1000
"output.checkpoint_period" = 1000
"""
GRID = """
[grid]
"system.packing_fraction" = [0.3, 0.5]
"law.parameters.gamma_f" = [1.0, 6.0]

[plot]
x = "system.packing_fraction"
y = "law.parameters.gamma_f"
color = "T_trans.mean"
"""
POINTS = [f"packing_fraction={phi}__gamma_f={g}" for phi in (0.3, 0.5) for g in (1.0, 6.0)]


def write_sweep(folder, text, steps=600):
    path = folder / "sweep.toml"
    path.write_text(SMALL + f'"run.steps" = {steps}\n' + text)
    return path


def sweep(path, out, *args):
    """fricgen sweep PATH --out OUT, on a local cluster of 2 workers unless ``args`` give --scheduler."""
    workers = [] if "--scheduler" in args else ["--workers", "2"]
    return main(["sweep", str(path), "--out", str(out), *workers, *args])


def rows(out):
    lines = (out / "results.csv").read_text().splitlines()
    header = lines[0].split(",")
    return [dict(zip(header, line.split(","))) for line in lines[1:]]


def without_seconds(table):
    return [{k: v for k, v in row.items() if k != "seconds"} for row in table]


def attempts(folder):
    return [line for line in (folder / "run.log").read_text().splitlines() if line.startswith("# ")]


@pytest.mark.parametrize(
    "text, message",
    [
        ('bsae = "passive"\n', "bsae: unknown key; did you mean 'base'?"),
        ("[grid]\n", "grid: has no axes"),
        ('[grid]\n"system.packing_fraction" = [0.5, 0.95]\n', "point packing_fraction=0.95: system.packing_fraction: 0.95 is impossible"),
        ('[grid]\n"system.packing_fraction" = []\n', "grid.system.packing_fraction: must be a non-empty list"),
        ('[grid]\n"system.radius" = [0.5]\n[grid.model]\nplain = {"law.frcition" = false}\n', "law.frcition: unknown key"),
        ("[grid]\nsytem.n = [64, 128]\n", "did you mean the section 'system'?"),
        (GRID.replace('x = "system.packing_fraction"', 'x = "system.n"'), "plot.x: 'system.n' is not an axis of the grid"),
        (
            GRID.replace('\n"law.parameters.gamma_f" = [1.0, 6.0]', '\n"law.parameters.gamma_f" = [1.0, 6.0]\n"run.seed" = [1, 2]'),
            "plot: the axis 'run.seed'",
        ),
        ('base = "nowhere.toml"\n[grid]\n"run.seed" = [1]\n', "base: no file"),
    ],
)
def test_a_bad_sweep_file_gets_one_line_and_no_folder(tmp_path, capsys, text, message):
    path = tmp_path / "sweep.toml"
    path.write_text(text if text.startswith(("bsae", "base")) else SMALL + text)
    assert sweep(path, tmp_path / "out") == 2
    err = capsys.readouterr().err
    assert err.startswith("fricgen sweep: ") and err.count("\n") == 1 and message in err, err
    assert not (tmp_path / "out").exists()


def test_workers_and_scheduler_exclude_each_other(tmp_path, capsys):
    assert (
        main(["sweep", str(write_sweep(tmp_path, GRID)), "--out", str(tmp_path / "out"), "--workers", "2", "--scheduler", "tcp://x:1"]) == 2
    )
    assert "--workers: sizes the local cluster" in capsys.readouterr().err and not (tmp_path / "out").exists()


def test_overrides_read_back_as_written():
    for key, value in [
        ("system.n", 64),
        ("thermostat.dt", 1e-05),
        ("law.calculus", 'it"o'),
        ("system.box", [20.0, 18.5]),
        ("law.friction", False),
    ]:
        assert parse_override(setting(key, value)) == (key, value)


def test_the_bundled_mips_sweep_is_fig_8_in_small():
    mips = load_sweep("mips")
    assert sweep_names() == ["mips"] and mips.base == "active"
    assert [(axis.name, len(axis.values)) for axis in mips.axes] == [("active.force", 3), ("system.packing_fraction", 3), ("model", 3)]
    assert mips.points()[0].settings[-1] == "law.friction=false" and mips.plot.color == "mips.phase_separated"


@pytest.mark.parametrize("path", sorted((ROOT / "docs" / "studies").glob("*.toml")), ids=lambda path: path.stem)
def test_every_study_of_the_docs_checks_point_by_point(path):
    """The study files the docs report on (docs/studies/*.toml) load, and every point's run
    configuration passes fricgen run's checks, so a reader's `fricgen sweep` does not fail at a late point."""
    study = load_sweep(str(path))
    points = study.points()
    assert len(points) == len({point.name for point in points}) > 1
    for point in points:
        assert check_run(study.base, list(point.settings)).run.steps > 0


@pytest.fixture(scope="module")
def scheduler():
    """The address of a running Dask cluster of 2 single-threaded workers (as `dask scheduler` and
    two `dask worker` would give)."""
    from distributed import LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None, silence_logs=logging.ERROR) as cluster:
        yield cluster.scheduler_address


@pytest.fixture(scope="module")
def finished(tmp_path_factory):
    """A 2 x 2 grid of passive points, run on a local cluster of 2 workers that the sweep starts."""
    folder = tmp_path_factory.mktemp("sweep")
    out = folder / "out"
    assert sweep(write_sweep(folder, GRID), out) == 0
    return folder, out


def test_a_grid_runs_every_point_into_its_folder(finished):
    _, out = finished
    table = rows(out)
    assert [row["point"] for row in table] == POINTS
    assert [(row["system.packing_fraction"], row["law.parameters.gamma_f"]) for row in table] == [
        (phi, g) for phi in ("0.3", "0.5") for g in ("1.0", "6.0")
    ]
    assert all(row["status"] == "done" and row["steps"] == "600" and float(row["T_trans.mean"]) > 0 for row in table)
    for name in POINTS:
        summary = json.loads((out / name / "summary.json").read_text())
        assert summary["steps"] == 600 and len(attempts(out / name)) == 1
    assert (out / "phase_diagram.png").stat().st_size > 10_000
    assert [p["name"] for p in json.loads((out / "sweep.json").read_text())["points"]] == POINTS


def test_a_rerun_runs_only_what_is_missing_and_resumes_bit_for_bit(finished, scheduler, tmp_path, capsys):
    folder, reference = finished
    out = tmp_path / "out"
    shutil.copytree(reference, out)
    interrupted, stale, untouched = out / POINTS[0], out / POINTS[1], POINTS[2:]
    before = {name: ((out / name / "summary.json").stat().st_mtime_ns, (out / name / "run.log").read_text()) for name in untouched}
    settings = json.loads((out / "sweep.json").read_text())["points"][0]["set"]
    shutil.rmtree(interrupted)
    assert main(["run", "passive", *(a for s in settings for a in ("--set", s)), "--steps", "300", "--out", str(interrupted)]) == 0
    (interrupted / "summary.json").unlink()  # a checkpoint at step 300 and no summary: as after Ctrl-C
    for name in ("summary.json", "checkpoint.npz"):
        (stale / name).unlink()  # a start that died before its first checkpoint
    capsys.readouterr()
    assert sweep(folder / "sweep.toml", out, "--json", "--scheduler", scheduler) == 0
    assert json.loads(capsys.readouterr().out)["ran"] == 2
    assert {name: ((out / name / "summary.json").stat().st_mtime_ns, (out / name / "run.log").read_text()) for name in untouched} == before
    assert "resume" in (interrupted / "run.log").read_text() and len(attempts(stale)) == 2
    for point in (interrupted, stale):
        for name in ("temperatures.csv", "checkpoint.npz"):
            assert (point / name).read_bytes() == (reference / point.name / name).read_bytes(), (point, name)
    assert without_seconds(rows(out)) == without_seconds(rows(reference))
    # a plot column that the summaries do not have: one line, no point runs again
    (folder / "bad.toml").write_text((folder / "sweep.toml").read_text().replace('"T_trans.mean"', '"T_trans.nope"'))
    assert sweep(folder / "bad.toml", out) == 2
    err = capsys.readouterr().err
    assert "plot.color: results.csv has no column 'T_trans.nope'" in err and err.count("\n") == 1
    # a sweep file changed since: its finished points are not mixed into the table
    (folder / "changed.toml").write_text((folder / "sweep.toml").read_text().replace("[grid]", '"run.seed" = 2\n[grid]'))
    assert sweep(folder / "changed.toml", out) == 2
    err = capsys.readouterr().err
    assert f"point {POINTS[0]}: run.seed: {interrupted} holds a finished run with 1, not 2" in err and err.count("\n") == 1


def test_a_run_from_before_a_setting_existed_counts_as_finished_at_its_default(finished, tmp_path, capsys):
    """A finished point whose config.json lacks a setting added since (law.rolling_noise) ran as its default
    says: the sweep keeps it; the same setting recorded at another value is refused."""
    folder, reference = finished
    out = tmp_path / "out"
    shutil.copytree(reference, out)
    config = out / POINTS[0] / "config.json"
    stored = json.loads(config.read_text())
    del stored["law"]["rolling_noise"]
    config.write_text(json.dumps(stored))
    assert sweep(folder / "sweep.toml", out, "--json") == 0
    assert json.loads(capsys.readouterr().out)["ran"] == 0
    stored["law"]["rolling_noise"] = False
    config.write_text(json.dumps(stored))
    assert sweep(folder / "sweep.toml", out) == 2
    assert f"point {POINTS[0]}: law.rolling_noise: {out / POINTS[0]} holds a finished run with False, not True" in capsys.readouterr().err


@pytest.mark.skipif(not Path("/proc/self/autogroup").exists(), reason="a kernel without autogroups")
def test_a_run_in_its_own_session_keeps_the_sweeps_niceness():
    """A new session starts a scheduling group at nice 0 (Linux autogroups); the run sets its own nice
    value there, so that a niced sweep yields the cores to other sessions' work."""
    code = "import os\nfrom fricgen.app.sweep.task import keep_niceness\nos.nice(7)\nkeep_niceness()\n"
    code += "print(open('/proc/self/autogroup').read())"
    done = subprocess.run([sys.executable, "-c", code], start_new_session=True, capture_output=True, text=True, check=True)
    assert done.stdout.split()[-1] == "7", done.stdout


def _child_of(out, point):
    """The process that runs ``point`` of the sweep into ``out`` (the task's child), or None."""
    for process in psutil.process_iter(["cmdline"]):
        line = " ".join(process.info["cmdline"] or [])
        if "fricgen.app.sweep.task" in line and str(out / point) in line:
            return process
    return None


def test_a_killed_worker_costs_no_point(scheduler, tmp_path):
    """Two identical points; the worker of one is killed (SIGKILL) after its first checkpoint: its run
    stops at a checkpoint, Dask runs the point again, which resumes, and both points end bit-identical."""
    grid = "[grid.copy]\na = {}\nb = {}\n"
    path, out = write_sweep(tmp_path, grid, steps=10_000), tmp_path / "out"
    env = {**os.environ, "NUMBA_NUM_THREADS": "1"}
    command = [sys.executable, "-m", "fricgen", "sweep", str(path), "--out", str(out), "--scheduler", scheduler]
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env) as running:
        deadline = time.monotonic() + 120
        while not (out / "copy=a" / "checkpoint.npz").exists():
            assert running.poll() is None and time.monotonic() < deadline, running.communicate()
            time.sleep(0.02)
        child = _child_of(out, "copy=a")
        os.kill(child.ppid(), signal.SIGKILL)  # the worker
        assert not (out / "copy=a" / "summary.json").exists()
        _, err = running.communicate(timeout=300)
    assert running.returncode == 0, err
    assert not child.is_running() or child.status() == psutil.STATUS_ZOMBIE  # the orphan is gone
    log = (out / "copy=a" / "run.log").read_text()
    assert len(attempts(out / "copy=a")) == 2 and "stopped at step" in log and "copy=a: resume" in log, log
    for name in ("temperatures.csv", "checkpoint.npz"):
        assert (out / "copy=a" / name).read_bytes() == (out / "copy=b" / name).read_bytes(), name
    first, second = without_seconds(rows(out))
    assert first.pop("point") == "copy=a" and first.pop("copy") == "a" and second.pop("point") == "copy=b" and second.pop("copy") == "b"
    assert first == second and first["steps"] == "10000"
