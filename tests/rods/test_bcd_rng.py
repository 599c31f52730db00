"""The BCD noise: ziggurat normals keyed on (key, i) are exact N(0, 1), independent and pure."""

import math

import numba
import numpy as np
import pytest
from scipy import stats

from fricgen.rng import _ZIG_F, _ZIG_R, _ZIG_W, fold_key, stream_key, ziggurat_normal

SAMPLES = 1_000_000


@numba.njit  # not cached: a cached copy would keep the inlined rng code of before an edit of fricgen/rng.py
def draws(seed, steps, indices, replica):
    """z[s, k] = ziggurat_normal(fold_key(stream_key(seed, s, 4), replica), indices[k]), as the engine draws them."""
    out = np.empty((steps.size, indices.size))
    for a, s in enumerate(steps):
        key = fold_key(stream_key(seed, s, 4), replica)
        for b, i in enumerate(indices):
            out[a, b] = ziggurat_normal(key, i)
    return out


@pytest.fixture(scope="module")
def z():
    return draws(3, np.arange(SAMPLES // 50), np.arange(50), 1)


def test_tables_close_the_ziggurat():
    """Every layer has the area v of the base strip plus tail; the top one ends at f(0) = 1."""
    v = _ZIG_R * math.exp(-0.5 * _ZIG_R**2) + math.sqrt(math.pi / 2) * math.erfc(_ZIG_R / math.sqrt(2))
    edges = _ZIG_W * 2.0**53
    areas = edges[1:] * (_ZIG_F[2:] - _ZIG_F[1:-1])
    np.testing.assert_allclose(areas, v, rtol=1e-12)
    assert edges[0] * _ZIG_F[1] == pytest.approx(v, rel=1e-15)


def test_moments_and_ks_against_the_standard_normal(z):
    flat = z.ravel()
    error = 1 / math.sqrt(flat.size)
    assert abs(flat.mean()) < 5 * error
    assert abs(flat.var() - 1) < 5 * math.sqrt(2) * error
    assert abs(stats.kurtosis(flat)) < 5 * math.sqrt(24) * error
    assert stats.kstest(flat, "norm").pvalue > 1e-3


@pytest.mark.parametrize("cut", [1.0, 3.0, 4.0])
def test_tails(z, cut):
    """P(|z| > cut) within 5 standard errors; beyond 3.65 the samples come from the tail branch."""
    expected = 2 * stats.norm.sf(cut)
    assert abs(np.mean(np.abs(z) > cut) - expected) < 5 * math.sqrt(expected / z.size)


def test_neighbours_steps_and_replicas_are_uncorrelated(z):
    other = draws(3, np.arange(z.shape[0]), np.arange(50), 2)
    bound = 5 / math.sqrt(z.size)
    for a, b in ((z[:, :-1], z[:, 1:]), (z[:-1], z[1:]), (z, other)):
        assert abs(np.mean(a * b)) < bound
        assert abs(np.corrcoef((a * a).ravel(), (b * b).ravel())[0, 1]) < bound


def test_a_pure_function_of_key_and_index():
    indices = np.random.default_rng(0).permutation(1000)
    forward = draws(7, np.array([123, 124]), np.arange(1000), 0)
    np.testing.assert_array_equal(draws(7, np.array([123]), indices, 0)[0], forward[0, indices])  # any order
    assert not np.any(forward[0] == forward[1])
