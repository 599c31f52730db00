"""The corpus of outputs, resume, deadlines and edge numbers (tests/inputs/outputs_cases.py): every
row exits with status 2 and one line on stderr that names the flag or key, prints nothing on stdout,
changes no file (what the user had stays as it was) and starts no simulation. Besides the rows: a
sweep against a server that accepts the connection and never answers gives up within its deadline,
a closed stdout ends in one line instead of BrokenPipeError, and a resumed run keeps the summary of
its earlier end.
"""

import json
import os
import re
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from fricgen.app.cli import main

from .outputs_cases import argv, build, rows
from .traps import Started, trap_simulations

ROWS = rows()


@pytest.fixture(autouse=True)
def trap(monkeypatch):
    trap_simulations(monkeypatch)


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("outputs")
    build(folder)
    return folder


def snapshot(*folders: Path) -> dict:
    """Every file, folder and link under ``folders`` with its size, modification time and content."""
    found = {}
    for folder in folders:
        for root, dirs, files in os.walk(folder):
            for name in dirs + files:
                path = Path(root, name)
                content = path.read_bytes() if path.is_file() and not path.is_symlink() else b""
                found[path] = (path.is_dir(), path.is_symlink(), path.lstat().st_size, path.lstat().st_mtime_ns, content)
    return found


@pytest.mark.parametrize(("args", "key", "piece"), ROWS, ids=[row[0] for row in ROWS])
def test_refused(args, key, piece, inputs, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    before = snapshot(inputs, tmp_path)
    status = main(argv(args, str(inputs)))
    out, err = capsys.readouterr()
    assert status == 2, (status, err)
    lines = err.splitlines()
    assert len(lines) == 1 and err.endswith("\n"), err
    assert lines[0].startswith("fricgen") and "Traceback" not in err, err
    assert re.search(rf"(?<![\w.-]){re.escape(key)}(?!\w)", lines[0]) and piece in lines[0], lines[0]
    assert out == ""
    assert snapshot(inputs, tmp_path) == before, "files were changed"


def test_the_corpus_is_large():
    assert len(ROWS) >= 40 and len({args for args, _, _ in ROWS}) == len(ROWS)


def test_the_valid_checkpoint_reaches_the_run(inputs, tmp_path, monkeypatch):
    """The damaged checkpoints are refused for their damage: the one they were made from resumes."""
    monkeypatch.chdir(tmp_path)
    with pytest.raises(Started):
        main(argv("run {in}/small.toml --resume {in}/ck_valid/checkpoint.npz", str(inputs)))


def test_a_scheduler_that_never_answers(inputs, tmp_path, monkeypatch, capsys):
    """A server that accepts the connection and never answers: one line within the deadline."""
    import fricgen.app.sweep.runner

    monkeypatch.setattr(fricgen.app.sweep.runner, "CONNECT_TIMEOUT", 1)
    server = socket.create_server(("127.0.0.1", 0))
    accepted = []
    thread = threading.Thread(target=lambda: accepted.append(server.accept()), daemon=True)
    thread.start()
    monkeypatch.chdir(tmp_path)
    clock = time.monotonic()
    try:
        status = main(["sweep", str(inputs / "small_sweep.toml"), "--scheduler", f"tcp://127.0.0.1:{server.getsockname()[1]}"])
    finally:
        server.close()
    err = capsys.readouterr().err
    assert status == 2 and time.monotonic() - clock < 15, err
    assert err.count("\n") == 1 and "--scheduler" in err and "did not answer" in err, err
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize("args", [["noise", "linear", "--u", "0,1", "--r", "1.05", "--json"], ["noise", "linear", "--u", "1", "--w", "1"]])
def test_a_closed_stdout(args, tmp_path):
    """``fricgen ... | head -c0``: one line on stderr, exit status 2, no BrokenPipeError."""
    reader, writer = os.pipe()
    os.close(reader)
    try:
        done = subprocess.run(
            [sys.executable, "-m", "fricgen", *args], stdout=writer, stderr=subprocess.PIPE, text=True, timeout=120, cwd=tmp_path
        )
    finally:
        os.close(writer)
    assert done.returncode == 2 and "BrokenPipeError" not in done.stderr and "Traceback" not in done.stderr, done.stderr
    assert done.stderr.count("\n") == 1 and "stdout was closed" in done.stderr


def test_a_resume_keeps_the_summary_of_the_earlier_end(tmp_path):
    """A finished run resumed for more steps keeps its earlier summary beside (summary-<step>.json)."""
    from fricgen.app.run.runner import _continue_from

    (tmp_path / "summary.json").write_text('{"steps": 2000}')
    _continue_from(tmp_path, 2000)
    assert json.loads((tmp_path / "summary-2000.json").read_text()) == {"steps": 2000}
    assert not (tmp_path / "summary.json").exists()
    (tmp_path / "summary.json").write_text('{"steps": 3000}')
    _continue_from(tmp_path, 2000)
    assert json.loads((tmp_path / "summary-2000-2.json").read_text()) == {"steps": 3000}
