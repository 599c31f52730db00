"""The two ways of summing conservative forces give the same bits, and the same as the pair slots."""

import numpy as np
import pytest

from fricgen.kernels import load_law_kernels, load_potential, no_weight
from fricgen.langevin import Particles, lattice_state
from fricgen.langevin.forces import _each_pair_once, _each_particle
from fricgen.langevin.neighbors import build_neighbors
from fricgen.langevin.pairs import PAIR_FIELDS, TERMS, gather, pair_slots
from fricgen.langevin.records import Bodies, Couplings, Dynamics


@pytest.mark.parametrize("dim", [2, 3])
def test_each_pair_once_and_each_particle_agree_bit_for_bit(dim):
    particles = Particles.spheres(300)
    state = lattice_state(particles, dim, 0.5 if dim == 2 else 0.3, seed=2)
    rng = np.random.default_rng(4)
    state.position[:, :dim] += rng.normal(0, 0.08, (300, dim))  # off the lattice: pairs at all distances
    state.position[:, :dim] %= state.box[:dim]
    bodies = Bodies(particles.radius, particles.inv_mass, particles.inv_inertia)
    inv_box = np.array([1 / state.box[a] if a < dim else 0.0 for a in range(3)])
    dyn = Dynamics(state.box, inv_box, np.zeros(3), dim, 1e-3, 1.0, 1.0, 1.0, 0.0, 1, 0, False, False, True, 0.3, 0.5, 2)
    wca = load_potential("wca")
    couplings = Couplings(np.array([1.0, 1.0]), np.zeros(1), False)
    lists = build_neighbors(state.position, state.box, dim, 2 ** (1 / 6) + 0.3)
    once, each = np.zeros((300, 3)), np.zeros((300, 3))
    touching_once, touching_each = np.ones(lists[1].size, dtype=bool), np.ones(lists[1].size, dtype=bool)
    cell, potential = (tuple(state.box), tuple(inv_box), dim), couplings.potential
    closest = _each_pair_once(state.position, bodies, cell, wca.force, potential, lists, once, touching_once)
    cell = (state.box, inv_box, dim)
    assert closest == _each_particle(state.position, bodies, cell, wca.force, potential, lists, each, touching_each) < 2 ** (1 / 6)
    owner = np.repeat(np.arange(300), np.diff(lists[0]))
    d = state.position[lists[1]] - state.position[owner]
    d -= state.box * np.rint(d / np.where(state.box > 0, state.box, 1))
    expected = (lists[1] > owner) & ((d[:, :dim] ** 2).sum(axis=1) < (2 ** (1 / 6)) ** 2)
    assert expected.any() and np.array_equal(touching_once, expected) and np.array_equal(touching_each, expected)
    slots, terms = np.zeros((lists[1].size, PAIR_FIELDS)), np.zeros((TERMS, 300, 3))
    switches = (np.uint64(1), False, False, True)
    contact = load_law_kernels("linear").contact("ito")  # not called: friction is off
    pair_slots((state.position, state.velocity, state.omega), bodies, dyn, couplings, wca.force, contact, no_weight, lists, switches, slots)
    gather(particles.radius, lists, slots, terms)
    assert np.abs(once).max() > 0
    assert np.array_equal(once, each) and np.array_equal(once, terms[0])
