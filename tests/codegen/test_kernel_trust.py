"""Kernels are code that fricgen wrote, law folders data (docs/trust-model.md).

- The manifests (fricgen.derive.law.manifests): what is recorded, what a damaged record is worth,
  files that are not files, copies of a folder, and records of folders that are gone.
- The loader (fricgen.kernels): a user folder's kernels, generated for real into a folder whose name
  holds quotes, a newline, a backslash and more, load and run; edited ones are refused before any file
  of the folder runs; a file dropped beside them, or a poisoned __pycache__ (Python's bytecode and
  Numba's pickled index), never runs.
- The names that reach generated code: a folder's name is printed into the Numba modules' and the
  C++ plugin's comments only in inert form; the code compiles and holds it nowhere else.
"""

from __future__ import annotations

import ast
import importlib
import json
import os
import pickle
import py_compile
import re
import shutil
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from fricgen import rng
from fricgen.app.cli import main
from fricgen.derive import derive_noise, load_law
from fricgen.derive.backends.lammps_plugin.module import plugin_files
from fricgen.derive.backends.numba_kernels.modules import law_module
from fricgen.derive.law import manifests
from fricgen.derive.law.catalogues import LawSearch, generate_command, inert, shell_word
from fricgen.kernels import KernelError, load_law_kernels

LAW = """name = "{name}"
friction = "w*gamma_f*u"
weight = "wca"
calculi = ["ito"]

[parameters.gamma_f]
default = 2.0
"""
#: A law folder's path, relative to a temporary folder, with what could break out of a comment or a
#: string: quotes, a newline, a carriage return, a backslash (also at the end of the name), a
#: docstring's quotes, the end of a C comment and a trigraph (across the separators: a name cannot hold
#: "/"), a LAMMPS continuation, a CMake bracket comment, a shell variable, a non-ASCII letter, a tab.
WEIRD = 'c*/tri??/we\'ird"\n"""import os; os.system(\'x\')\r & #[[ $HOME \u00f6\tmessage(FATAL_ERROR injected) \\'


def _law_folder(parent: Path, folder_name: str, name: str = "trusty") -> Path:
    folder = parent / folder_name
    folder.mkdir(parents=True)
    (folder / f"{name}.toml").write_text(LAW.format(name=name))
    return folder


# --- the manifests --------------------------------------------------------------------------------


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv(manifests.CACHE_ENV, str(tmp_path / "cache"))
    return tmp_path / "cache"


def _written(folder: Path, files: dict[str, bytes]) -> None:
    for name, data in files.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_bytes(data)
    manifests.record(folder, {name: manifests.sha256(data) for name, data in files.items()})


def test_a_manifest_records_and_authenticates(cache, tmp_path):
    folder = tmp_path / "out"
    _written(folder, {"a.py": b"x = 1\n", "laws/b.py": b"y = 2\n"})
    assert manifests.manifest(folder) == {"a.py": manifests.sha256(b"x = 1\n"), "laws/b.py": manifests.sha256(b"y = 2\n")}
    assert manifests.verified(folder, ["a.py", "laws/b.py"], "regenerate") == {"a.py": b"x = 1\n", "laws/b.py": b"y = 2\n"}
    (folder / "a.py").write_bytes(b"x = 2\n")
    with pytest.raises(manifests.UntrustedFile, match=r"a\.py is not the file that fricgen wrote .*: run `regenerate`"):
        manifests.verified(folder, ["a.py"], "regenerate")
    (folder / "c.py").write_bytes(b"z = 3\n")
    with pytest.raises(manifests.UntrustedFile, match=r"c\.py was not written by fricgen on this machine"):
        manifests.verified(folder, ["c.py"], "regenerate")
    manifests.record(folder, {}, removed=("laws/b.py",))
    assert list(manifests.manifest(folder)) == ["a.py"]


@pytest.mark.parametrize("damage", ["edited", "truncated", "fifo", "folder", "foreign", "format"])
def test_a_damaged_manifest_authenticates_nothing(cache, tmp_path, damage):
    folder = tmp_path / "out"
    _written(folder, {"a.py": b"x = 1\n"})
    (path,) = cache.rglob("manifest.json")
    data = json.loads(path.read_text())
    if damage == "edited":  # a record written by hand for another file: its sha256 no longer holds
        data["files"]["a.py"] = manifests.sha256(b"evil = 1\n")
        path.write_text(json.dumps(data))
    elif damage == "truncated":
        path.write_text(path.read_text()[:40])
    elif damage == "fifo":
        path.unlink()
        os.mkfifo(path)
    elif damage == "folder":
        path.unlink()
        path.mkdir()
    elif damage == "foreign":  # a whole manifest of another folder under this folder's key
        payload = {"format": manifests.FORMAT, "folder": str(tmp_path / "elsewhere"), "files": data["files"]}
        path.write_text(json.dumps({**payload, "sha256": manifests._payload_digest(payload)}))
    else:
        payload = {"format": 0, "folder": data["folder"], "files": data["files"]}
        path.write_text(json.dumps({**payload, "sha256": manifests._payload_digest(payload)}))
    result = []
    reader = threading.Thread(target=lambda: result.append(manifests.manifest(folder)), daemon=True)
    reader.start()
    reader.join(10)
    assert not reader.is_alive() and result == [{}], "a damaged manifest was read as a record, or waited on"
    if damage != "foreign":  # (the other folder's record of the same bytes still vouches for them)
        with pytest.raises(manifests.UntrustedFile):
            manifests.verified(folder, ["a.py"], "regenerate")


@pytest.mark.parametrize(
    ("make", "kind"),
    [
        (os.mkfifo, "is a FIFO (named pipe)"),
        (os.mkdir, "is a folder"),
        (lambda path: path.symlink_to(path.with_name("nowhere")), "is a dangling symbolic link"),
        (lambda path: None, "is missing"),
    ],
)
def test_what_is_not_a_file_is_said_so_never_waited_on(cache, tmp_path, make, kind):
    folder = tmp_path / "out"
    _written(folder, {"a.py": b"x = 1\n"})
    (folder / "a.py").unlink()
    make(folder / "a.py")
    with pytest.raises(manifests.UntrustedFile, match=f"a.py {re.escape(kind)}"):
        manifests.verified(folder, ["a.py"], "regenerate")


def test_a_copied_folder_holds_the_same_code_and_a_gone_folder_is_forgotten(cache, tmp_path):
    folder = tmp_path / "out"
    _written(folder, {"a.py": b"x = 1\n"})
    copy = tmp_path / "copy"
    shutil.copytree(folder, copy)
    assert manifests.verified(copy, ["a.py"], "regenerate") == {"a.py": b"x = 1\n"}
    assert manifests.manifest(copy) == manifests.manifest(folder)  # recorded for the copy too
    (copy / "a.py").write_bytes(b"x = 2\n")
    with pytest.raises(manifests.UntrustedFile, match="is not the file that fricgen wrote"):
        manifests.verified(copy, ["a.py"], "regenerate")
    shutil.rmtree(folder)
    manifests.record(tmp_path / "third", {})  # any record prunes those of folders that are gone
    assert manifests.manifest(folder) == {} and len(list((cache / "written").iterdir())) == 2


def test_trusted_copies_and_a_missing_home(cache, tmp_path, monkeypatch):
    folder = tmp_path / "out"
    copy = manifests.trusted_copy(folder, "laws/a.py", b"x = 1\n")
    assert copy.is_relative_to(cache) and copy.read_bytes() == b"x = 1\n"
    stamp = copy.stat().st_mtime_ns
    assert manifests.trusted_copy(folder, "laws/a.py", b"x = 1\n") == copy and copy.stat().st_mtime_ns == stamp  # Numba's cache stays valid
    for variable in (manifests.CACHE_ENV, "XDG_CACHE_HOME", "HOME"):
        monkeypatch.delenv(variable, raising=False)
    monkeypatch.setattr(Path, "home", lambda: (_ for _ in ()).throw(RuntimeError("no home")))
    with pytest.raises(manifests.UntrustedFile, match="no folder to record generated files in"):
        manifests.store()


def test_the_records_live_in_the_cache_even_when_the_lemma_cache_is_off(tmp_path, monkeypatch):
    """FRICGEN_CACHE=off switches off the lemma cache only: the records are no cache of results."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    monkeypatch.setenv(manifests.CACHE_ENV, "off")
    assert manifests.store() == tmp_path / "xdg" / "fricgen" / "written"
    monkeypatch.setenv(manifests.CACHE_ENV, str(tmp_path / "mine"))
    assert manifests.store() == tmp_path / "mine" / "written"


def test_a_lock_that_is_not_a_file_is_refused(cache, tmp_path):
    folder = tmp_path / "out"
    entry = manifests._entry(folder)
    entry.mkdir(parents=True)
    os.mkfifo(entry / ".lock")
    with pytest.raises(manifests.UntrustedFile, match="cannot record what fricgen wrote"):
        manifests.record(folder, {"a.py": manifests.sha256(b"")})


# --- names in generated code (printing only: no proof needed) --------------------------------------


@pytest.fixture(scope="module")
def printed(tmp_path_factory):
    """The Numba module and the plugin's files of one law, from a plain folder and from WEIRD."""
    parent = tmp_path_factory.mktemp("names")
    texts = {}
    for key, folder_name in (("plain", "plain"), ("weird", WEIRD)):
        folder = _law_folder(parent, folder_name)
        law = load_law(folder / "trusty.toml")
        model = derive_noise(law, "ito")
        source = f"{folder.name}/trusty.toml"
        module = law_module(law, {"ito": model}, law.source_hash, source, generate_command("trusty", folder))
        texts[key] = {"trusty.py": module, **plugin_files(law, model, law.source_hash, source, rng.ZIGGURAT)}
    return texts


def _changed_lines(plain: str, weird: str) -> list[str]:
    a, b = plain.splitlines(), weird.splitlines()
    assert len(a) == len(b), "a name added lines to generated code"
    return [y for x, y in zip(a, b) if x != y]


def test_a_folder_name_reaches_the_python_kernels_only_as_a_comment(printed):
    weird = printed["weird"]["trusty.py"]
    changed = _changed_lines(printed["plain"]["trusty.py"], weird)
    assert [line.split(":")[0] for line in changed] == ["# Source", "# Regenerate"]
    assert all(line.isascii() and line.isprintable() for line in changed)
    assert inert(f"{Path(WEIRD).name}/trusty.toml") in changed[0] and "*\\/tri\\u003f\\u003f\\/" in changed[1]
    tree = ast.parse(weird)  # compiles
    assert ast.dump(tree) == ast.dump(ast.parse(printed["plain"]["trusty.py"]))  # the same code: comments aside


@pytest.mark.parametrize("name", ["pair_fricgen_trusty.h", "pair_fricgen_trusty.cpp", "fricgen_trusty_plugin.cpp"])
def test_a_folder_name_reaches_the_cxx_plugin_only_as_a_comment(printed, name, tmp_path):
    """The changed lines hold no token for the C++ preprocessor (with trigraphs on): no line end, no
    splice, no end of comment escapes them."""
    changed = _changed_lines(printed["plain"][name], printed["weird"][name])
    assert changed and all(line.startswith("// Source:") for line in changed)
    probe = tmp_path / "probe.cpp"
    probe.write_text("\n".join(changed) + "\nint fricgen_probe;\n")
    done = subprocess.run(["g++", "-std=c++17", "-trigraphs", "-E", "-P", str(probe)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["int", "fricgen_probe;"], done.stdout


def test_a_folder_name_reaches_cmake_and_lammps_inputs_only_as_a_comment(printed, tmp_path):
    for name in ("CMakeLists.txt", "in.trusty_2d", "in.trusty_3d"):
        changed = _changed_lines(printed["plain"][name], printed["weird"][name])
        assert changed and all(line.startswith("# Source:") and not line.rstrip().endswith(("&", "\\")) for line in changed)
    script = tmp_path / "probe.cmake"
    script.write_text("\n".join(_changed_lines(printed["plain"]["CMakeLists.txt"], printed["weird"]["CMakeLists.txt"])) + "\n")
    cmake = shutil.which("cmake", path=str(Path(sys.prefix) / "bin")) or shutil.which("cmake")
    if cmake is None:
        pytest.fail("cmake is needed (pip install cmake, the [test] extra)")
    done = subprocess.run([cmake, "-P", str(script)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and done.stdout == done.stderr == "", done.stderr


def test_commands_in_messages_stay_on_one_line():
    assert shell_word("/a b/c") == "'/a b/c'"
    assert shell_word("/a\nb'\\") == "$'/a\\x0ab\\'\\\\'"  # bash reads \x0a as a newline
    assert shell_word("/x\udcff") == "$'/x\\xff'"  # a byte that is not UTF-8
    assert inert("laws/user_viscous.toml") == "laws/user_viscous.toml"
    assert inert("a*/b") == '"a*\\/b"' and inert("a??/b") == '"a\\u003f\\u003f\\/b"' and inert("a\\") == '"a\\\\"'


# --- the loader, on kernels generated for real -----------------------------------------------------


@pytest.fixture(scope="module")
def generated(tmp_path_factory):
    """A law folder named WEIRD with its kernels, generated by `fricgen generate --laws` (the proof runs)."""
    folder = _law_folder(tmp_path_factory.mktemp("generated"), WEIRD)
    assert main(["generate", "--laws", str(folder)]) == 0
    return folder


def _copy(generated: Path, tmp_path: Path) -> Path:
    copy = tmp_path / "laws"
    shutil.copytree(generated, copy, ignore=shutil.ignore_patterns("__pycache__"))
    return copy


def test_kernels_of_a_weird_folder_load_and_run(generated):
    kernels = load_law_kernels("trusty", LawSearch.only(generated))
    assert kernels.noise_amplitude("ito")(1.0, 3.0, 1.0, 7.0, 1.0, kernels.parameters()) == 6.0  # D = w gamma_f
    source = (generated / "generated" / "laws" / "trusty.py").read_text()
    assert f"# Regenerate: {inert(generate_command('trusty', generated))}\n" in source
    assert f"# Source: law 'trusty' ({inert(generated.resolve().name + '/trusty.toml')})" in source
    module_file = Path(kernels.module.__file__)
    assert module_file.is_relative_to(manifests.store()) and module_file.read_text() == source  # run from the trusted copy


@pytest.mark.parametrize("file", ["laws/trusty.py", "special.py", "__init__.py", "laws/__init__.py"])
def test_an_edited_kernel_is_refused_before_anything_runs(generated, tmp_path, file):
    copy = _copy(generated, tmp_path)
    load_law_kernels("trusty", LawSearch.only(copy))  # a copy holds fricgen's bytes: accepted (and recorded for the copy)
    canary = tmp_path / "RAN"
    path = copy / "generated" / file
    text = path.read_text().replace("return gamma_f*u*w", "return 2*gamma_f*u*w")
    path.write_text(text + f"open({str(canary)!r}, 'w')\n")  # the header kept
    with pytest.raises(KernelError, match=f"{re.escape(file.split('/')[-1])} is not the file that fricgen wrote") as refused:
        load_law_kernels("trusty", LawSearch.only(copy))
    assert "fricgen generate --laws" in str(refused.value) and not canary.exists()
    assert main(["generate", "--laws", str(copy), "trusty"]) == 0  # what the message says to do
    assert load_law_kernels("trusty", LawSearch.only(copy)).parameters()[0] == 2.0


def test_a_dropped_file_and_a_poisoned_pycache_never_run(generated, tmp_path):
    copy = _copy(generated, tmp_path)
    canary = tmp_path / "RAN"
    laws = copy / "generated" / "laws"
    (laws / "evil.py").write_text(f"open({str(canary)!r}, 'w')\n")
    cache = laws / "__pycache__"
    cache.mkdir()
    tag = f"py{sys.version_info.major}{sys.version_info.minor}"

    class Poison:
        def __reduce__(self):
            return (open, (str(canary), "w"))

    tree = ast.parse((laws / "trusty.py").read_text())
    for node in tree.body:  # Numba's index of each cached function: a pickle, loaded where it is found
        if isinstance(node, ast.FunctionDef):
            line = node.decorator_list[0].lineno if node.decorator_list else node.lineno
            (cache / f"trusty.{node.name}-{line}.{tag}.nbi").write_bytes(pickle.dumps(Poison()))
    evil = tmp_path / "evil_source.py"
    evil.write_text(f"open({str(canary)!r}, 'w')\n")  # Python's bytecode that skips its source check
    py_compile.compile(
        str(evil),
        cfile=str(cache / f"trusty.{sys.implementation.cache_tag}.pyc"),
        invalidation_mode=py_compile.PycInvalidationMode.UNCHECKED_HASH,
    )
    kernels = load_law_kernels("trusty", LawSearch.only(copy))
    assert kernels.friction(1.0, 1.0, 1.0, kernels.parameters()) == 2.0
    package = kernels.module.__name__.rsplit(".", 2)[0]
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module(f"{package}.laws.evil")
    assert not canary.exists(), "code from the law folder ran"
