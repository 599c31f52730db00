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
"""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

from fricgen.derive.law import manifests
from fricgen.derive.law.catalogues import GENERATED
from fricgen.derive.law.lawdata import read_law_data, source_hash

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
"""

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
    (root / "run_tampered.toml").write_text('[system]\nn = 16\npacking_fraction = 0.5\n[law]\nname = "kern"\nfolder = "k_init"\n')


def rows() -> list[tuple[str, str, str]]:
    """The rows of :data:`ROWS` as (args, key, piece)."""
    return [tuple(part.strip() for part in line.split(" | ")) for line in ROWS.strip("\n").splitlines()]
