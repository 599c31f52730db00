"""The heap-driven BCD step against a direct transcription of the algorithm (B-11..19), and runs that do
not depend on the number of threads."""

import numba
import numpy as np

from fricgen.rods import RodSimulation, bcd, rod_config


def reference_step(x, forces, length, sigma, mu, dt):
    """One BCD step the plain way: clusters, then repeatedly the earliest collision over all pairs, every
    rod moved to it, the two clusters merged. Returns (x, v, number of merges)."""
    n, tolerance = x.size, bcd.CONTACT_TOLERANCE * sigma
    x, v = x.copy(), np.empty(x.size)

    def gap(i):
        return (x[i + 1] if i + 1 < n else x[0] + length) - x[i] - sigma

    start = next(i for i in range(n) if gap(i) > tolerance)
    members = []
    for offset in range(1, n + 1):
        members.append((start + offset) % n)
        if gap(members[-1]) > tolerance:
            count = len(members)
            stack, prefix = np.empty((2 * count + 2, 2), dtype=np.int64), np.empty(count + 1)
            bcd._cluster_velocities(forces, np.array(members), count, mu, v, stack, prefix)
            members = []
    elapsed, merges = 0.0, 0
    while True:
        first, when = -1, dt - elapsed
        for i in range(n):
            if v[i] > v[(i + 1) % n] and gap(i) / (v[i] - v[(i + 1) % n]) < when:
                first, when = i, max(gap(i) / (v[i] - v[(i + 1) % n]), 0.0)
        x += v * when
        elapsed += when
        if first < 0:
            return x, v, merges
        left, right = first, (first + 1) % n
        m, k = 1, 1
        while m < n and v[(left - m) % n] == v[left] and gap((left - m) % n) <= tolerance:
            m += 1
        while k < n and v[(right + k) % n] == v[right] and gap((right + k - 1) % n) <= tolerance:
            k += 1
        merged = (m * v[left] + k * v[right]) / (m + k)
        v[[(left - q) % n for q in range(m)] + [(right + q) % n for q in range(k)]] = merged
        merges += 1


def test_step_matches_the_direct_algorithm():
    """Dense rods (rho_bar sigma = 0.9) with long steps: many collisions and clusters per step."""
    config = rod_config(n=90, length=50.0, sigma=0.5, dt=1e-3, seed=3)
    simulation = RodSimulation(config)
    simulation.advance(200)  # leaves clusters in exact contact
    x, n = simulation.positions[0].copy(), config.model.n
    rng = np.random.default_rng(4)
    v, members, stack, prefix = np.empty(n), np.empty(n, dtype=np.int64), np.empty((2 * n + 2, 2), dtype=np.int64), np.empty(n + 1)
    heap_t, heap_i, when = np.empty(3 * n), np.empty(3 * n, dtype=np.int64), np.empty(n)
    merges = 0
    for _ in range(30):
        forces = rng.normal(0.0, np.sqrt(2.0 / config.numerics.dt), n)
        expected, expected_v, count = reference_step(x, forces, config.model.length, config.model.sigma, 1.0, config.numerics.dt)
        status = bcd._step(
            x, forces, v, config.model.length, config.model.sigma, 1.0, config.numerics.dt, (members, stack, prefix), (heap_t, heap_i, when)
        )
        assert status == bcd.OK
        np.testing.assert_allclose(x, expected, rtol=0, atol=1e-10)
        np.testing.assert_allclose(v, expected_v, rtol=1e-12)
        merges += count
    assert merges > 300


def test_a_full_heap_keeps_the_valid_events_only():
    """Pairs 1 and 5 hold valid events, pairs 2 and 6 cancelled ones (when = -1); scheduling pair 3 (gap
    0.5, closing at speed 1000: t = 5e-4) into the full heap rebuilds it from ``when`` first."""
    n, length, sigma, dt = 8, 8.0, 0.5, 1e-3
    x, v = np.arange(n, dtype=float), np.zeros(n)
    v[3] = 1000.0
    when = np.full(n, -1.0)
    when[1], when[5] = 3e-4, 1e-4
    heap_t, heap_i = np.empty(4), np.empty(4, dtype=np.int64)
    size = 0
    for t, i in ((3e-4, 1), (1e-4, 5), (9e-4, 2), (7e-4, 6)):
        size = bcd._push(heap_t, heap_i, size, t, i)
    size = bcd._schedule(x, v, 3, 0.0, length, sigma, dt, (heap_t, heap_i, when), size)
    events = []
    while size > 0:
        t, i, size = bcd._pop(heap_t, heap_i, size)
        events.append((t, i))
    assert events == [(1e-4, 5), (3e-4, 1), (5e-4, 3)] and when[3] == 5e-4


def test_runs_do_not_depend_on_the_number_of_threads():
    config = rod_config(n=40, dt=1e-4, replicas=3, seed=2)
    threads = numba.get_num_threads()
    runs = []
    try:
        for count in (1, min(2, numba.config.NUMBA_NUM_THREADS)):
            numba.set_num_threads(count)
            simulation = RodSimulation(config)
            simulation.advance(500)
            runs.append(simulation.positions)
    finally:
        numba.set_num_threads(threads)
    assert np.array_equal(*runs)
