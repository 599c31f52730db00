"""Cross-starts (``system.initial``): a run starts from the positions and body axes of another run's
checkpoint, with another model or mass; velocities and spins are drawn afresh at kT. A checkpoint of
another system is refused in one line."""

import numpy as np

from fricgen.app.cli import main
from fricgen.app.run.build import build
from fricgen.app.run.config import load_config, parse_override, resolve_source

SMALL = ["--set", "system.n=16", "--set", "run.equilibrate=0", "--set", "run.chunk=50", "--set", "output.trajectory_period=0"]


def _config(*settings):
    return load_config(resolve_source("passive"), [parse_override(text) for text in [*SMALL[1::2], *settings]])


def test_a_run_continues_the_state_of_another_with_another_model_and_mass(tmp_path):
    assert main(["run", "passive", *SMALL, "--steps", "100", "--out", str(tmp_path / "first")]) == 0
    checkpoint = tmp_path / "first" / "checkpoint.npz"
    simulation = build(_config(f"system.initial={checkpoint}", "law.contact_noise=false", "system.mass=0.5"))
    with np.load(checkpoint) as data:
        assert np.array_equal(simulation.state.position, data["position"])
        assert np.array_equal(simulation.state.orientation, data["orientation"])
        assert not np.array_equal(simulation.state.velocity, data["velocity"])  # drawn for the new mass
    assert simulation.state.step == 0 and (simulation.particles.mass == 0.5).all() and not simulation.config.law.contact_noise
    out = tmp_path / "second"
    assert main(["run", "passive", *SMALL, "--steps", "50", "--set", f"system.initial={checkpoint}", "--out", str(out)]) == 0
    assert (out / "summary.json").is_file()


def test_a_checkpoint_of_another_system_is_refused_in_one_line(tmp_path, capsys):
    assert main(["run", "passive", *SMALL, "--steps", "50", "--out", str(tmp_path / "first")]) == 0
    capsys.readouterr()
    checkpoint = tmp_path / "first" / "checkpoint.npz"
    for setting, expected in ((["--set", "system.n=25"], "holds 16 particles"), ([], "cannot read")):
        source = checkpoint if setting else tmp_path / "nothing.npz"
        args = ["run", "passive", *SMALL, *setting, "--set", f"system.initial={source}", "--out", str(tmp_path / "x")]
        assert main(args) == 2
        error = capsys.readouterr().err.strip()
        assert "system.initial" in error and expected in error and "\n" not in error, error
        assert not (tmp_path / "x").exists()
