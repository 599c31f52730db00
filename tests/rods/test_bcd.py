"""Brownian cluster dynamics: the cluster rule, hard-core invariants, reproducibility, physics."""

import numpy as np
import pytest

from fricgen import bcd
from fricgen.rods import RodConfig, RodSimulation, best_exponent, sticky_force_max
from fricgen.rods_theory import rod_profile


def velocities(forces):
    forces = np.array(forces, dtype=float)
    n = forces.size
    v = np.zeros(n)
    bcd._cluster_velocities(forces, np.arange(n), n, 1.0, v, np.zeros((2 * n + 2, 2), dtype=np.int64), np.zeros(n + 1))
    return v


def test_cluster_rule_splits_at_the_largest_positive_mean_force_difference():
    np.testing.assert_allclose(velocities([-1.0, 0.0, 1.0]), [-1.0, 0.0, 1.0])  # pulled apart: three 1-clusters
    np.testing.assert_allclose(velocities([1.0, 0.0, -1.0]), [0.0, 0.0, 0.0])  # pushed together: one 3-cluster
    np.testing.assert_allclose(velocities([2.0, -1.0, 3.0]), [0.5, 0.5, 3.0])  # {2, 1}: (3 - 0.5) beats (1 - 2)


def test_rods_never_overlap_or_pass_in_long_dense_runs():
    config = RodConfig(n=180, length=100.0, sigma=0.5, dt=1e-3, replicas=4, seed=5)  # rho_bar sigma = 0.9
    simulation = RodSimulation(config)
    for _ in range(20):
        simulation.advance(1000)  # raises on any overlap (the engine checks after every step)
        x = simulation.positions
        gaps = np.diff(np.concatenate([x, x[:, :1] + config.length], axis=1), axis=1)
        assert gaps.min() >= config.sigma * (1 - 1e-9)


def test_same_seed_same_run_and_chunking_does_not_matter():
    config = RodConfig(n=60, dt=1e-4, replicas=2, seed=9)
    a, b, c = RodSimulation(config), RodSimulation(config), RodSimulation(RodConfig(n=60, dt=1e-4, replicas=2, seed=10))
    a.advance(600)
    for _ in range(3):
        b.advance(200)
    c.advance(600)
    assert np.array_equal(a.positions, b.positions) and not np.array_equal(a.positions, c.positions)


def test_dilute_density_profile_matches_the_exact_theory():
    """rho_bar = 0.4, sigma = 0.5, U0 = 6 (B sec. III C): chi^2 per bin against Percus's profile."""
    config = RodConfig(n=40, length=100.0, sigma=0.5, dt=1e-5, replicas=4, bins=50, seed=7)
    simulation = RodSimulation(config)
    simulation.equilibrate(20.0, dt=1e-4)
    measured = simulation.run(200_000)
    theory = rod_profile(lambda x: 3 * np.cos(2 * np.pi * x), 0.5, 0.4)
    edges = np.linspace(0, 1, config.bins + 1)
    expected = np.array([theory.at(np.linspace(a, b, 41)).mean() for a, b in zip(edges, edges[1:])])
    chi2 = np.mean(((measured.rho - expected) / measured.rho_err) ** 2)
    assert chi2 < 2.0, chi2  # 50 bins: P(chi^2/50 > 2) < 1e-4 for a correct profile
    assert np.mean(np.abs(measured.rho - expected)) / 0.4 < 0.01


def test_sticky_force_helpers():
    """max|f_p| from (B-32) and the paper's optimal exponent p ~ 2.95 at eps = 0.05 (Fig. 5)."""
    s = np.linspace(1e-6, 0.05, 200_001)
    direct = np.max(3 * s**2 / (0.05**4 / 4 + s**3))
    assert sticky_force_max(1.0, 3.0, 0.05) == pytest.approx(direct, rel=1e-4)
    assert best_exponent(0.05) == pytest.approx(2.95, abs=0.05)


def test_bad_configurations_are_refused():
    with pytest.raises(ValueError, match="close packing"):
        RodConfig(n=200, length=100.0, sigma=0.5)
    with pytest.raises(ValueError, match="whole number of wavelengths"):
        RodConfig(length=100.5)
    with pytest.raises(ValueError, match="p > 1"):
        RodConfig(gamma=1.0, p=1.0)
    with pytest.warns(UserWarning, match="B-33"):
        RodSimulation(RodConfig(gamma=1.0, dt=1e-3))
