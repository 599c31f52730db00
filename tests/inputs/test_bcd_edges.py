"""``fricgen bcd`` at its edges (issue 37 item 5): densities at or near close packing, extreme stickiness,
eps, U0 and dt are refused on one line before anything runs; an output path that is a folder is refused
up front, even with --force; a ``.new-*`` link planted in --out is never written through; Ctrl-C stops
the Monte Carlo start (exit 130, nothing written). Each fails when its guard is removed."""

import _thread
import gc
import os
import re
import threading
import time

import pytest

from fricgen.app.cli import main

from .traps import trap_simulations

#: args | key | piece: exit status 2, one line naming key and holding piece, no simulation started.
ROWS = """
bcd --n 199 | --n | too close to close packing
bcd --n 197 | --n | too close to close packing
bcd --U0 1e4 | --dt | mu max|U''| dt = 19.7
bcd --dt 0.05 | --dt | the field's Euler step
bcd --gamma 1e8 | --dt | B-33
bcd --gamma 1 --eps 1e-9 | --dt | B-33
bcd --force --out {in}/folder_result | --out | is a folder: the result cannot replace it
"""


def rows():
    return [tuple(part.strip() for part in line.split(" | ")) for line in ROWS.strip().splitlines()]


@pytest.mark.parametrize(("args", "key", "piece"), rows(), ids=[row[0] for row in rows()])
def test_refused_before_the_run(args, key, piece, tmp_path, monkeypatch, capsys):
    trap_simulations(monkeypatch)  # a missing guard reaches the simulation: Started
    (tmp_path / "folder_result" / "profile.png").mkdir(parents=True)
    monkeypatch.chdir(tmp_path)
    status = main([word.replace("{in}", str(tmp_path)) for word in args.split()])
    out, err = capsys.readouterr()
    assert status == 2 and out == "", (status, err)
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    assert re.search(rf"(?<![\w.-]){re.escape(key)}(?!\w)", err) and piece in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["folder_result"]
    assert [p.name for p in (tmp_path / "folder_result").iterdir()] == ["profile.png"]


def test_a_planted_new_file_link_is_never_written_through(tmp_path, capsys):
    """.new-profile.csv and .new-profile.png planted as links to the user's files: both stay as they were."""
    out, mine = tmp_path / "out", tmp_path / "mine"
    out.mkdir()
    mine.mkdir()
    for name in ("profile.csv", "profile.png"):
        (mine / name).write_text("the user's own file\n")
        (out / f".new-{name}").symlink_to(mine / name)
    args = ["bcd", "--n", "20", "--length", "20", "--replicas", "2", "--bins", "5", "--time", "0.2", "--equilibrate", "0"]
    assert main([*args, "--out", str(out)]) == 0, capsys.readouterr().err
    assert all((mine / name).read_text() == "the user's own file\n" for name in ("profile.csv", "profile.png"))
    assert (out / "profile.csv").read_text().startswith("x,rho,") and not (out / "profile.csv").is_symlink()
    assert sorted(p.name for p in out.iterdir()) == [".new-profile.csv", ".new-profile.png", "profile.csv", "profile.png"]
    assert oct((out / "profile.csv").stat().st_mode & 0o777) == oct(0o666 & ~_umask())


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def test_ctrl_c_stops_the_monte_carlo_start(tmp_path, capsys):
    """1e8 sweeps of 50 rods (minutes in one compiled call): interrupted 2 s in, the run ends within seconds.

    The cyclic garbage collector is off meanwhile: in a long pytest process it may run an earlier test's
    finalizer just when the interrupt arrives, and Python swallows an exception raised in a finalizer
    ("Exception ignored in"). For that case the interrupt is repeated every 5 s until the run returns."""
    args = ["bcd", "--replicas", "2", "--start-sweeps", "100000000", "--out", str(tmp_path / "bcd")]
    returned = threading.Event()

    def interrupt():
        for delay in (2.0, 5.0, 5.0):
            if returned.wait(delay):
                return
            _thread.interrupt_main()

    interrupter = threading.Thread(target=interrupt, daemon=True)
    gc.collect()
    gc.disable()
    clock = time.monotonic()
    interrupter.start()
    try:
        status = main(args)
    finally:
        returned.set()
        gc.enable()
    interrupter.join()
    err = capsys.readouterr().err
    assert status == 130 and err.strip().endswith("interrupted"), err
    assert time.monotonic() - clock < 20
    assert not (tmp_path / "bcd").exists()
