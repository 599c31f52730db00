"""The trust corpus as data: law folders and kernels as a careless or hostile user hands them over.

Rows are ``args | key | piece`` as in :mod:`tests.inputs.cases`; ``{in}`` is the folder that
:func:`build` fills. Each row must exit with status 2 and one line naming ``key`` and holding
``piece``, run nothing of the folder and change no file (tests/inputs/test_trust_inputs.py).

The kernel folders k_* hold the built-in package's own kernel files (fricgen.generated: __init__.py,
special.py, laws/__init__.py and laws/linear.py as laws/kern.py, its SOURCE_HASH set to that of
kern.toml), recorded in the manifest of the test's cache as ``fricgen generate`` records what it
writes, so that no derivation is needed; k_good, left as it is, loads and runs (the control), and so
does k_copy, a copy of it (its files hold what fricgen wrote); every other one is damaged in one
way. Damaged code writes a canary file when run: a case that ran it changes the folder.

Names that become one name in code (fricgen.derive.law.names): clash/ holds Foo_bar and foo_bar (one
file on a case-insensitive file system), path_a/ and path_b/ hold rate_2 and rate2 (one C++ class)
on a search path of two folders, upper/ holds Linear beside the built-in linear. The sweeps
(sweeps/sweep.toml, one point seed=1) find in their --out a finished point that ran another version
of its law (its checkpoint's law hash), a point folder that is a symbolic link to a sibling or to
nothing, a finished point whose config.json is cut short, a point name longer than a file name may
be, and a checkpoint.npz.tmp that is a folder; :data:`SWEEP_GOOD` is the finished point with its
law's hash, which the sweep keeps (the control).
"""

from __future__ import annotations

import json
import os
import re
import shutil
from pathlib import Path

import numpy as np

from fricgen.app.run.outputs import dumps
from fricgen.app.run.runner import check_run
from fricgen.derive.law import manifests
from fricgen.derive.law.catalogues import GENERATED
from fricgen.derive.law.lawdata import read_law_data, source_hash
from fricgen.kernels import load_law_kernels

LAW = """name = "{name}"
friction = "w*{parameter}*u"
weight = "wca"
calculi = {calculi}

[parameters.{parameter}]
default = 1.0
"""

#: Law files whose parameter name a target language or the generated code reserves: name -> parameter.
RESERVED = {
    "infinity_law": "INFINITY",
    "nan_law": "NAN",
    "mpi_law": "M_PI",
    "errno_law": "errno",
    "helper_law": "expm1_given_exp",
    "switch_law": "switch_0",
    "keyword_law": "new",
    "params_law": "params",
    "typedef_law": "uint64_t",
}

#: A line of Python that, if it ever runs, leaves a file beside the code that ran it.
CANARY = 'open(__import__("os").path.join(r"{folder}", "RAN"), "w").write("injected code ran")\n'
#: The header a generated kernel starts with: copying it does not make a file fricgen's.
HEADER = (GENERATED / "__init__.py").read_text().splitlines(keepends=True)[0]

ROWS = """
noise --laws {in}/fifo_laws fifo_law --u 1 --w 1 | LAW | is a FIFO (named pipe), not a law file
noise --laws {in}/dir_laws dir_law --u 1 --w 1 | LAW | is a folder, not a law file
noise --laws {in}/dangling_laws gone --u 1 --w 1 | LAW | is a dangling symbolic link, not a law file
thermostat-check --laws {in}/dangling_laws gone | LAW | is a dangling symbolic link
verify --laws {in}/fifo_laws fifo_law | LAW | is a FIFO (named pipe), not a law file
verify --laws {in}/fifo_laws | fifo_law.toml | is a FIFO (named pipe), not a law file
generate --laws {in}/dir_laws dir_law | LAW | is a folder, not a law file
generate --laws {in}/dir_laws | dir_law.toml | is a folder, not a law file
verify --laws {in}/empty_laws | empty_laws | holds no law files
generate --laws {in}/empty_laws | empty_laws | holds no law files
verify --laws {in}/hyphen_laws | my-law.toml | a law file's name must be an identifier
generate --laws {in}/hyphen_laws | my-law.toml | rename it my_law.toml
noise --laws {in}/hyphen_laws my-law --u 1 --w 1 | LAW | rename it my_law.toml
verify --laws {in}/only_hk --calculus ito | --calculus | nothing was verified
verify --laws {in}/reserved infinity_law | INFINITY | a macro, type or function of C/C++
verify --laws {in}/reserved nan_law | NAN | a macro, type or function of C/C++
verify --laws {in}/reserved mpi_law | M_PI | a macro, type or function of C/C++
verify --laws {in}/reserved errno_law | errno | a macro, type or function of C/C++
verify --laws {in}/reserved typedef_law | uint64_t | a macro, type or function of C/C++
verify --laws {in}/reserved helper_law | expm1_given_exp | a name of the generated kernels
verify --laws {in}/reserved switch_law | switch_0 | a name of the generated kernels
verify --laws {in}/reserved keyword_law | new | a C++ keyword
generate --laws {in}/reserved params_law | params | a name of the generated kernels
lammps --laws {in}/reserved nan_law --out {in}/nowhere | NAN | a macro, type or function of C/C++
noise --laws {in}/k_edited kern --u 1 --w 1 | kern.py | is not the file that fricgen wrote
noise --laws {in}/k_init kern --u 1 --w 1 | __init__.py | is not the file that fricgen wrote
noise --laws {in}/k_special kern --u 1 --w 1 | special.py | is not the file that fricgen wrote
noise --laws {in}/k_lawsinit kern --u 1 --w 1 | __init__.py | is not the file that fricgen wrote
noise --laws {in}/k_unrecorded kern --u 1 --w 1 | __init__.py | was not written by fricgen on this machine
noise --laws {in}/k_dropped kern --u 1 --w 1 | kern.py | was not written by fricgen on this machine
noise --laws {in}/k_fifo kern --u 1 --w 1 | kern.py | is a FIFO (named pipe), not a file that fricgen wrote
noise --laws {in}/k_dir kern --u 1 --w 1 | kern.py | is a folder, not a file that fricgen wrote
noise --laws {in}/k_dangling kern --u 1 --w 1 | kern.py | is a dangling symbolic link
noise --laws {in}/k_nopackage kern --u 1 --w 1 | __init__.py | is missing
noise --laws {in}/k_stale kern --u 1 --w 1 | kern | are stale
thermostat-check kern --laws {in}/k_init | __init__.py | is not the file that fricgen wrote
run {in}/run_tampered.toml | __init__.py | is not the file that fricgen wrote
generate --laws {in}/clash | foo_bar | have names that become the same file name on a case-insensitive file system
verify --laws {in}/clash Foo_bar | LAW | laws 'Foo_bar'
noise --laws {in}/clash foo_bar --u 1 --w 1 | LAW | and 'foo_bar'
noise --laws {in}/path_a --laws {in}/path_b rate2 --u 1 --w 1 | LAW | become the same C++ class name, 'Rate2'
lammps --laws {in}/path_a --laws {in}/path_b rate_2 --out {in}/nowhere | LAW | become the same C++ class name
noise --laws {in}/upper linear --u 1 --w 1 | LAW | laws 'Linear'
lammps --laws {in}/upper Linear --out {in}/nowhere | LAW | one would run the other's code
noise --laws {in}/gen_file kern --u 1 --w 1 | generated | is a file, not the folder of the kernels
generate --laws {in}/gen_file kern | generated | is a file, not a folder
generate --laws {in}/gen_file | generated | move it away
sweep {in}/sweeps/sweep.toml --out {in}/sweep_stale | law | ran another version of their laws than this run's (the law hashes
sweep {in}/sweeps/sweep.toml --out {in}/sweep_stale --json | --rerun-stale | seed=1
sweep {in}/sweeps/sweep.toml --out {in}/sweep_linked | --out | is a symbolic link (to
sweep {in}/sweeps/sweep.toml --out {in}/sweep_dangling | --out | is a symbolic link (to
sweep {in}/sweeps/sweep.toml --out {in}/sweep_truncated | --out | whose config.json cannot be read
sweep {in}/sweeps/long.toml --out {in}/sweep_long | grid | more than the file system allows
sweep {in}/sweeps/sweep.toml --out {in}/sweep_tmpdir | --out | checkpoint.npz.tmp is a folder
sweep {in}/sweeps/sweep.toml --out {in}/sweep_fresh --scheduler http://localhost:8786 | --scheduler | http:// is not a scheme of Dask's
run passive --set system.n=64 --out {in}/sweep_tmpdir/seed=1 | --out | is a folder, in the way of a file the run writes
"""

#: A sweep of one point, seed=1 (the runs of a second that tests/cli/test_sweep.py makes).
SWEEP = """base = "passive"

[set]
"system.n" = 64
"run.steps" = 600
"run.equilibrate" = 200
"run.chunk" = 100
"output.period" = 100

[grid]
"run.seed" = [1]
"""
#: The finished point with its law's hash: the sweep keeps it (ran 0).
SWEEP_GOOD = "sweep {in}/sweeps/sweep.toml --out {in}/sweep_good --json"

#: The controls: the same kernels, undamaged, load and run, and so does a copy of their folder.
GOOD = ("noise --laws {in}/k_good kern --u 1 --w 1 --json", "noise --laws {in}/k_copy kern --u 1 --w 1 --json")


def _law(folder: Path, name: str, parameter: str = "gamma_f", calculi: str = '["ito"]') -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{name}.toml"
    path.write_text(LAW.format(name=name, parameter=parameter, calculi=calculi))
    return path


def _kernels(folder: Path) -> dict[str, bytes]:
    """A law folder with law kern and its kernel files (from the package's), recorded as fricgen's."""
    law = _law(folder, "kern")
    digest = source_hash(read_law_data(law))
    kernel = (GENERATED / "laws" / "linear.py").read_text()
    start = kernel.index("SOURCE_HASH = ")
    kernel = kernel[:start] + f"SOURCE_HASH = {digest!r}" + kernel[kernel.index("\n", start) :]
    files = {
        "__init__.py": (GENERATED / "__init__.py").read_bytes(),
        "special.py": (GENERATED / "special.py").read_bytes(),
        "laws/__init__.py": (GENERATED / "laws" / "__init__.py").read_bytes(),
        "laws/kern.py": kernel.encode(),
    }
    generated = folder / "generated"
    for name, data in files.items():
        (generated / name).parent.mkdir(parents=True, exist_ok=True)
        (generated / name).write_bytes(data)
    manifests.record(generated.resolve(), {name: manifests.sha256(data) for name, data in files.items()})
    return files


def finished_point(folder: Path, law_hash: str | None = None) -> Path:
    """The folder of a finished point seed=1 of :data:`SWEEP`: its config.json as fricgen run writes it,
    a summary, and a checkpoint that records ``law_hash`` (default: that of the law's kernels) as the
    hash of the law it ran."""
    settings = ["system.n=64", "run.steps=600", "run.equilibrate=200", "run.chunk=100", "output.period=100", "run.seed=1"]
    config = check_run("passive", settings)
    folder.mkdir(parents=True)
    (folder / "config.json").write_text(dumps({"command": ["fricgen", "run", "passive"], **config.as_dict()}))
    (folder / "summary.json").write_text('{"steps": 600}')
    stored = json.dumps({"law": {"name": config.law.name}})
    law_hash = load_law_kernels(config.law.name).source_hash if law_hash is None else law_hash
    np.savez(folder / "checkpoint.npz", config=stored, law_file="", law_hash=law_hash)
    return folder


def build_sweeps(root: Path) -> None:
    """The sweep files and the output folders of the sweep rows."""
    (root / "sweeps").mkdir()
    (root / "sweeps" / "sweep.toml").write_text(SWEEP)
    (root / "sweeps" / "long.toml").write_text(SWEEP.replace('"run.seed" = [1]', "[grid.model]\n" + "x" * 300 + " = {}"))
    finished_point(root / "sweep_good" / "seed=1")
    finished_point(root / "sweep_stale" / "seed=1", "0" * 64)  # the law edited and regenerated since
    finished_point(root / "sweep_linked" / "elsewhere")
    (root / "sweep_linked" / "seed=1").symlink_to(root / "sweep_linked" / "elsewhere")
    (root / "sweep_dangling").mkdir()
    (root / "sweep_dangling" / "seed=1").symlink_to(root / "sweep_dangling" / "gone")
    config = finished_point(root / "sweep_truncated" / "seed=1") / "config.json"
    config.write_text(config.read_text()[:100])
    (root / "sweep_tmpdir" / "seed=1" / "checkpoint.npz.tmp").mkdir(parents=True)


def build(root: Path) -> None:
    """The folders and files the rows refer to, under ``root`` ({in}); the manifests go to the cache
    that FRICGEN_CACHE names (set by the caller)."""
    (root / "fifo_laws").mkdir(parents=True)
    os.mkfifo(root / "fifo_laws" / "fifo_law.toml")
    (root / "dir_laws" / "dir_law.toml").mkdir(parents=True)
    (root / "dangling_laws").mkdir()
    (root / "dangling_laws" / "gone.toml").symlink_to(root / "dangling_laws" / "nowhere.toml")
    (root / "empty_laws").mkdir()
    _law(root / "hyphen_laws", "my_law").rename(root / "hyphen_laws" / "my-law.toml")
    _law(root / "only_hk", "hk_only", calculi='["hk"]')
    for name, parameter in RESERVED.items():
        _law(root / "reserved", name, parameter)

    _kernels(root / "k_good")
    shutil.copytree(root / "k_good", root / "k_copy")  # not recorded for k_copy: the same bytes as k_good's
    canary = CANARY
    edited = root / "k_edited"
    _kernels(edited)
    kernel = edited / "generated" / "laws" / "kern.py"
    kernel.write_text(kernel.read_text().replace("return gamma_f*u*w", "return 2*gamma_f*u*w") + canary.format(folder=edited))
    for name, file in (("k_init", "__init__.py"), ("k_special", "special.py"), ("k_lawsinit", "laws/__init__.py")):
        folder = root / name
        _kernels(folder)
        with (folder / "generated" / file).open("a") as stream:
            stream.write(canary.format(folder=folder))
    unrecorded = root / "k_unrecorded"  # kernels from another machine (another version): files fricgen never wrote here
    files = _kernels(unrecorded)
    manifests.record((unrecorded / "generated").resolve(), {}, removed=tuple(files))
    for name in files:
        path = unrecorded / "generated" / name
        path.write_text(re.sub(r"generator \d+\)", "generator 0)", path.read_text(), count=1))
    dropped = root / "k_dropped"  # the package recorded, the law's module dropped in with a plausible header
    _kernels(dropped)
    manifests.record((dropped / "generated").resolve(), {}, removed=("laws/kern.py",))
    (dropped / "generated" / "laws" / "kern.py").write_text(HEADER + canary.format(folder=dropped))
    for name, make in (
        ("k_fifo", os.mkfifo),
        ("k_dir", os.mkdir),
        ("k_dangling", lambda path: path.symlink_to(path.with_name("nowhere.py"))),
    ):
        _kernels(root / name)
        kernel = root / name / "generated" / "laws" / "kern.py"
        kernel.unlink()
        make(kernel)
    _kernels(root / "k_nopackage")
    (root / "k_nopackage" / "generated" / "__init__.py").unlink()
    _kernels(root / "k_stale")
    _law(root / "k_stale", "kern", "gamma_s")  # the law edited after its kernels were generated
    for name in ("Foo_bar", "foo_bar"):
        _law(root / "clash", name)
    _law(root / "path_a", "rate_2")
    _law(root / "path_b", "rate2")
    _law(root / "upper", "Linear")
    _law(root / "gen_file", "kern")
    (root / "gen_file" / "generated").write_text("not a folder\n")
    build_sweeps(root)
    (root / "run_tampered.toml").write_text('[system]\nn = 16\npacking_fraction = 0.5\n[law]\nname = "kern"\nfolder = "k_init"\n')


def rows() -> list[tuple[str, str, str]]:
    """The rows of :data:`ROWS` as (args, key, piece)."""
    return [tuple(part.strip() for part in line.split(" | ")) for line in ROWS.strip("\n").splitlines()]
