"""The sticky boundary of Baxter's rods (eps = 0, fricgen.rods.sticky; docs/physics-bcd-sticky-boundary.md)."""

import math

import numba
import numpy as np
import pytest
from scipy import integrate, stats

from fricgen.rods import RodSimulation, deviations, exact_profile, rod_config
from fricgen.rods.sticky import detach_probability, emission_norm, emitted_gap


@pytest.mark.parametrize("alpha", [0.0, 3e-7, 0.2, -0.7])
def test_emission_variates_invert_the_emission_law(alpha):
    """Q(alpha) is the integral of h, and emitted_gap inverts its distribution (quadrature)."""

    def h(y):
        return math.exp(2 * alpha * y) * stats.norm.cdf(-y - alpha) + stats.norm.cdf(alpha - y)

    norm = integrate.quad(h, 0, 40)[0]
    assert emission_norm(alpha) == pytest.approx(norm, rel=1e-9)
    for u in (0.02, 0.5, 0.97):
        assert integrate.quad(h, 0, emitted_gap(alpha, u))[0] / norm == pytest.approx(u, abs=1e-8)


@numba.njit(cache=True)
def _pair_chain(gaps, steps, drift, spread, gamma, alpha_used, seed):
    """Gaps of one pair each, with constant drift (per step) and spread sqrt(v), on the sticky boundary
    (0: bonded): the free bridge, a touch bonds; a bond breaks with probability q(alpha_used) to an emitted
    gap. Returns the bonded fraction and the mean free gap per gap, over the steps."""
    np.random.seed(seed)
    bonded, free = np.zeros(gaps.size), np.zeros(gaps.size)
    q = detach_probability(alpha_used, spread, gamma)
    for _ in range(steps):
        for i in range(gaps.size):
            a = gaps[i]
            if a == 0.0:
                if np.random.random() < q:
                    gaps[i] = spread * emitted_gap(alpha_used, np.random.random())
            else:
                b = a + drift + spread * np.random.normal()
                touched = b <= 0.0 or -math.log1p(-np.random.random()) > 2 * a * b / spread**2
                gaps[i] = 0.0 if touched else b
            if gaps[i] == 0.0:
                bonded[i] += 1.0 / steps
            else:
                free[i] += gaps[i] / steps
    return bonded, free


@pytest.mark.parametrize("alpha_used", ["drift", "drift-free"])
def test_a_pair_pushed_together_keeps_baxter_law_at_a_long_step(alpha_used):
    """A pair with constant relative drift c < 0 (D_rel = 2): the stationary law is
    p0 [exp(c g / D_rel) dg + gamma delta(g)], bonded fraction gamma / (gamma + D_rel / |c|). At dt = 0.01,
    c = -10 (alpha = -0.5) the scheme keeps it; the drift-free detach and emission (alpha = 0) give a bonded
    fraction near gamma Q(alpha) / Q(0) / (...) instead: its control."""
    relative, c, dt, gamma = 2.0, -10.0, 0.01, 0.5
    spread = math.sqrt(2 * relative * dt)
    used = c * dt / spread if alpha_used == "drift" else 0.0
    gaps = np.full(8000, 0.2)
    _pair_chain(gaps, 100, c * dt, spread, gamma, used, 3)  # to the stationary law (relaxation: about 3 steps)
    bonded, free = _pair_chain(gaps, 400, c * dt, spread, gamma, used, 4)
    fraction, mean_gap = gamma / (gamma + relative / abs(c)), relative / abs(c)
    groups = bonded.reshape(40, -1).mean(1)  # the pairs are independent
    measured, error = groups.mean(), groups.std(ddof=1) / math.sqrt(groups.size)
    free_mean = free.sum() / (1 - bonded).sum()
    assert (abs(measured - fraction) < 4 * error) == (alpha_used == "drift"), (measured, error, fraction)
    if alpha_used == "drift":
        assert free_mean == pytest.approx(mean_gap, rel=0.02), free_mean


def test_two_rods_on_a_ring_bond_with_baxter_weight():
    """Two free rods on a ring (one cluster when bonded): a pair is bonded with probability
    gamma / (L - 2 sigma + 2 gamma), the ratio of the atom to the gap's measure."""
    gamma, dt, steps = 0.3, 1e-3, 20_000
    config = rod_config(n=2, length=3.0, sigma=0.5, U0=0.0, gamma=gamma, eps=0.0, dt=dt, replicas=32, bins=10, start_sweeps=200)
    simulation = RodSimulation(config)
    counts = (np.zeros((32, 10)), np.zeros((32, 10, config.sampling.gap_bins)))
    simulation.advance(steps, counts)
    per_ring = counts[1][:, :, 0].sum(1) / (2 * steps)
    exact = gamma / (3.0 - 1.0 + 2 * gamma)
    assert abs(per_ring.mean() - exact) < 3 * per_ring.std(ddof=1) / math.sqrt(32), (per_ring.mean(), exact)


@pytest.fixture(scope="module")
def baxter_runs():
    """The default study (N = 50, L = 100, sigma = 0.5, U0 = 6, 16 rings, 0.25 + 1.25 time units; 20 000 sweeps) at
    dt = 1e-4 for gamma = 1 and 10 (44 % of the pairs bonded), and gamma = 10 run as 5: the sojourn rate twice too high."""

    def run(gamma, simulated):
        config = rod_config(gamma=gamma, eps=0.0, dt=1e-4, seed=1, start_sweeps=20_000)  # sticky rings relax slowly in MC
        simulation = RodSimulation(config.replace(gamma=simulated))
        simulation.equilibrate(0.25)
        return deviations(simulation.run(12_500), exact_profile(config))

    return {"1": run(1.0, 1.0), "10": run(10.0, 10.0), "10 as 5": run(10.0, 5.0)}


@pytest.mark.parametrize("gamma", ["1", "10"])
def test_baxter_profiles_within_error_at_dt_1e_4(baxter_runs, gamma):
    """rho(x) and the bonded density gamma rho_2(x, x + sigma+) against the exact Baxter profile."""
    figures = baxter_runs[gamma]
    assert figures["chi2_per_dof"] < 2.0 and figures["contact_chi2_per_dof"] < 2.0, figures
    assert abs(figures["contact_ratio"] - 1) < 3 * figures["contact_ratio_err"], figures


def test_a_wrong_sojourn_is_caught(baxter_runs):
    """The negative control: bonds that break twice as often (gamma / 2 in q) miss the profile and the
    shape of the bonded density (counted with that gamma) by far more than their errors."""
    figures = baxter_runs["10 as 5"]
    assert figures["chi2_per_dof"] > 5.0 and figures["contact_chi2_per_dof"] > 5.0, figures


def test_the_sticky_boundary_starts_from_20000_sweeps_by_default():
    """2000 Monte Carlo sweeps leave sticky rings 2-3 errors per bin off at gamma = 1: the boundary's default is 20 000,
    hard rods keep 2000, and a given number is kept."""
    assert rod_config(gamma=1.0, eps=0.0).start_sweeps == 20_000
    assert rod_config().start_sweeps == 2000
    assert rod_config(gamma=1.0, eps=0.0, start_sweeps=300).start_sweeps == 300
