"""Compiled Langevin dynamics of frictional spheres (F-35..40) in 2-D and 3-D.

One code path with 3-vectors: in 2-D, z = 0, spins are along z and the contact noise acts along
the single tangent t = z x r_hat (docs/physics.md#the-two-dimensional-reduction). A step of length
dt is the splitting B A O A B C with the pairwise contact step, B A O A C B with the explicit kick
(docs/physics.md#integrators-that-match-the-calculus):

- B: v += (dt/2) F/m with F = -dU/dr (WCA by default) + F0 e1 (active) + F_bulk;
- A: x += v dt/2 and the orientation turns by omega dt/2 (q <- exp(omega dt/4) q, lab frame);
- O: solvent, exact Ornstein–Uhlenbeck v <- c v + sqrt(kT (1 - c^2)/m) xi, c = exp(-gamma dt/m)
  (gamma_R, I for omega): no time-step bias of the solvent part; B A O A is one pass over the
  particles (fricgen.langevin.single_particle), the forces another (fricgen.langevin.forces);
- C: the contact, friction plus its noise, by one of two schemes (docs/physics.md#the-pairwise-contact-step):
  pairwise (the default; fricgen.langevin.contact_step): the pairs in contact one after another, each
  a Metropolis-adjusted update of its contact mode that keeps Maxwell–Boltzmann exact at any dt;
  explicit: the kick v += dt F_f/m + J/m (omega likewise with torques; fricgen.langevin.pairs), first
  order, with D taken where the calculus demands: at the start (Itô, Euler–Maruyama), averaged over
  start and predicted end (Stratonovich, stochastic Heun) or at the predicted end
  (Hänggi–Klimontovich); the prediction is the Euler–Maruyama kick, same noise.
  Laws on the rolling and spinning modes (docs/physics-modes.md) join both schemes: the pairwise step
  updates each pair's modes in turn (contact_step.contact_step_modes), the kick adds their torques
  (fricgen.langevin.modes); a run with a sliding law only takes the paper's path, unchanged.

Immobile (wall) particles have inverse mass and inertia 0: they never move, and drop out of
mu_ik = 1/m_i + 1/m_k + R_i^2/I_i + R_k^2/I_k. Kernels enter as first-class functions of the
types in fricgen.kernels, state and parameters as the records of fricgen.langevin.records: the
engine is compiled once for every law and cached on disk.
"""

from __future__ import annotations

import numba
import numpy as np
from numba import types

from fricgen.derive.calculus import Calculus

from ..rng import CONTACT, ROLLING, SOLVENT, SPINNING, stream_key
from .contact_step import contact_step, contact_step_modes
from .forces import conservative_forces
from .modes import MODE_FIELDS, gather_modes, mode_slots
from .neighbors import neighbor_list, still_valid
from .pairs import PAIR_FIELDS, TERMS, WCA_RANGE, gather, pair_slots
from .records import BODIES, COUPLINGS, DYNAMICS, KERNELS, MODE_KERNELS, MOTION, NEIGHBOR_LIST
from .single_particle import half_kick, kick_drift_solvent, solvent_coefficients

OK, NOT_FINITE, OVERLAP = 0, 1, 2  # status of advance()
_ITO, _STRATONOVICH = Calculus.ITO.index, Calculus.STRATONOVICH.index


@numba.njit(parallel=True, cache=True)
def _contact_kick(motion, bodies, dyn, terms, new):
    """Euler–Maruyama contact kick into new = (v, omega) (the Itô step and the predictor of the others)."""
    vel, omega, vnew, wnew, dt = motion.velocity, motion.omega, new[0], new[1], dyn.dt
    for i in numba.prange(vel.shape[0]):
        for a in range(3):
            vnew[i, a] = vel[i, a] + bodies.inv_mass[i] * (dt * terms[1, i, a] + terms[3, i, a])
            wnew[i, a] = omega[i, a] + bodies.inv_inertia[i] * (dt * terms[2, i, a] + terms[4, i, a])
        if dyn.dims == 2:
            vnew[i, 2] = 0.0
            wnew[i, 0] = wnew[i, 1] = 0.0


@numba.njit(parallel=True, cache=True)
def _correct(new, bodies, dyn, terms, again):
    """Replace the predictor's contact terms: Heun averages start and end, HK takes the end-point noise."""
    vnew, wnew, dt = new[0], new[1], dyn.dt
    for i in numba.prange(vnew.shape[0]):
        for a in range(3):
            if dyn.scheme == _STRATONOVICH:
                dv = 0.5 * (dt * (again[1, i, a] - terms[1, i, a]) + again[3, i, a] - terms[3, i, a])
                dw = 0.5 * (dt * (again[2, i, a] - terms[2, i, a]) + again[4, i, a] - terms[4, i, a])
            else:
                dv = again[3, i, a] - terms[3, i, a]
                dw = again[4, i, a] - terms[4, i, a]
            vnew[i, a] += bodies.inv_mass[i] * dv
            wnew[i, a] += bodies.inv_inertia[i] * dw


@numba.njit(cache=True)
def _per_slot(listed, explicit, modes):
    """For a neighbour list: (start, neighbors, reverse), the explicit kick's pair slots (none for the
    pairwise step), ``touching``, the pairs in contact that the force pass marks, and the explicit
    kick's slots of the rolling and spinning modes (none unless ``modes``)."""
    lists = (listed.start, listed.neighbors, listed.reverse)
    slots = np.zeros((listed.neighbors.size if explicit else 0, PAIR_FIELDS))
    mode_slots = np.zeros((listed.neighbors.size if explicit and modes else 0, MODE_FIELDS))
    return lists, slots, np.zeros(listed.neighbors.size, dtype=np.bool_), mode_slots


#: advance(motion, bodies, dynamics, couplings, kernels, mode kernels, neighbour list, first step, steps) -> (status,
#: steps, neighbour builds, contact proposals, rejections, sum of rejection probabilities, neighbour list)
_ADVANCE = types.Tuple([types.int64] * 5 + [types.float64, NEIGHBOR_LIST])(
    MOTION, BODIES, DYNAMICS, COUPLINGS, KERNELS, MODE_KERNELS, NEIGHBOR_LIST, types.int64, types.int64
)


@numba.njit(_ADVANCE, cache=True)
def advance(motion, bodies, dyn, couplings, kernels, modes, listed, first_step, steps):
    """Advance the motion in place by ``steps`` steps from step ``first_step``; returns (status, steps
    done, neighbour builds), the pairwise contact step's tally (proposals, rejections, sum of the
    rejection probabilities 1 - min(1, alpha)) and the neighbour list to pass to the next call.
    ``kernels``: (force, contact, slope, weight) as records.KERNELS, ``modes`` the rolling and spinning laws'
    kernels (records.MODE_KERNELS; ``couplings`` says which laws act); ``listed``: the list the last call returned
    (NeighborList.unbuilt() at first), kept while still valid for the motion's positions.

    status: OK, NOT_FINITE (a velocity became inf or NaN) or OVERLAP (r < overlap_limit sigma_ik).
    Forces at the current positions are recomputed on entry, so chunked runs and restarts are
    bit-identical to one long run.
    """
    pot_force, contact, slope, weight = kernels
    pos, vel, omega = motion.position, motion.velocity, motion.omega
    size, dims, skin = pos.shape[0], dyn.dims, dyn.skin
    cutoff = WCA_RANGE * 2.0 * bodies.radius.max() + skin
    builds = 0
    if not still_valid(listed, pos, dyn.box, dyn.inv_box, dims, cutoff, skin):
        listed, builds = neighbor_list(pos, dyn.box, dims, cutoff), 1
    solvent = solvent_coefficients(bodies, dyn)
    proposals, rejections, rejection = 0, 0, 0.0
    explicit = dyn.friction and not dyn.pairwise
    only_sliding = couplings.sliding and not (couplings.rolling or couplings.spinning)  # the paper's contact: its own path
    lists, slots, touching, spin_slots = _per_slot(listed, explicit, not only_sliding)
    terms, again = np.zeros((TERMS if explicit else 1, size, 3)), np.zeros((TERMS if explicit else 0, size, 3))
    force = terms[0]  # the conservative force (the explicit kick's pair pass fills it with the contact terms)
    new = (np.empty((size, 3)), np.empty((size, 3)))
    conservative_forces(pos, bodies, dyn, couplings, pot_force, lists, force, touching)  # at the initial positions
    for step in range(first_step, first_step + steps):
        n = step - first_step
        if kick_drift_solvent(motion, bodies, dyn, force, solvent, stream_key(dyn.seed, step, SOLVENT), listed.reference) > 0.5 * skin:
            listed = neighbor_list(pos, dyn.box, dims, cutoff)
            lists, slots, touching, spin_slots = _per_slot(listed, explicit, not only_sliding)
            builds += 1
        key = stream_key(dyn.seed, step, CONTACT)
        keys = (stream_key(dyn.seed, step, ROLLING), stream_key(dyn.seed, step, SPINNING)) if not only_sliding else (key, key)
        if explicit:
            switches = (key, couplings.sliding, dyn.noise, True)
            closest = pair_slots((pos, vel, omega), bodies, dyn, couplings, pot_force, contact, weight, lists, switches, slots)
            gather(bodies.radius, lists, slots, terms)
            if not only_sliding:
                mode_slots((pos, vel, omega), bodies, dyn, couplings, modes, lists, keys, dyn.noise, spin_slots)
                gather_modes(size, lists, spin_slots, terms)
        else:
            closest = conservative_forces(pos, bodies, dyn, couplings, pot_force, lists, force, touching)
        if closest < dyn.overlap_limit:
            return OVERLAP, n, builds, proposals, rejections, rejection, listed
        if explicit:
            _contact_kick(motion, bodies, dyn, terms, new)
            if dyn.noise and dyn.scheme != _ITO:
                switches = (key, couplings.sliding, True, False)
                pair_slots((pos, new[0], new[1]), bodies, dyn, couplings, pot_force, contact, weight, lists, switches, slots)
                gather(bodies.radius, lists, slots, again)
                if not only_sliding:
                    mode_slots((pos, new[0], new[1]), bodies, dyn, couplings, modes, lists, keys, True, spin_slots)
                    gather_modes(size, lists, spin_slots, again)
                _correct(new, bodies, dyn, terms, again)
        if explicit:
            vel[:] = new[0]
            omega[:] = new[1]
        if not half_kick(motion, bodies, dyn, force):
            return NOT_FINITE, n, builds, proposals, rejections, rejection, listed
        if dyn.friction and not explicit:  # the pairwise contact step, after the last half kick
            if only_sliding:
                tally = contact_step(motion, bodies, dyn, couplings, (contact, slope, weight), lists, touching, key)
            else:
                modes_keys = (key, keys[0], keys[1])
                tally = contact_step_modes(motion, bodies, dyn, couplings, (contact, slope, weight), modes, lists, touching, modes_keys)
            proposals, rejections, rejection = proposals + tally[0], rejections + tally[1], rejection + tally[2]
    return OK, steps, builds, proposals, rejections, rejection, listed
