"""Brownian cluster dynamics: the cluster rule, hard-core invariants, reproducibility, and profiles
against the exact theory (hard rods dilute and dense, sticky rods)."""

import dataclasses
import math

import numpy as np
import pytest

from fricgen.rods import (
    RodProfiles,
    RodSimulation,
    bcd,
    best_exponent,
    deviations,
    exact_profile,
    extrapolate_to_zero_dt,
    rod_config,
    sticky_force_max,
)


def velocities(forces):
    forces = np.array(forces, dtype=float)
    n = forces.size
    v = np.zeros(n)
    bcd._cluster_velocities(forces, np.arange(n), n, 1.0, v, np.zeros((2 * n + 2, 2), dtype=np.int64), np.zeros(n + 1))
    return v


def sample(config, duration, equilibration=0.25):
    """From the Monte Carlo equilibrium start: ``equilibration`` at dt (the BCD contact layer forms), then sample."""
    simulation = RodSimulation(config)
    simulation.equilibrate(equilibration)
    return simulation.run(round(duration / config.numerics.dt))


def test_cluster_rule_splits_at_the_largest_positive_mean_force_difference():
    np.testing.assert_allclose(velocities([-1.0, 0.0, 1.0]), [-1.0, 0.0, 1.0])  # pulled apart: three 1-clusters
    np.testing.assert_allclose(velocities([1.0, 0.0, -1.0]), [0.0, 0.0, 0.0])  # pushed together: one 3-cluster
    np.testing.assert_allclose(velocities([2.0, -1.0, 3.0]), [0.5, 0.5, 3.0])  # {2, 1}: (3 - 0.5) beats (1 - 2)


@pytest.mark.parametrize("layer", ["merge", "reflect", "bridge"])
def test_rods_never_overlap_or_pass_in_long_dense_runs(layer):
    config = rod_config(n=180, length=100.0, sigma=0.5, dt=1e-3, replicas=4, seed=5, contact_layer=layer)  # rho_bar sigma = 0.9
    simulation = RodSimulation(config)
    for _ in range(20):
        simulation.advance(1000)  # raises on any overlap (the engine checks after every step)
        x = simulation.positions
        gaps = np.diff(np.concatenate([x, x[:, :1] + config.model.length], axis=1), axis=1)
        assert gaps.min() >= config.model.sigma * (1 - 1e-9)


@pytest.mark.parametrize("layer", ["merge", "bridge"])
def test_same_seed_same_run_and_chunking_does_not_matter(layer):
    config = rod_config(n=60, dt=1e-4, replicas=2, seed=9, contact_layer=layer)
    a, b, c = RodSimulation(config), RodSimulation(config), RodSimulation(config.replace(seed=10))
    a.advance(600)
    for _ in range(3):
        b.advance(200)
    c.advance(600)
    assert np.array_equal(a.positions, b.positions) and not np.array_equal(a.positions, c.positions)


def test_dilute_density_profile_matches_the_exact_theory():
    """rho_bar sigma = 0.2, U0 = 6 (B sec. III C): chi^2 per bin against the exact profile."""
    config = rod_config(n=40, length=100.0, sigma=0.5, dt=1e-5, replicas=16, bins=50, seed=7)
    figures = deviations(sample(config, 0.5), exact_profile(config), contact=False)
    assert figures["chi2_per_dof"] < 2.0, figures  # 50 bins: P(chi^2/50 > 2) < 1e-4 for a correct profile
    assert figures["l1_dev_over_rho"] < 0.01, figures


def test_any_generated_field_the_asymmetric_ratchet():
    """Rods in the ratchet field U = (U0/2)[sin 2 pi x + (a/4) sin 4 pi x], a = 1.5, match its exact
    profile within error (the mean error is about 1.3 % of rho_bar here); the exact profile at
    a = 1.25 is rejected."""
    ratchet = {"field": "ratchet", "field_params": {"a": 1.5}}
    config = rod_config(n=40, length=100.0, sigma=0.5, U0=4.0, **ratchet, dt=1e-5, replicas=16, bins=50, seed=8)
    measured = sample(config, 1.0)
    figures = deviations(measured, exact_profile(config), contact=False)
    assert figures["chi2_per_dof"] < 2.0, figures
    other = deviations(measured, exact_profile(config.replace(field_params={"a": 1.25})), contact=False)
    assert other["chi2_per_dof"] > 10.0, other


def test_continuous_pair_force_from_a_generated_pair_potential():
    """Rods of length 0.5 with a WCA repulsion of diameter 0.55 (B-28; 6.5 kT at contact, zero beyond
    r = 0.55 * 2^(1/6)) at rho_bar sigma = 0.6 match the exact theory with that pair potential; the
    hard-rod profile is rejected."""
    wca = {"pair": "wca", "pair_params": {"epsilon": 1.0, "sigma": 0.55}, "pair_range": 0.55 * 2 ** (1 / 6) - 0.5}
    config = rod_config(n=120, length=100.0, sigma=0.5, **wca, dt=1e-5, replicas=16, bins=50, seed=1)
    measured = sample(config, 1.0)
    figures = deviations(measured, exact_profile(config), contact=False)
    assert figures["chi2_per_dof"] < 2.0, figures
    hard = deviations(measured, exact_profile(config.replace(pair=None, pair_params={}, pair_range=0.0)), contact=False)
    assert hard["chi2_per_dof"] > 10.0, hard


def tilted_cosine_drift(U0, force, kT=1.0, mu=1.0, points=400):
    """Exact mean velocity of one overdamped particle in (U0/2) cos(2 pi x) + constant force (lambda = 1):
    v = mu kT (1 - exp(-beta F)) / int_0^1 dx int_0^1 dz exp(beta[U(x + z) - U(x) - F z]) (periodic
    stationary current; the midpoint rule is spectrally accurate here)."""
    x = (np.arange(points) + 0.5) / points
    start, shift = np.meshgrid(x, x, indexing="ij")

    def energy(y):
        return U0 / 2 * np.cos(2 * np.pi * y)

    rise = energy(start + shift) - energy(start) - force * shift
    return mu * kT * (1 - np.exp(-force / kT)) / np.mean(np.exp(rise / kT))


def test_constant_drive_gives_the_exact_drift_in_the_tilted_field():
    """Two rods on a ring of 100 wavelengths (they rarely meet) driven by F = 2 over U0 = 4 barriers:
    the mean velocity over 50 time units is the exact single-particle drift, not the free mu F."""
    config = rod_config(n=2, length=100.0, sigma=0.5, U0=4.0, drive=2.0, dt=1e-4, replicas=32, seed=3)
    simulation = RodSimulation(config)
    simulation.equilibrate(1.0)
    start, duration = simulation.positions.copy(), 50.0
    simulation.advance(round(duration / config.numerics.dt))
    drift = (simulation.positions - start).mean(1) / duration  # one sample per replica
    mean, error = drift.mean(), drift.std(ddof=1) / np.sqrt(drift.size)
    assert abs(mean - tilted_cosine_drift(4.0, 2.0)) < 4 * error, (mean, error)
    assert abs(mean - config.model.mu * config.model.drive) > 10 * error


def test_open_line_hard_rods_are_sorted_free_brownian_motions():
    """On an open line without a field, y_i = x_i - i sigma of hard rods are independent Brownian
    motions relabelled in order (reflection = exchange of labels). From 3 rods packed in contact, at time T:
    E[y_last] = -E[y_first] = sqrt(2 D T) E[max of 3 normals] = sqrt(2 D T) 3 / (2 sqrt(pi)), E[y_middle] = 0,
    Var(mean y) = 2 D T / 3. Rods that passed through each other or stayed one cluster would give 0."""
    config = rod_config(n=3, length=math.inf, sigma=0.5, U0=0.0, dt=1e-5, replicas=3000, start_sweeps=0, seed=2)
    packed = np.arange(config.model.n) * config.model.sigma
    simulation = RodSimulation(config, positions=packed)
    duration = 0.1
    simulation.advance(round(duration / config.numerics.dt))
    y = (simulation.positions - packed) / math.sqrt(2 * config.model.diffusion * duration)
    error = y.std(0, ddof=1) / math.sqrt(config.sampling.replicas)
    expected = np.array([-1.0, 0.0, 1.0]) * 3 / (2 * math.sqrt(math.pi))
    assert np.all(np.abs(y.mean(0) - expected) < 4 * error), (y.mean(0), error)
    assert y.mean(1).var() * config.model.n == pytest.approx(1.0, abs=4 * math.sqrt(2 / config.sampling.replicas))
    with pytest.raises(ValueError, match="ring of finite length"):
        simulation.run(10)
    with pytest.raises(ValueError, match="needs initial positions"):
        RodSimulation(config)
    with pytest.raises(ValueError, match="no equilibrium"):
        rod_config(length=math.inf)
    with pytest.raises(ValueError, match="at least sigma"):
        RodSimulation(config, positions=[0.0, 0.4, 1.0])


@pytest.mark.parametrize("layer", ["bridge", "merge"])
def test_pooled_contact_error_counts_the_correlation_of_a_rings_bins(layer):
    """16 rings whose contact density is the exact one times (1 + 0.01 z_r) in every bin (a ring-wide fluctuation,
    as from its long-wavelength density modes): the pooled ratio's error is the scatter of the rings' pooled
    ratios, 0.01 std(z) / 4, for the local time (bridge) and the jackknife of the fit (merge). Adding the bins'
    errors in quadrature, as if they were independent, gave it about 4 times too small."""
    config = rod_config(n=140, length=100.0, sigma=0.5, dt=1e-4, replicas=16, bins=25, start_sweeps=0, contact_layer=layer)
    exact, c = exact_profile(config), config.sampling
    expected = exact.bin_means(c.bins, "contact")
    factor = 1 + 0.01 * np.random.default_rng(5).standard_normal(c.replicas)
    decay = np.exp(-4.0 * (np.arange(c.gap_bins) - 0.5).clip(0) * c.gap_width)  # rho_2(x, sigma + g) / rho_2(x, sigma+)
    density = factor[:, None, None] * expected[None, :, None] * decay[None, None, :]
    contact, covariance = RodSimulation(config)._contact(density)
    x, error = (np.arange(c.bins) + 0.5) / c.bins, np.sqrt(np.diagonal(covariance))
    measured = RodProfiles(x, np.zeros(c.bins), np.ones(c.bins), contact, error, 1, covariance)
    figures = deviations(measured, exact)
    assert figures["contact_ratio_err"] == pytest.approx(factor.std(ddof=1) / 4, rel=1e-3), figures
    assert figures["contact_ratio"] == pytest.approx(factor.mean(), rel=1e-4), figures  # merge: the fit of exp(-k g) per bin
    independent = deviations(dataclasses.replace(measured, contact_cov=None), exact)  # the bins' errors in quadrature
    assert independent["contact_ratio_err"] < 0.4 * figures["contact_ratio_err"], independent


def test_dense_profile_and_contact_density_after_extrapolation_in_sqrt_dt():
    """BCD's own merge layer at rho_bar sigma = 0.7: its O(sqrt(dt)) bias is resolved at dt = 4e-5 and 1e-5 (the contact density
    is 12 % and 6 % low), and the extrapolation to dt = 0 agrees with the exact theory within error."""
    coarse, fine = (
        rod_config(n=140, length=100.0, sigma=0.5, dt=dt, replicas=16, bins=25, seed=11, contact_layer="merge") for dt in (4e-5, 1e-5)
    )
    exact = exact_profile(fine)
    runs = [sample(config, 1.25) for config in (coarse, fine)]
    biased = deviations(runs[0], exact)
    assert biased["contact_ratio"] < 1 - 4 * biased["contact_ratio_err"], biased  # the bias is detected
    figures = deviations(extrapolate_to_zero_dt(*runs, 4.0), exact)
    assert figures["chi2_per_dof"] < 2.0, figures
    assert abs(figures["contact_ratio"] - 1) < 3 * figures["contact_ratio_err"] + 0.01, figures


def test_sticky_rods_match_the_exact_theory_of_their_representation_after_extrapolation_in_sqrt_dt():
    """gamma = 1, p = 3, eps = 0.05 at rho_bar sigma = 0.25, U0 = 6. The sticky force varies on the scale
    kT / max|f| = 0.017, so BCD's O(sqrt(dt)) contact layer over-binds: too many bonded pairs, which straddle
    the barrier tops. Detected at dt = 1e-5; extrapolated from 1e-5 and 2.5e-6 the profile is within error
    of the exact delta_eps profile (B-31), and the hard-rod profile is rejected. Baxter's limit (B-29)
    differs by O(eps), about 0.4 % of rho_bar (fricgen bcd reports it)."""
    coarse, fine = (
        rod_config(n=50, length=100.0, sigma=0.5, gamma=1.0, p=3.0, eps=0.05, dt=dt, replicas=16, bins=25, seed=4, contact_layer="merge")
        for dt in (1e-5, 2.5e-6)
    )
    exact = exact_profile(fine)
    runs = [sample(config, 1.5, equilibration=0.1) for config in (coarse, fine)]
    biased = deviations(runs[0], exact, contact=False)
    assert biased["chi2_per_dof"] > 3.0, biased
    figures = deviations(extrapolate_to_zero_dt(*runs, 4.0), exact, contact=False)
    assert figures["chi2_per_dof"] < 2.0 and figures["l1_dev_over_rho"] < 0.025, figures
    hard = deviations(runs[1], exact_profile(fine.replace(gamma=0.0)), contact=False)
    assert hard["chi2_per_dof"] > 10.0, hard


def test_sticky_force_helpers():
    """max|f_p| from (B-32) and the paper's optimal exponent p ~ 2.95 at eps = 0.05 (Fig. 5)."""
    s = np.linspace(1e-6, 0.05, 200_001)
    direct = np.max(3 * s**2 / (0.05**4 / 4 + s**3))
    assert sticky_force_max(1.0, 3.0, 0.05) == pytest.approx(direct, rel=1e-4)
    assert best_exponent(0.05) == pytest.approx(2.95, abs=0.05)


def test_bad_configurations_are_refused():
    with pytest.raises(ValueError, match="close packing"):
        rod_config(n=200, length=100.0, sigma=0.5)
    with pytest.raises(ValueError, match="whole number of wavelengths"):
        rod_config(length=100.5)
    with pytest.raises(ValueError, match="p > 1"):
        rod_config(gamma=1.0, p=1.0)
    with pytest.warns(UserWarning, match="B-33"):
        RodSimulation(rod_config(gamma=1.0, dt=1e-3))
    with pytest.warns(UserWarning, match="the field's Euler step"):
        RodSimulation(rod_config(n=20, dt=3e-3, replicas=2, start_sweeps=0))
    with pytest.raises(ValueError, match="close packing"):
        exact_profile(rod_config(n=197))  # the theory's vectors beyond double precision: rho < 0 without the check
    with pytest.raises(ValueError, match="gap_bins"):
        RodSimulation(rod_config(n=20, dt=1e-3, gap_bins=10, replicas=2, contact_layer="merge")).run(20)
    with pytest.raises(ValueError, match="pair potential"):
        RodSimulation(rod_config(field="sticky"))
    with pytest.raises(ValueError, match=r"no parameter\(s\) \['b'\]"):
        exact_profile(rod_config(field="ratchet", field_params={"b": 1.0}))
    with pytest.raises(LookupError, match="no generated potential 'sawtooth'"):
        RodSimulation(rod_config(field="sawtooth"))
    with pytest.raises(ValueError, match="U0 and wavelength"):
        rod_config(field_params={"lambda": 2.0})
    wca = {"pair": "wca", "pair_params": {"sigma": 0.55}}
    with pytest.raises(ValueError, match="gamma = 0"):
        rod_config(**wca, pair_range=0.12, gamma=1.0)
    with pytest.raises(ValueError, match="pair_range < sigma"):
        rod_config(**wca, pair_range=0.5)
    with pytest.raises(ValueError, match="not zero beyond"):
        RodSimulation(rod_config(**wca, pair_range=0.1))  # WCA reaches 0.617
    with pytest.raises(ValueError, match="external field"):
        RodSimulation(rod_config(pair="cosine", pair_range=0.1))
    with pytest.raises(ValueError, match="need a pair potential"):
        rod_config(pair_range=0.1)
    with pytest.raises(ValueError, match="replicas >= 2"):
        RodSimulation(rod_config(n=20, dt=1e-3, replicas=1)).run(20)
