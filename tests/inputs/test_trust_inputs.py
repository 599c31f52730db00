"""The trust corpus (tests/inputs/trust_cases.py): law folders and their kernels as a careless or
hostile user hands them over. Every row exits with status 2 and one line on stderr that names the
file, flag or key, runs nothing of the folder (a canary in the damaged code would leave a file),
changes no file (the law folders and the user's cache alike) and starts no simulation and no
derivation. Law files are read for real (the refusals of parameter names happen when a law is
read); derivations and simulations are replaced by a trap that raises.
"""

import json
import os
import re
from pathlib import Path

import pytest

from fricgen.app.cli import main
from fricgen.derive.law import manifests
from fricgen.kernels import load_law_kernels

from .cases import argv
from .traps import stop, trap_simulations
from .trust_cases import GOOD, build, rows

ROWS = rows()


@pytest.fixture(autouse=True)
def trap(monkeypatch):
    import fricgen.derive.driver
    import fricgen.derive.noise.derivation
    import fricgen.derive.noise.verification

    trap_simulations(monkeypatch)
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
    assert {"noise", "verify", "generate", "thermostat-check", "run", "lammps"} <= commands


@pytest.mark.parametrize("args", GOOD)
def test_the_undamaged_kernels_load_and_run(args, inputs, capsys):
    """The controls: the same kernels as the damaged ones, undamaged (and a copy of their folder, whose
    files hold what fricgen wrote), are accepted, so that each refusal above is the damage's doing;
    they run from their trusted copies in the cache."""
    folder, cache = inputs
    assert main(argv(args, str(folder))) == 0, capsys.readouterr().err
    assert json.loads(capsys.readouterr().out)["D"] == [1.0]  # D = w gamma_f
    law_folder = folder / args.split()[2].removeprefix("{in}/")
    copy = Path(load_law_kernels("kern", law_folder).module.__file__)
    assert copy.is_relative_to(cache) and copy.read_bytes() == (law_folder / "generated" / "laws" / "kern.py").read_bytes()
