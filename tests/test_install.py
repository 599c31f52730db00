"""As a user installs it: a wheel built from a copy of the sources, installed (not editable) into a
fresh venv, its package made read-only; then, from a folder outside the repository, the demo, a law
of one's own (`generate --laws DIR`, `noise`, `thermostat-check`), a LAMMPS plugin (`lammps --out`),
and the refusal to regenerate the built-in laws. One import root: ``derive`` and ``generated`` are
not importable, ``fricgen.derive`` and ``fricgen.generated`` are. Nothing of the installed package
changes (Python's and Numba's __pycache__ folders aside). The venv reaches the dependencies of this
environment through a .pth file (no network), not its editable fricgen."""

import hashlib
import json
import os
import shutil
import site
import stat
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

from fricgen.derive.noise.lemma_cache import cache_folder

ROOT = Path(__file__).resolve().parents[1]
LAW = """name = "user_viscous"
description = "A user's viscous law: f = w gamma_f u, D = w gamma_f."
friction = "w*gamma_f*u"
weight = "wca"
calculi = ["ito", "stratonovich"]

[parameters.gamma_f]
default = 2.0
unit = "t0/sigma"
"""


def _files(folder: Path) -> dict[str, str]:
    """sha256 of every file under ``folder`` but Python's and Numba's caches (__pycache__)."""
    return {
        str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and "__pycache__" not in p.parts
    }


def _read_only(folder: Path) -> None:
    for path in [folder, *folder.rglob("*")]:
        if "__pycache__" not in path.parts:
            path.chmod(path.stat().st_mode & ~(stat.S_IWUSR | stat.S_IWGRP | stat.S_IWOTH))


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """(run, purelib, work): a command runner in the user's folder ``work`` of a fresh venv into
    which the wheel is installed, and the venv's site-packages."""
    tmp = tmp_path_factory.mktemp("install")
    source = tmp / "source"
    for folder in ("derive", "fricgen", "generated"):
        shutil.copytree(ROOT / folder, source / folder, ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    for name in ("pyproject.toml", "README.md"):
        shutil.copy2(ROOT / name, source / name)
    venv = tmp / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    unset = ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV", "FRICGEN_LAWS", "NUMBA_CACHE_DIR")
    env = {k: v for k, v in os.environ.items() if k not in unset}
    env |= {"PATH": f"{venv / 'bin'}{os.pathsep}{env.get('PATH', '')}", "PIP_DISABLE_PIP_VERSION_CHECK": "1", "PIP_NO_INPUT": "1"}
    # the user's own cache folder; the law-independent lemma is taken from this session's cache (proving it costs 30 s)
    env |= {"XDG_CACHE_HOME": str(tmp / "xdg"), "FRICGEN_CACHE": str(cache_folder() or "off")}
    work = tmp / "work"  # the user's folder, outside the repository
    work.mkdir()

    def run(*args, **variables):
        return subprocess.run([str(a) for a in args], cwd=work, env=env | variables, capture_output=True, text=True, timeout=900)

    python = venv / "bin" / "python"
    purelib = Path(run(python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])").stdout.strip())
    (purelib / "_dependencies.pth").write_text("\n".join(dict.fromkeys([*site.getsitepackages(), sysconfig.get_paths()["purelib"]])) + "\n")
    probe = run(python, "-c", "import pip, setuptools; assert tuple(map(int, setuptools.__version__.split('.')[:2])) >= (70, 1)")
    if probe.returncode:
        pytest.fail(f"building the wheel offline needs pip and setuptools >= 70.1 (the [test] extra): {probe.stderr.strip()}")
    wheel = run(python, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "--no-index", "--quiet", "-w", tmp / "dist", source)
    assert wheel.returncode == 0, wheel.stdout + wheel.stderr
    (built,) = (tmp / "dist").glob("fricgen-*.whl")
    install = run(python, "-m", "pip", "install", "--no-deps", "--no-index", "--quiet", built)
    assert install.returncode == 0, install.stdout + install.stderr
    _read_only(purelib / "fricgen")
    yield run, purelib, work


def test_one_import_root(installed):
    run, purelib, _ = installed
    code = (
        "import importlib.util as u, fricgen.derive, fricgen.generated.laws.linear as k\n"
        "print(u.find_spec('derive'), u.find_spec('generated'), fricgen.derive.__file__, k.__file__)"
    )
    done = run("python", "-c", code)
    assert done.returncode == 0, done.stderr
    missing_derive, missing_generated, *files = done.stdout.split()
    assert (missing_derive, missing_generated) == ("None", "None")
    assert all(Path(f).is_relative_to(purelib / "fricgen") for f in files), files
    catalogue = purelib / "fricgen" / "derive" / "law" / "catalogue" / "linear.toml"
    assert catalogue.is_file() and (purelib / "fricgen" / "generated" / "lammps" / "linear" / "CMakeLists.txt").is_file()


def test_a_user_runs_the_demo_and_brings_a_law(installed):
    run, purelib, work = installed
    before = _files(purelib / "fricgen")
    demo = run("fricgen", "demo", "--out", "demo", "--json")
    assert demo.returncode == 0, demo.stderr
    summary = json.loads((work / "demo" / "summary.json").read_text())
    assert summary["runs"]["with_contact_noise"]["passed"] and not summary["runs"]["without_contact_noise"]["passed"], summary
    assert (work / "demo" / "histograms.png").is_file()

    (work / "laws").mkdir()
    (work / "laws" / "user_viscous.toml").write_text(LAW)
    generate = run("fricgen", "generate", "--laws", "laws", "user_viscous")
    assert generate.returncode == 0, generate.stderr
    assert (work / "laws" / "generated" / "laws" / "user_viscous.py").is_file()
    noise = run("fricgen", "noise", "--laws", "laws", "user_viscous", "--u", "0,1", "--w", "1", "--json")
    assert noise.returncode == 0 and json.loads(noise.stdout)["D"] == [2.0, 2.0], noise.stderr
    check = run("fricgen", "thermostat-check", "user_viscous", "--n", "16", "--time", "4", "--json", FRICGEN_LAWS="laws")
    assert check.returncode in (0, 1) and json.loads(check.stdout)["law"] == "user_viscous", check.stderr
    lammps = run("fricgen", "lammps", "--laws", "laws", "user_viscous", "--out", "plugin")
    assert lammps.returncode == 0, lammps.stderr
    assert (work / "plugin" / "pair_fricgen_user_viscous.cpp").is_file() and (work / "plugin" / "CMakeLists.txt").is_file()
    built_in = run("fricgen", "lammps", "linear")  # no --out: the user's cache, not the package
    assert built_in.returncode == 0, built_in.stderr
    assert (work.parent / "xdg" / "fricgen" / "lammps-sources" / "linear" / "CMakeLists.txt").is_file()
    assert _files(purelib / "fricgen") == before, "the installed package was written to"


def test_regenerating_the_built_in_laws_is_refused_with_what_works(installed):
    run, purelib, _ = installed
    before = _files(purelib / "fricgen")
    done = run("fricgen", "generate", "linear")
    assert done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1, done.stderr
    assert "fricgen generate --laws DIR" in done.stderr and "source checkout" in done.stderr
    assert _files(purelib / "fricgen") == before
