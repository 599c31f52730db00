"""The LAMMPS plugin's sources and build cache are fricgen's own (docs/trust-model.md): CMake builds
only the sources that ``fricgen lammps`` wrote, from their verified copies in a folder that holds
nothing else; a build is reused only if fricgen built that very .so from those sources; a stamp or a
lock that is not a regular file is refused, never waited on; sources written before their law file
changed are refused as stale, before CMake runs.

CMake and LAMMPS are stood in for (tests/lammps builds and runs the real plugin): the stand-in
writes the .so and notes which sources it was given.
"""

from __future__ import annotations

import os
import threading
from pathlib import Path

import pytest

from fricgen.app.cli import lammps as plugin
from fricgen.derive.law import manifests
from fricgen.derive.law.lawdata import read_law_data, source_hash

LAW = "fake"


@pytest.fixture
def setup(tmp_path, monkeypatch):
    """(the plugin's folder, a LAMMPS, the builds made, the law file): the sources written by emit_plugin
    (their texts stood in for, with the law's source hash as the generator writes it: no derivation), and
    a CMake that writes the .so."""
    monkeypatch.setenv(manifests.CACHE_ENV, str(tmp_path / "cache"))
    law_file = tmp_path / "laws" / f"{LAW}.toml"
    law_file.parent.mkdir()
    law_file.write_text(f'name = "{LAW}"\nfriction = "gamma_f*u"\n')
    header = f"Source hash: {source_hash(read_law_data(law_file))}\n"
    texts = {name: f"// {name} of the plugin {LAW}\n// {header}" for name in plugin.plugin_sources(LAW)}
    texts["CMakeLists.txt"] = f"# {header}"
    monkeypatch.setattr(plugin, "plugin_texts", lambda name, calculus="ito": {**texts, f"in.{LAW}_2d": "# input\n"})
    builds = []

    def cmake(tool, source, build, lammps, jobs):
        builds.append(sorted(p.name for p in source.iterdir() if p.is_file()))
        (build / f"fricgen_{LAW}.so").write_bytes(b"\x7fELF built by fricgen's build")

    monkeypatch.setattr(plugin, "_cmake", cmake)
    monkeypatch.setattr(plugin, "_tool", lambda name: name)
    folder, written = plugin.emit_plugin(law_file, out=tmp_path / "sources")  # the texts are stood in for
    assert {status for _, status in written} == {"written"}
    lammps = plugin.Lammps(tmp_path / "lammps", tmp_path / "lammps", tmp_path / "lammps" / "lmp")
    return folder, lammps, builds, law_file


def test_a_build_is_reused_only_while_it_is_the_one_fricgen_made(setup, tmp_path):
    folder, lammps, builds, law_file = setup
    build = tmp_path / "build"
    so = plugin.build_plugin(folder, lammps, law_file, build)
    assert builds == [sorted(plugin.plugin_sources(LAW))]  # the verified sources, and nothing else
    assert plugin.build_plugin(folder, lammps, law_file, build) == so and len(builds) == 1  # reused
    so.write_bytes(b"\x7fELF not built by fricgen")  # a .so put in its place
    assert plugin.build_plugin(folder, lammps, law_file, build) == so and len(builds) == 2
    assert so.read_bytes() == b"\x7fELF built by fricgen's build"


def test_a_planted_build_with_a_right_stamp_is_not_reused(setup, tmp_path):
    """Anyone can compute the stamp (a hash of the sources): it proves nothing without the record
    of the build in the user's cache."""
    folder, lammps, builds, law_file = setup
    build = tmp_path / "planted"
    build.mkdir()
    source = plugin.verified_sources(folder.resolve(), LAW, "fricgen lammps")
    (build / plugin.STAMP).write_text(plugin.sources_hash(source, lammps) + "\n")
    (build / f"fricgen_{LAW}.so").write_bytes(b"\x7fELF someone else's")
    plugin.build_plugin(folder, lammps, law_file, build)
    assert len(builds) == 1 and (build / f"fricgen_{LAW}.so").read_bytes() == b"\x7fELF built by fricgen's build"


def test_edited_or_added_sources_never_reach_the_compiler(setup, tmp_path):
    folder, lammps, builds, law_file = setup
    (folder / "pair.h").write_text("#error a header dropped beside the sources, found before LAMMPS's own\n")
    plugin.build_plugin(folder, lammps, law_file, tmp_path / "build")
    assert "pair.h" not in builds[0]
    (folder / "CMakeLists.txt").write_text("execute_process(COMMAND touch RAN)\n")
    with pytest.raises(
        plugin.LammpsError, match=r"CMakeLists\.txt is not the file that fricgen wrote .*lammps fake --laws .* --out"
    ):
        plugin.build_plugin(folder, lammps, law_file, tmp_path / "build2")
    assert len(builds) == 1


@pytest.mark.parametrize("name", [plugin.STAMP, "fricgen-build.lock"])
@pytest.mark.parametrize("make", [os.mkfifo, os.mkdir])
def test_a_stamp_or_lock_that_is_not_a_file_is_refused_never_waited_on(setup, tmp_path, name, make):
    folder, lammps, builds, law_file = setup
    build = tmp_path / "build"
    build.mkdir()
    make(build / name)
    result = []

    def attempt():
        try:
            plugin.build_plugin(folder, lammps, law_file, build)
        except plugin.LammpsError as error:
            result.append(str(error))

    worker = threading.Thread(target=attempt, daemon=True)
    worker.start()
    worker.join(20)
    assert not worker.is_alive(), "the build waited on a FIFO"
    assert len(result) == 1 and f"{Path(build / name)} is a" in result[0] and "\n" not in result[0], result
    assert builds == []


def test_sources_older_than_their_law_file_are_refused_before_cmake_runs(setup, tmp_path):
    folder, lammps, builds, law_file = setup
    plugin.build_plugin(folder, lammps, law_file, tmp_path / "build")  # the control: fresh sources build
    law_file.write_text(law_file.read_text().replace("gamma_f*u", "2*gamma_f*u"))
    with pytest.raises(plugin.LammpsError) as refused:
        plugin.build_plugin(folder, lammps, law_file, tmp_path / "build")  # even where a build of the old sources is kept
    message = str(refused.value)
    assert "sources of law fake are stale" in message and f"{law_file} changed" in message and "\n" not in message
    assert f"run `fricgen lammps fake --laws {law_file.parent} --out {folder}`" in message
    assert len(builds) == 1
