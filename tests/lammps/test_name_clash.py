"""Two plugins whose laws' names become one C++ class (fricgen.derive.law.names), loaded into one LAMMPS:
the second plugin's code resolves the class to the first one's (LAMMPS loads plugins with global
symbols), and loading it fails with a LAMMPS error instead of its styles running the other law.

fricgen refuses such a pair of laws before it writes a plugin, so the second plugin is the committed
plugin of linear with its law renamed Linear (style fricgen/Linear, files and target fricgen_Linear,
built for "Linear <hash>"), its class still PairFricgenLinear."""

from __future__ import annotations

import re
import shutil

import pytest

from fricgen.app.cli.lammps import _cmake, _tool, sources_hash
from fricgen.derive.law.catalogues import GENERATED

from .conftest import BUILD_ROOT
from .helpers import run

SCRIPT = """units lj
atom_style sphere
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 single 1 1 1
set type 1 diameter 1.0
set type 1 mass 1.0
{loads}
pair_style fricgen/{style} 1.0 1
pair_coeff * * 1.0 1.0
comm_modify vel yes
run 0
"""


@pytest.fixture(scope="module")
def renamed(lammps):
    """The .so of linear's plugin renamed Linear (its class unchanged), built once per session."""
    source = GENERATED / "lammps" / "linear"
    digest = re.search(r"Source hash: (\w+)", (source / "pair_fricgen_linear.cpp").read_text()).group(1)
    folder = BUILD_ROOT / f"renamed-{sources_hash(source, lammps)[:16]}"
    plugin = folder / "build" / "fricgen_Linear.so"
    if not plugin.is_file():
        shutil.rmtree(folder, ignore_errors=True)
        (folder / "src").mkdir(parents=True)
        for path in source.iterdir():
            text = path.read_text().replace(f'"linear {digest}"', f'"Linear {digest}"')
            for old, new in (("fricgen/linear", "fricgen/Linear"), ("fricgen/exact/linear", "fricgen/exact/Linear")):
                text = text.replace(old, new)
            text = text.replace("fricgen_linear", "fricgen_Linear")  # files, CMake target
            (folder / "src" / path.name.replace("fricgen_linear", "fricgen_Linear")).write_text(text)
        _cmake(_tool("cmake"), folder / "src", folder / "build", lammps, 2)
    return plugin


def test_a_plugin_refuses_the_class_of_another_law(lammps, plugin, renamed, tmp_path):
    first = plugin("linear")
    alone = tmp_path / "alone"
    alone.mkdir()
    run(lammps, alone, SCRIPT.format(loads=f"plugin load {renamed}", style="Linear"))  # the control: alone it runs
    both = tmp_path / "both"
    both.mkdir()
    with pytest.raises(AssertionError, match="plugin fricgen/Linear: its class PairFricgenLinear holds the code of law linear"):
        run(lammps, both, SCRIPT.format(loads=f"plugin load {first}\nplugin load {renamed}", style="Linear"))
