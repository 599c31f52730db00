"""A user's own law (a law file in their folder, as the notebook define_a_friction_law writes it) goes
through the same command: `fricgen lammps LAW --laws DIR --build` writes DIR/generated/lammps/LAW/,
builds it, and the plugin keeps kT under `mpirun -np 2`; once the law file changes, its sources are
stale and their build is refused, with the command that regenerates them."""

from __future__ import annotations

import pytest

from fricgen.app.cli import laws
from fricgen.app.cli.arguments import Parser
from fricgen.app.cli.lammps import LammpsError, add_lammps_command, build_plugin

from .helpers import run
from .test_thermostat import KT, script, temperatures

LAW = """name = "coulomb_viscous"
description = "Viscous below the slip speed, Coulomb plus a viscous part above (a user's law)."
friction = "Min(gamma_f*u, w*kappa_f + eta_f*u)"
weight = "wca"
calculi = ["ito"]

[parameters.gamma_f]
default = 6.0

[parameters.kappa_f]
default = 2.0

[parameters.eta_f]
default = 0.5
"""


def test_a_user_law_runs_in_lammps_under_two_ranks(lammps, tmp_path, capsys):
    folder = tmp_path / "my_laws"
    folder.mkdir()
    (folder / "coulomb_viscous.toml").write_text(LAW)
    parser = Parser(prog="fricgen")
    add_lammps_command(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["lammps", "coulomb_viscous", "--laws", str(folder), "--build", "--build-dir", str(tmp_path / "build")])
    args.search = laws.law_search(args)
    assert args.run(args) == 0
    assert "pair_fricgen_coulomb_viscous.cpp" in capsys.readouterr().out
    assert (folder / "generated" / "lammps" / "coulomb_viscous" / "in.coulomb_viscous_2d").is_file()
    plugin = tmp_path / "build" / "fricgen_coulomb_viscous.so"
    text = script(plugin, "coulomb_newton", 2, True, 4000, cells=20).replace("fricgen/coulomb_newton", "fricgen/coulomb_viscous")
    text = text.replace("gamma_f 6.0 kappa_f 5.0", "gamma_f 6.0 kappa_f 2.0 eta_f 0.5")
    work = tmp_path / "run"
    work.mkdir()
    found = temperatures(run(lammps, work, text, ranks=2))
    for name, (value, error) in found.items():
        assert abs(value - KT) < 3.0 * error, f"{name} = {value:.4f} +- {error:.4f} ({found})"
    law_file = folder / "coulomb_viscous.toml"
    law_file.write_text(LAW.replace("default = 0.5", "default = 0.25"))
    with pytest.raises(LammpsError, match=rf"law coulomb_viscous are stale: .*run `fricgen lammps coulomb_viscous --laws {folder}`$"):
        build_plugin(folder / "generated" / "lammps" / "coulomb_viscous", lammps, law_file, tmp_path / "build")
