"""The trust corpus (tests/inputs/trust_cases.py): law folders and their kernels as a careless or
hostile user hands them over. Every row exits with status 2 and one line on stderr that names the
file, flag or key, runs nothing of the folder (a canary in the damaged code would leave a file),
changes no file (the law folders and the user's cache alike) and starts no simulation and no
derivation. Law files are read for real (the refusals of parameter names happen when a law is
read); derivations, simulations and a sweep's cluster are replaced by a trap that raises.
"""

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from fricgen.app.cli import main
from fricgen.app.run.checkpoints import recorded_laws
from fricgen.derive.law import manifests
from fricgen.derive.law.catalogues import LawSearch
from fricgen.kernels import load_law_kernels

from .cases import argv
from .traps import Started, stop, trap_simulations
from .trust_cases import GOOD, SWEEP_GOOD, build, rows

ROWS = rows()


@pytest.fixture(autouse=True)
def trap(monkeypatch):
    import fricgen.app.sweep.runner
    import fricgen.derive.driver
    import fricgen.derive.noise.derivation
    import fricgen.derive.noise.verification

    trap_simulations(monkeypatch)
    monkeypatch.setattr(fricgen.app.sweep.runner, "_client", stop)
    monkeypatch.setattr(fricgen.derive.noise.derivation, "derive_noise", stop)
    monkeypatch.setattr(fricgen.derive.noise.verification, "prove", stop)
    for name in ("derive_noise", "verify", "verified_models"):
        monkeypatch.setattr(fricgen.derive.driver, name, stop)


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    """({in}, the cache folder): the corpus's folders, their kernels recorded in a cache of its own."""
    root = tmp_path_factory.mktemp("trust")
    cache = root / "cache"
    saved = os.environ.get(manifests.CACHE_ENV)
    os.environ[manifests.CACHE_ENV] = str(cache)
    try:
        build(root / "in")
        yield root / "in", cache
    finally:
        if saved is None:
            os.environ.pop(manifests.CACHE_ENV, None)
        else:
            os.environ[manifests.CACHE_ENV] = saved


@pytest.fixture
def inputs(corpus, monkeypatch):
    folder, cache = corpus
    monkeypatch.setenv(manifests.CACHE_ENV, str(cache))
    return folder, cache


def snapshot(*folders: Path) -> dict:
    """Every entry under ``folders`` (links not followed: FIFOs and dangling links are entries too),
    with its kind, size and modification time, and the bytes of regular files."""
    found = {}
    for folder in folders:
        for root, dirs, files in os.walk(folder):
            for name in dirs + files:
                path = Path(root, name)
                status = path.lstat()
                content = path.read_bytes() if path.is_file() and not path.is_symlink() else b""
                found[path] = (status.st_mode, status.st_size, status.st_mtime_ns, content)
    return found


@pytest.mark.parametrize(("args", "key", "piece"), ROWS, ids=[row[0] for row in ROWS])
def test_trust_case(args, key, piece, inputs, tmp_path, monkeypatch, capsys):
    folder, cache = inputs
    monkeypatch.chdir(tmp_path)
    before = snapshot(folder, cache, tmp_path)
    status = main(argv(args, str(folder)))
    out, err = capsys.readouterr()
    assert status == 2, (status, err)
    lines = err.splitlines()
    assert len(lines) == 1 and err.endswith("\n"), err
    line = lines[0]
    assert line.startswith("fricgen") and "Traceback" not in line, line
    assert re.search(rf"(?<![\w.-]){re.escape(key)}(?!\w)", line) and piece in line, line
    assert out == ""
    assert not list(folder.rglob("RAN")), "code from a law folder ran"
    assert snapshot(folder, cache, tmp_path) == before, "files were written"


def test_the_corpus_is_large_and_unrepeated():
    assert len(ROWS) >= 30 and len({args for args, _, _ in ROWS}) == len(ROWS)
    commands = {args.split()[0] for args, _, _ in ROWS}
    assert {"noise", "verify", "generate", "thermostat-check", "run", "lammps", "sweep"} <= commands


@pytest.mark.parametrize("args", GOOD)
def test_the_undamaged_kernels_load_and_run(args, inputs, capsys):
    """The controls: the same kernels as the damaged ones, undamaged (and a copy of their folder, whose
    files hold what fricgen wrote), are accepted, so that each refusal above is the damage's doing;
    they run from their trusted copies in the cache."""
    folder, cache = inputs
    assert main(argv(args, str(folder))) == 0, capsys.readouterr().err
    assert json.loads(capsys.readouterr().out)["D"] == [1.0]  # D = w gamma_f
    law_folder = folder / args.split()[2].removeprefix("{in}/")
    copy = Path(load_law_kernels("kern", LawSearch.only(law_folder)).module.__file__)
    assert copy.is_relative_to(cache) and copy.read_bytes() == (law_folder / "generated" / "laws" / "kern.py").read_bytes()


def test_a_finished_point_of_this_law_is_kept_and_a_stale_one_reruns_with_the_flag(inputs, capsys):
    """The controls of the sweep rows: the finished point whose checkpoint records its law's hash is kept
    (ran 0: the refusal of the stale one is the hash's doing); with --rerun-stale the stale point goes to
    the cluster (the trap)."""
    folder, _ = inputs
    assert main(argv(SWEEP_GOOD, str(folder))) == 0, capsys.readouterr().err
    assert json.loads(capsys.readouterr().out)["ran"] == 0
    with pytest.raises(Started):
        main(argv("sweep {in}/sweeps/sweep.toml --out {in}/sweep_stale --rerun-stale", str(folder)))


def test_a_stale_point_starts_afresh_in_its_task(inputs, tmp_path, monkeypatch):
    """The point's task (run in its child process) finds the checkpoint of another law version: the old
    summary is kept as summary-stale.json, the run files go, and the run starts fresh (the trap)."""
    import fricgen.app.sweep.task as task

    folder, _ = inputs
    point = tmp_path / "seed=1"
    shutil.copytree(folder / "sweep_stale" / "seed=1", point)
    (point / "run.log").touch()  # the task made it
    good = json.loads(json.dumps(recorded_laws(folder / "sweep_good" / "seed=1" / "checkpoint.npz")))
    monkeypatch.setattr(task, "_watch", lambda parent: None)
    spec = {"name": "seed=1", "folder": str(point), "steps": 600, "parent": 0, "law_hashes": good}
    spec |= {"base": "passive", "settings": [], "laws": []}
    with pytest.raises(Started):
        task._child(spec)
    assert (point / "summary-stale.json").is_file() and not (point / "summary.json").exists() and not (point / "checkpoint.npz").exists()


def test_laws_of_fricgen_laws_with_a_line_end_are_found(inputs, monkeypatch, capsys):
    """FRICGEN_LAWS as `export FRICGEN_LAWS=$(...)` or an editor leaves it, with a line end: the folder is
    read, not reported missing."""
    folder, _ = inputs
    monkeypatch.setenv("FRICGEN_LAWS", f"{folder / 'k_good'}\n")
    assert main(["noise", "kern", "--u", "1", "--w", "1", "--json"]) == 0, capsys.readouterr().err


def test_a_warning_is_one_line(monkeypatch, capsys):
    """A warning of any command reaches stderr as one line naming the command, not Python's two."""
    import warnings

    import fricgen.app.cli.commands as commands

    def warn(args):
        warnings.warn("D is off\nby 2 %", stacklevel=1)
        return 0

    monkeypatch.setattr(commands, "_noise", warn)
    assert main(["noise", "linear", "--u", "1", "--w", "1"]) == 0
    assert capsys.readouterr().err == "fricgen noise: warning: D is off by 2 %\n"


def test_names_that_become_one_name_in_code_clash():
    """fricgen.derive.law.names: the pairs that share a name in code, and those that do not; the built-in
    catalogue is free of clashes."""
    from fricgen.derive.law.catalogues import CATALOGUE, check_law_files
    from fricgen.derive.law.names import clash

    assert "file name" in clash([("Foo_bar", "a"), ("foo_bar", "b")])
    assert "C++ class name, 'Rate2'" in clash([("rate_2", "a"), ("rate2", "b")])
    assert "C++ class name, 'FooBar'" in clash([("foo__bar", "a"), ("fooBar", "b")])
    assert clash([("foo_bar", "a"), ("foobar", "b"), ("foo_bar", "c")]) is None  # the same law twice is no clash
    assert clash([("ab", "a"), ("AB", "b"), ("cd", "c")], name="cd") is None  # only pairs with the law looked up
    assert check_law_files(CATALOGUE)


def test_a_plugin_refuses_a_class_built_for_another_law():
    """A plugin, when loaded, compares what its class says it was built for with its own law and hash (the
    class of a plugin loaded earlier with the same class name says another): in the committed plugin of
    linear, which tests/lammps/test_generated.py keeps what the generator prints."""
    from fricgen.derive.law.catalogues import GENERATED

    files = {path.name: path.read_text() for path in (GENERATED / "lammps" / "linear").iterdir()}
    digest = re.search(r"Source hash: (\w+)", files["pair_fricgen_linear.cpp"]).group(1)
    built_for = f'"linear {digest}"'
    assert f"return {built_for};" in files["pair_fricgen_linear.cpp"]
    assert f"std::strcmp(PairFricgenLinear::built_for(), {built_for}) != 0" in files["fricgen_linear_plugin.cpp"]
    assert "static const char *built_for();" in files["pair_fricgen_linear.h"]


def test_noise_uses_the_mobility_of_the_law_s_mode(capsys):
    """fricgen noise of a rolling law: D at the rolling mobility of two spheres m = 1, R = 1/2 (1.25), not the
    sliding one (7), and the output names the mode and the mobility."""
    args = ["noise", "rolling_coulomb_newton", "--u", "0,1", "--w", "1"]
    results = []
    for extra in ([], ["--mu", "1.25"], ["--mu", "7"]):
        assert main([*args, *extra, "--json"]) == 0
        results.append(json.loads(capsys.readouterr().out))
    assert results[0]["mode"] == "rolling" and results[0]["mu"] == 1.25
    assert results[0]["D"] == results[1]["D"] != results[2]["D"]
    assert main(args) == 0
    assert "(ito, rolling mode), w = 1, mu = 1.25 (the rolling mobility of two spheres m = 1, R = 1/2)" in capsys.readouterr().out


def test_a_scheduler_address_that_answers_http_gets_one_line(inputs, tmp_path):
    """An HTTP server given as --scheduler ws://... (Dask's websocket scheme): one line, no traceback, no
    output folder (a fresh process, as a user runs it)."""
    folder, _ = inputs
    code = f"""
import http.server, sys, threading
class Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass
server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Quiet)
threading.Thread(target=server.serve_forever, daemon=True).start()
from fricgen.app.cli import main
address = f"ws://127.0.0.1:{{server.server_port}}"
sys.exit(main(["sweep", {str(folder / "sweeps" / "sweep.toml")!r}, "--out", "out", "--scheduler", address]))
"""
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert done.returncode == 2 and done.stderr.count("\n") == 1, done.stderr
    assert "as a Dask scheduler: Non-websocket response" in done.stderr and not (tmp_path / "out").exists()
