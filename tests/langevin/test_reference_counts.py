"""The engine's pair loops hold no atomic reference-count operations.

Numba counts references to arrays with atomic increments and decrements (NRT_incref/NRT_decref). In
a loop that calls a kernel, an array taken from a tuple within the loop, or passed to an inlined
helper that calls a kernel or branches, costs two such operations per pair, which took about a
quarter of the step before they were moved out (README, Speed). These tests compile the loop
functions afresh (the engine's cache holds machine code, not LLVM IR), with the kernels typed as
the engine types them (first-class functions), and look for reference counts in the blocks of the
control-flow graph that lie on a cycle. A negative control shows that the search finds them.
"""

from __future__ import annotations

import re

import numba
import numpy as np
import pytest
from numba import types

from fricgen.kernels import CONTACT_KERNEL, FRICTION_KERNEL, SCALAR_KERNEL, load_law_kernels, load_potential
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, lattice_state
from fricgen.langevin.contact_step import _sweep, colour_classes, find_contacts
from fricgen.langevin.forces import _each_pair_once, _each_particle
from fricgen.langevin.neighbors import build_neighbors
from fricgen.langevin.pairs import PAIR_FIELDS, pair_slots
from fricgen.langevin.records import Bodies, Motion
from fricgen.langevin.single_particle import kick_drift_solvent, solvent_coefficients
from fricgen.rng import CONTACT, stream_key

from .. import engine as passes

_REFCOUNT = re.compile(r"call void @(NRT_incref|NRT_decref)\(ptr %([\w.$]+)")


def counts_in_loops(function_ir: str) -> list[tuple[str, str]]:
    """(operation, value) of every reference count in a block of ``function_ir`` (one LLVM function)
    from which the block can be reached again."""
    blocks, label = {"entry": []}, "entry"
    for line in function_ir.splitlines()[1:]:
        start = re.match(r"^([\w.$-]+):", line)
        if start:
            label = start.group(1)
            blocks[label] = []
        else:
            blocks[label].append(line)
    successors = {name: set(re.findall(r"label %([\w.$-]+)", "\n".join(lines))) for name, lines in blocks.items()}

    def on_cycle(name: str) -> bool:
        seen, todo = set(), list(successors[name])
        while todo:
            block = todo.pop()
            if block == name:
                return True
            if block not in seen and block in successors:
                seen.add(block)
                todo.extend(successors[block])
        return False

    return [m.groups() for name, lines in blocks.items() if on_cycle(name) for m in map(_REFCOUNT.search, lines) if m]


def loop_bodies(dispatcher, arguments: tuple, kernels: dict[int, types.FunctionType]) -> list[str]:
    """The LLVM functions of ``dispatcher`` compiled afresh for ``arguments`` (argument j typed as
    kernels[j] where given) that run the loops: a parallel function's loop bodies (parfor gufuncs),
    else the function itself."""
    options = {k: v for k, v in dispatcher.targetoptions.items() if k != "cache"}
    fresh = numba.njit(**options)(dispatcher.py_func)
    signature = tuple(kernels.get(j) or numba.typeof(a) for j, a in enumerate(arguments))
    fresh.compile(signature)
    name = "parfor_gufunc" if options.get("parallel") else dispatcher.py_func.__name__
    functions = [f for f in re.split(r"\n(?=define )", fresh.inspect_llvm(signature)) if f.startswith("define")]
    named = [(re.search(r"@([\w.$]+)\(", f.splitlines()[0]).group(1), f) for f in functions]
    return [f for symbol, f in named if name in symbol and not symbol.startswith(("cpython.", "__gufunc__", "cfunc."))]  # no wrappers


@pytest.fixture(scope="module")
def engine():
    """Records and neighbour lists of a small 2-D fluid with contacts, after a few steps."""
    particles = Particles.spheres(64)
    law = load_law_kernels("coulomb_newton")
    sim = Simulation(LangevinConfig(law=Law("coulomb_newton")), particles, lattice_state(particles, 2, 0.7, seed=3), law)
    sim.threads = 1
    sim.advance(200)
    s = sim.state
    motion = Motion(s.position, s.velocity, s.omega, s.orientation)
    bodies, dyn = Bodies(particles.radius, particles.inv_mass, particles.inv_inertia), sim.dynamics()
    lists = build_neighbors(s.position, s.box, 2, 2 ** (1 / 6) + sim.config.skin)
    weight = sim.kernels.module.weight
    return sim, motion, bodies, dyn, lists, weight


def _check(dispatcher, arguments, kernels):
    bodies = loop_bodies(dispatcher, arguments, kernels)
    assert bodies, f"no loop function found in {dispatcher.py_func.__name__}"
    found = [count for body in bodies for count in counts_in_loops(body)]
    assert not found, f"{dispatcher.py_func.__name__}: reference counts within its loops: {found}"


def test_the_force_loops_count_no_references(engine):
    sim, motion, bodies, dyn, lists, _ = engine
    force, touching = np.zeros((64, 3)), np.zeros(lists[1].size, dtype=np.bool_)
    for loop, cell in (
        (_each_pair_once, (tuple(dyn.box), tuple(dyn.inv_box), dyn.dims)),
        (_each_particle, (dyn.box, dyn.inv_box, dyn.dims)),
    ):
        arguments = (motion.position, bodies, cell, sim.potential.force, sim.couplings.potential, lists, force, touching)
        _check(loop, arguments, {3: SCALAR_KERNEL})


def test_the_contact_loops_count_no_references(engine):
    sim, motion, bodies, dyn, lists, weight = engine
    touching = np.zeros(lists[1].size, dtype=np.bool_)
    passes.conservative_forces(motion.position, bodies, dyn, sim.couplings, sim.potential.force, lists, np.zeros((64, 3)), touching)
    pairs, geometry = passes.find_contacts(motion.position, bodies, dyn, sim.couplings, weight, lists, touching)
    assert pairs.shape[0] > 0
    _check(find_contacts, (motion.position, bodies, dyn, sim.couplings, weight, lists, touching), {4: SCALAR_KERNEL})
    law = (sim.contact, sim.kernels.friction_slope, weight)
    law_type = types.Tuple((CONTACT_KERNEL, FRICTION_KERNEL, SCALAR_KERNEL))
    key = np.uint64(stream_key(1, 1, CONTACT))
    arguments = (motion, bodies, dyn, sim.couplings.law, law, key, pairs, geometry, colour_classes(pairs, 64))
    _check(_sweep, arguments, {4: law_type})


def test_the_explicit_pair_loop_counts_no_references(engine):
    sim, motion, bodies, dyn, lists, weight = engine
    slots, switches = np.zeros((lists[1].size, PAIR_FIELDS)), (np.uint64(1), True, True, True)
    coordinates = (motion.position, motion.velocity, motion.omega)
    arguments = (coordinates, bodies, dyn, sim.couplings, sim.potential.force, sim.contact, weight, lists, switches, slots)
    _check(pair_slots, arguments, {4: SCALAR_KERNEL, 5: CONTACT_KERNEL, 6: SCALAR_KERNEL})


def test_the_particle_pass_counts_no_references(engine):
    """B A O A and the displacement since the list's build (an inlined helper with a loop)."""
    sim, motion, bodies, dyn, _, _ = engine
    key = np.uint64(stream_key(1, 1, CONTACT))
    arguments = (motion, bodies, dyn, np.zeros((64, 3)), solvent_coefficients(bodies, dyn), key, motion.position.copy())
    _check(kick_drift_solvent, arguments, {})


@numba.njit(inline="always")
def _helper(values, i, kernel, params):  # an array into an inlined helper that branches and calls a kernel
    if values[i] > 3.0:
        return 0.0
    return kernel(values[i], params)


@numba.njit
def _counting_loop(values, kernel, params):
    total = 0.0
    for i in range(values.size):
        total += _helper(values, i, kernel, params)
    return total


def test_the_search_finds_reference_counts_where_there_are_some():
    values = np.ones(4)
    bodies = loop_bodies(_counting_loop, (values, load_potential("wca").force, values), {1: SCALAR_KERNEL})
    assert [op for body in bodies for op, _ in counts_in_loops(body)].count("NRT_incref") >= 1
