"""A law resolved once and handed to the engine as an object: a notebook loads a law of its own
folder with ``fricgen.load_law`` and builds a simulation with it, without any context manager or
environment variable; a checkpoint records the law file it ran, and resuming with another version
of the law is refused."""

import numpy as np
import pytest

import fricgen
from fricgen.app.run.build import resolve_law
from fricgen.derive.driver import generate
from fricgen.derive.law.catalogues import BUILT_IN
from fricgen.errors import ConfigError, KernelError
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, lattice_state, load_checkpoint, save_checkpoint
from fricgen.langevin.contact_law import ContactLaw

from .helpers import arrays, passive

LAW = """name = "notebook_viscous"
description = "A viscous law of one's own: f = w gamma_f u."
friction = "w*gamma_f*u"
weight = "wca"
calculi = ["ito"]

[parameters.gamma_f]
default = {default}
unit = "t0/sigma"
"""


def _law_folder(folder, default):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "notebook_viscous.toml").write_text(LAW.format(default=default))
    generate(catalogue=folder)
    return folder


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return _law_folder(tmp_path_factory.mktemp("notebook") / "laws", 2.0)


def test_a_law_of_ones_own_folder_runs_without_a_context_manager(folder, monkeypatch):
    monkeypatch.delenv("FRICGEN_LAWS", raising=False)
    with pytest.raises(KernelError, match="unknown law 'notebook_viscous'"):
        fricgen.load_law("notebook_viscous")  # not on the search path
    law = fricgen.load_law("notebook_viscous", folder=folder)
    assert law.path == (folder / "notebook_viscous.toml").resolve()
    simulation = passive("notebook_viscous", n=16, law_kernels=law)
    simulation.run(20)
    assert simulation.state.step == 20 and np.isfinite(arrays(simulation)).all()


def test_kernels_of_another_law_are_refused(folder):
    with pytest.raises(ConfigError, match="law.name: is 'coulomb_newton', but the kernels .* 'notebook_viscous'"):
        passive("coulomb_newton", n=16, law_kernels=fricgen.load_law("notebook_viscous", folder=folder))


def test_a_missing_folder_is_one_clear_error(tmp_path):
    with pytest.raises(KernelError, match="does not exist"):
        fricgen.load_law("notebook_viscous", folder=tmp_path / "nowhere")


def test_resuming_with_another_version_of_the_law_is_refused(folder, tmp_path):
    law = fricgen.load_law("notebook_viscous", folder=folder)
    simulation = passive("notebook_viscous", n=16, law_kernels=law)
    simulation.run(10)
    checkpoint = save_checkpoint(tmp_path / "run.npz", simulation)
    resumed = load_checkpoint(checkpoint, law=law)
    assert np.array_equal(arrays(resumed), arrays(simulation)) and resumed.state.step == 10
    other = _law_folder(tmp_path / "edited", 3.0)  # the same name, another law file
    with pytest.raises(ConfigError, match="the checkpoint ran .*notebook_viscous.toml .* not .*edited"):
        load_checkpoint(checkpoint, law=fricgen.load_law("notebook_viscous", folder=other))


def test_the_engine_takes_the_resolved_law_never_a_name():
    """A name is a TypeError on one line (the engine looks nothing up); kernels are bound to the
    configuration once; an edge's ContactLaw is taken as it is, and refused for another configuration."""
    particles = Particles.spheres(16)
    state = lattice_state(particles, 2, 0.6, seed=1)
    config = LangevinConfig(law=Law("linear"))
    with pytest.raises(TypeError, match="law must be the resolved law .* not 'linear'") as refused:
        Simulation(config, particles, state, "linear")
    assert "\n" not in str(refused.value)
    law = resolve_law(config.law, 2, BUILT_IN)
    assert isinstance(law, ContactLaw) and law.names == ["linear"] and law.first.kernels.path.name == "linear.toml"
    simulation = Simulation(config, particles, state, law)
    assert simulation.law is law and simulation.kernels.source_hash == simulation.kernels.module.SOURCE_HASH
    with pytest.raises(ConfigError, match="law: the contact law handed to the simulation is \\['linear'\\] \\(ito\\), not \\['coulomb'\\]"):
        Simulation(LangevinConfig(law=Law("coulomb")), particles, state, law)


def test_a_parameter_out_of_range_is_refused_once_with_its_key():
    with pytest.raises(ConfigError, match="law.rolling_parameters.gamma_r"):
        resolve_law(Law("coulomb_newton", rolling="rolling_coulomb_newton", rolling_parameters={"gamma_r": -1.0}), 3, BUILT_IN)
