"""What the exact contact step costs by itself, against the whole step and LAMMPS's frictionless step.

The pairwise contact step (fricgen.langevin.contact_step) is a Metropolis–Hastings move of each
contact mode; its acceptance needs the proposal density of the way back, so D is evaluated at the
start x and at the proposal y of every pair. This benchmark takes the contacts of the benchmark fluid
(2-D, N = 10 000, area fraction 0.6, WCA + solvent + Coulomb–Newton with its noise, Itô, dt = 1e-3,
one thread, after 2000 steps from the lattice) and times, per contact:

- the two evaluations of the law's kernel (f/u, D) at |x| and |y|, alone;
- the proposal of fricgen.langevin.contact_step (both evaluations, the map and its inverse, the
  normal and the uniform, the acceptance), without the velocity update, the colouring or a parallel loop;
- contact_step itself (finding the contacts, colouring them, the sweep that updates the velocities).

The kernels are compiled into these loops (the engine calls them as first-class functions, 2 to 3.5 %
slower: README), so the per-contact figures are, if anything, low.

Beside these, the whole step per particle-step with and without friction, and LAMMPS's system A (WCA +
Langevin, no friction) on one process, alternately, REPEATS times (medians). Any step that keeps
Maxwell–Boltzmann exact by accepting or rejecting evaluates the law at both ends, so the two kernel
evaluations per contact bound from below what friction with its noise adds to a step: fricgen with
friction reaches LAMMPS A per core only if its frictionless part costs at most LAMMPS A's step less
that bound (and less the proposal's whole cost, as the proposal is today).

LAMMPS: FRICGEN_LAMMPS as in benchmarks/langevin.py (without it, fricgen's figures only).
Run: python benchmarks/contact_floor.py
"""

from __future__ import annotations

import os
import statistics
import sys
import time
from pathlib import Path

import numba
import numpy as np

from fricgen.langevin.contact_step import _propose, contact_mode, contact_step, find_contacts
from fricgen.langevin.forces import conservative_forces
from fricgen.langevin.records import Bodies, Motion
from fricgen.rng import CONTACT, stream_key

sys.path.insert(0, str(Path(__file__).resolve().parent))
from langevin import N, lammps_rate, rate, simulation  # noqa: E402

REPEATS, CALLS = 5, 20


@numba.njit
def modes(motion, bodies, dims, pairs, geometry):
    """The contact mode x of every pair."""
    out = np.empty(pairs.shape[0], dtype=np.complex128)
    for p in range(pairs.shape[0]):
        i, k = pairs[p, 0], pairs[p, 1]
        nx, ny, nz = geometry[p, 0], geometry[p, 1], geometry[p, 2]
        out[p] = contact_mode(motion.velocity, motion.omega, i, k, bodies.radius[i], bodies.radius[k], nx, ny, nz, dims)[0]
    return out


@numba.njit(parallel=True)
def proposals(xs, dyn, params, law, key, pairs, geometry):
    """The proposal y (or x where it stays) of every pair, as the contact step draws it. A parallel loop
    (run on one thread) as in the engine: a serial loop would pay reference counts on ``params`` per call."""
    out = np.empty_like(xs)
    for p in numba.prange(xs.size):
        w, r, mu = geometry[p, 4], geometry[p, 3], geometry[p, 5]
        out[p] = _propose(xs[p], w, r, mu, dyn, params, law, key, pairs[p, 0], pairs[p, 1], dyn.dims - 1)[0]
    return out


@numba.njit(parallel=True)
def evaluations(xs, ys, dyn, params, contact, geometry):
    """The sum of (f/u + D) over both ends of every pair: two kernel evaluations per pair (a parallel
    loop for the same reason)."""
    total = 0.0
    for p in numba.prange(xs.size):
        w, r, mu = geometry[p, 4], geometry[p, 3], geometry[p, 5]
        for z in (xs[p], ys[p]):
            ratio, amplitude = contact(abs(z), w, r, mu, dyn.kT, params)
            total += ratio + amplitude
    return total


def seconds(call) -> float:
    """Median wall time of one call, over CALLS calls."""
    times = []
    for _ in range(CALLS):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    venv = Path(os.environ["FRICGEN_LAMMPS"]) if os.environ.get("FRICGEN_LAMMPS") else None
    numba.set_num_threads(1)
    sim, free = simulation(2), simulation(2, friction=False)
    sim.threads = 1
    s, p = sim.state, sim.particles
    bodies, dyn, couplings = Bodies(p.radius, p.inv_mass, p.inv_inertia), sim.dynamics(), sim.couplings
    force_kernel, contact, slope, weight = sim.step_kernels()
    listed = sim.neighbor_list
    lists, touching = (listed.start, listed.neighbors, listed.reverse), np.zeros(listed.neighbors.size, dtype=np.bool_)
    conservative_forces(s.position, bodies, dyn, couplings, force_kernel, lists, np.zeros((N, 3)), touching)
    pairs, geometry = find_contacts(s.position, bodies, dyn, couplings, weight, lists, touching)
    law, key = (contact, slope, weight), stream_key(dyn.seed, s.step, CONTACT)
    xs = modes(Motion(s.position, s.velocity, s.omega, s.orientation), bodies, s.dim, pairs, geometry)
    ys = proposals(xs, dyn, couplings.law, law, key, pairs, geometry)
    evaluations(xs, ys, dyn, couplings.law, contact, geometry)

    def step() -> None:
        motion = Motion(s.position, s.velocity.copy(), s.omega.copy(), s.orientation)
        contact_step(motion, bodies, dyn, couplings, law, lists, touching, key)

    step()
    figures = {name: [] for name in ("two D", "proposal", "contact_step", "pairwise", "frictionless", "LAMMPS A")}
    for _ in range(REPEATS):  # alternate: the machine's drift hits everyone
        figures["two D"].append(seconds(lambda: evaluations(xs, ys, dyn, couplings.law, contact, geometry)) / len(xs))
        figures["proposal"].append(seconds(lambda: proposals(xs, dyn, couplings.law, law, key, pairs, geometry)) / len(xs))
        figures["contact_step"].append(seconds(step) / len(xs))
        figures["pairwise"].append(1 / rate(sim, 1))
        figures["frictionless"].append(1 / rate(free, 1))
        if venv:
            figures["LAMMPS A"].append(1 / lammps_rate(venv, "in.A_2d_wca_langevin"))
    ns = {name: 1e9 * statistics.median(values) for name, values in figures.items() if values}
    per_particle = len(xs) / N
    print(f"2-D, N = {N}, {len(xs)} contacts ({per_particle:.2f} per particle), one thread, medians of {REPEATS} alternating repeats")
    print(f"  per contact: two kernel evaluations {ns['two D']:.0f} ns, the proposal {ns['proposal']:.0f} ns, "
          f"contact_step {ns['contact_step']:.0f} ns")  # fmt: skip
    print(f"  per particle-step: fricgen pairwise {ns['pairwise']:.0f} ns, frictionless {ns['frictionless']:.0f} ns "
          f"(friction adds {ns['pairwise'] - ns['frictionless']:.0f} ns)")  # fmt: skip
    if "LAMMPS A" in ns:
        floor, today = ns["LAMMPS A"] - per_particle * ns["two D"], ns["LAMMPS A"] - per_particle * ns["proposal"]
        print(f"  LAMMPS A {ns['LAMMPS A']:.0f} ns. To match it per core, fricgen's frictionless part may cost at most "
              f"{floor:.0f} ns with all of the contact step but the two kernel evaluations free "
              f"({floor / ns['frictionless']:.2f} of today's), {today:.0f} ns with today's proposal")  # fmt: skip


if __name__ == "__main__":
    sys.exit(main())
