"""MIPS detection: the verdict on synthetic configurations of known phases, and the ``mips`` entry
that ``fricgen run`` writes for active discs."""

import json

import numpy as np
import pytest

from fricgen.app.cli import main
from fricgen.app.studies.mips import Frame, detect, detect_trajectory, local_area_fraction, local_maxima, run_mips

R = 0.5
DISC = np.pi * R**2


def poisson(phi: float, length: float, seed: int) -> Frame:
    """An ideal gas (uniform random centres) at area fraction phi."""
    rng = np.random.default_rng(seed)
    n = round(phi * length**2 / DISC)
    return Frame(rng.uniform(0, length, (n, 2)), np.full(n, R), (length, length))


def hexagonal(phi: float, length: float, rows: int) -> np.ndarray:
    """``rows`` rows of a triangular lattice at area fraction phi along x, from y = 0."""
    spacing = np.sqrt(np.pi / (2 * np.sqrt(3)) * (2 * R) ** 2 / phi)
    columns = round(length / spacing)
    i, j = np.meshgrid(np.arange(columns), np.arange(rows))
    return np.c_[(i + 0.5 * (j % 2)).ravel() * length / columns, j.ravel() * spacing * np.sqrt(3) / 2]


def coexistence(phi_dense: float, phi_dilute: float, length: float, seed: int, shape: str) -> tuple[Frame, float]:
    """A dense hexagonal slab (half the box) or disc (a third of it) in a gas at phi_dilute; returns the
    frame and the dense area fraction as built."""
    rng = np.random.default_rng(seed)
    if shape == "slab":
        rows = round(length / 2 / (np.sqrt(np.pi / (2 * np.sqrt(3)) / phi_dense) * np.sqrt(3) / 2))
        dense = hexagonal(phi_dense, length, rows)
        height = dense[:, 1].max() + R
        inside = lambda p: p[:, 1] < height + R  # noqa: E731
        region = length * height
    else:
        radius = length * np.sqrt(1 / (3 * np.pi))
        lattice = hexagonal(phi_dense, length, round(length / np.sqrt(np.pi / (2 * np.sqrt(3)) / phi_dense) / 0.866))
        dense = lattice[np.hypot(*(lattice - length / 2).T) < radius]
        inside = lambda p: np.hypot(*(p - length / 2).T) < radius + 2 * R  # noqa: E731
        region = np.pi * radius**2
    gas = rng.uniform(0, length, (round(phi_dilute * length**2 / DISC * 1.5), 2))
    gas = gas[~inside(gas)][: round(phi_dilute * (length**2 - region) / DISC)]
    position = np.r_[dense, gas]
    return Frame(position, np.full(len(position), R), (length, length)), len(dense) * DISC / region


@pytest.mark.parametrize("phi", [0.003, 0.02, 0.1, 0.3, 0.5, 0.7])
def test_a_uniform_fluid_is_not_phase_separated(phi):
    mips = detect([poisson(phi, 60.0, seed) for seed in range(3)])
    assert not mips.phase_separated
    assert mips.phi_dilute is None and mips.phi_dense is None
    assert mips.phi_mean == pytest.approx(phi, abs=1e-3)


@pytest.mark.parametrize(
    "phi_dense, phi_dilute, shape", [(0.85, 0.1, "slab"), (0.8, 0.05, "slab"), (0.88, 0.2, "disc"), (0.75, 0.3, "disc")]
)
def test_coexisting_phases_are_found_with_their_area_fractions(phi_dense, phi_dilute, shape):
    """Dense and dilute area fractions within 0.02 and 0.03 of those built."""
    frame, built = coexistence(phi_dense, phi_dilute, 60.0, 1, shape)
    mips = detect([frame])
    assert mips.phase_separated
    assert mips.phi_dense == pytest.approx(built, abs=0.02)
    assert mips.phi_dilute == pytest.approx(phi_dilute, abs=0.03)
    assert mips.dip_ratio < 0.5
    assert 0.2 < mips.dense_share < 0.6


@pytest.mark.parametrize("seed", range(3))
def test_a_smooth_density_gradient_is_not_phase_separated(seed):
    """A gas whose area fraction ramps from 0.05 to 0.8 and back across the box: a flat histogram
    with noisy maxima at both ends (dip ratios 0.8 to 1), not two phases."""
    rng, length = np.random.default_rng(seed), 60.0
    n = round(0.425 * length**2 / DISC)
    y = rng.uniform(0, length, 4 * n)
    y = y[rng.uniform(0, 0.8, 4 * n) < 0.05 + 0.75 * (1 - np.abs(2 * y / length - 1))][:n]
    mips = detect([Frame(np.c_[rng.uniform(0, length, n), y], np.full(n, R), (length, length))])
    assert not mips.phase_separated
    assert mips.dip_ratio > 0.5


def test_two_phases_too_close_are_not_called_separated():
    frame, _ = coexistence(0.55, 0.4, 60.0, 2, "slab")
    assert not detect([frame]).phase_separated


def test_local_maxima_count_the_humps_of_a_histogram_including_its_edges():
    assert local_maxima(np.array([3.0, 2.0, 1.0, 4.0, 4.0, 0.5])).tolist() == [0, 3]  # edge bin; a plateau once
    assert local_maxima(np.array([0.0, 1.0, 2.0, 1.0, 0.0])).tolist() == [2]
    frame, _ = coexistence(0.75, 0.1, 60.0, 3, "slab")
    mips = detect([frame])
    assert len(local_maxima(np.array(mips.probability))) >= 2
    assert len(local_maxima(np.array(detect([poisson(0.4, 40.0, 6)]).probability))) == 1


def test_the_grid_holds_the_disc_areas():
    frame = poisson(0.3, 40.0, 5)
    field = local_area_fraction(frame)
    assert field.shape == (40, 40)
    assert field.mean() == pytest.approx(len(frame.radius) * DISC / 40.0**2, rel=1e-3)


def test_bad_input_is_refused():
    frame = poisson(0.3, 40.0, 5)
    with pytest.raises(ValueError, match="exceed 8 kernel widths"):
        local_area_fraction(Frame(frame.position, frame.radius, (10.0, 10.0)))
    with pytest.raises(ValueError, match="N radii"):
        local_area_fraction(Frame(frame.position, frame.radius[:-1], frame.box))
    with pytest.raises(ValueError, match="positive"):
        local_area_fraction(frame, kernel=0.0)
    with pytest.raises(ValueError, match="at least one frame"):
        detect([])


def test_a_run_in_a_box_too_small_gets_no_verdict(tmp_path):
    small = poisson(0.3, 11.0, 1)
    mips = run_mips(tmp_path, tmp_path / "trajectory.gsd", small, 100, 0)
    assert mips["phase_separated"] is None and "8 kernel widths" in mips["reason"]
    assert not (tmp_path / "local_density.png").exists()
    final = poisson(0.3, 40.0, 1)
    assert run_mips(tmp_path, tmp_path / "trajectory.gsd", final, 100, 0)["steps"] == [100]  # no trajectory: the final state


def test_fricgen_run_writes_the_mips_entry_and_figure(tmp_path, capsys):
    folder = tmp_path / "active"
    settings = ["system.n=300", "system.packing_fraction=0.3", "thermostat.dt=1e-4", "law.friction=false", "run.equilibrate=100"]
    settings += ["run.chunk=100", "output.period=100", "output.trajectory_period=100", "output.checkpoint_period=0"]
    assert main(["run", "active", *(a for s in settings for a in ("--set", s)), "--steps", "300", "--out", str(folder)]) == 0
    assert "MIPS (3 frames)" in capsys.readouterr().out
    mips = json.loads((folder / "summary.json").read_text())["mips"]
    assert mips["steps"] == [100, 200, 300]
    assert mips["phase_separated"] is False
    assert (folder / "local_density.png").stat().st_size > 10_000
    again = detect_trajectory(folder / "trajectory.gsd", first_step=100)
    assert again.probability == pytest.approx(mips["probability"], abs=1e-4)
