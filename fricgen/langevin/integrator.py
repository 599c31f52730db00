"""Compiled Langevin dynamics of frictional spheres (F-35..40) in 2-D and 3-D.

One code path with 3-vectors: in 2-D, z = 0, spins are along z and the contact noise acts along
the single tangent t = z x r_hat (docs/physics.md#the-two-dimensional-reduction). A step of length
dt is the splitting B A O A C B (docs/physics.md#integrators-that-match-the-calculus):

- B: v += (dt/2) F/m with F = -dU/dr (WCA by default) + F0 e1 (active) + F_bulk;
- A: x += v dt/2 and the orientation turns by omega dt/2 (q <- exp(omega dt/4) q, lab frame);
- O: solvent, exact Ornstein–Uhlenbeck v <- c v + sqrt(kT (1 - c^2)/m) xi, c = exp(-gamma dt/m)
  (gamma_R, I for omega): no time-step bias of the solvent part;
- C: the contact, friction plus its noise, by one of two schemes (docs/physics.md#the-pairwise-contact-step):
  pairwise (the default; fricgen.langevin.contact_step): the pairs in contact one after another, each
  a Metropolis-adjusted update of its contact mode that keeps Maxwell–Boltzmann exact at any dt;
  explicit: the kick v += dt F_f/m + J/m (omega likewise with torques; fricgen.langevin.pairs), first
  order, with D taken where the calculus demands: at the start (Itô, Euler–Maruyama), averaged over
  start and predicted end (Stratonovich, stochastic Heun) or at the predicted end
  (Hänggi–Klimontovich); the prediction is the Euler–Maruyama kick, same noise.

Immobile (wall) particles have inverse mass and inertia 0: they never move, and drop out of
mu_ik = 1/m_i + 1/m_k + R_i^2/I_i + R_k^2/I_k. Kernels enter as first-class functions of the
types in fricgen.kernels, state and parameters as the records of fricgen.langevin.records: the
engine is compiled once for every law and cached on disk.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types

from derive.calculus import Calculus

from ..kernels import CONTACT_KERNEL, FRICTION_KERNEL, SCALAR_KERNEL
from ..rng import CONTACT, SOLVENT, normal_pair_at, stream_key
from .contact_step import contact_step
from .neighbors import build_neighbors, minimum_image
from .pairs import PAIR_FIELDS, TERMS, WCA_RANGE, gather, pair_slots
from .records import BODIES, COUPLINGS, DYNAMICS, MOTION

OK, NOT_FINITE, OVERLAP = 0, 1, 2  # status of advance()
_ITO, _STRATONOVICH = Calculus.ITO.index, Calculus.STRATONOVICH.index


@numba.njit(inline="always", cache=True)
def _body_x(q):
    """e1 = R(q) (1, 0, 0) for a unit quaternion q = (s, x, y, z)."""
    s, x, y, z = q[0], q[1], q[2], q[3]
    return 1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + s * z), 2.0 * (x * z - s * y)


@numba.njit(inline="always", cache=True)
def _rotate(q, wx, wy, wz, dt):
    """q <- exp(omega dt/2) q: exact rotation by the lab-frame angle omega dt."""
    rate = math.sqrt(wx * wx + wy * wy + wz * wz)
    if rate == 0.0:
        return
    c, s = math.cos(0.5 * rate * dt), math.sin(0.5 * rate * dt) / rate
    a0, a1, a2, a3 = c, s * wx, s * wy, s * wz
    b0, b1, b2, b3 = q[0], q[1], q[2], q[3]
    q0 = a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3
    q1 = a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2
    q2 = a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1
    q3 = a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0
    norm = math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    q[0], q[1], q[2], q[3] = q0 / norm, q1 / norm, q2 / norm, q3 / norm


@numba.njit(parallel=True, cache=True)
def _half_kick(motion, bodies, dyn, force):
    """v += (dt/2) (F_conservative + F0 e1 + F_bulk) / m."""
    vel, quat, inv_mass, active, bulk = motion.velocity, motion.orientation, bodies.inv_mass, dyn.active, dyn.bulk
    for i in numba.prange(vel.shape[0]):
        e0, e1, e2 = _body_x(quat[i]) if active != 0.0 else (0.0, 0.0, 0.0)
        scale = 0.5 * dyn.dt * inv_mass[i]
        vel[i, 0] += scale * (force[i, 0] + active * e0 + bulk[0])
        vel[i, 1] += scale * (force[i, 1] + active * e1 + bulk[1])
        if dyn.dims == 3:
            vel[i, 2] += scale * (force[i, 2] + active * e2 + bulk[2])


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


@numba.njit(parallel=True, cache=True)
def _solvent(motion, bodies, dyn, key):
    """Exact Ornstein–Uhlenbeck update of v and omega (mobile particles), noise keyed on (key, i)."""
    vel, omega, inv_mass, inv_inertia, dt, kT = motion.velocity, motion.omega, bodies.inv_mass, bodies.inv_inertia, dyn.dt, dyn.kT
    for i in numba.prange(vel.shape[0]):
        if inv_mass[i] == 0.0:
            continue
        c = math.exp(-dyn.gamma * inv_mass[i] * dt)
        spread = math.sqrt(kT * inv_mass[i] * (1.0 - c * c))
        cr = math.exp(-dyn.gamma_rot * inv_inertia[i] * dt)
        spread_rot = math.sqrt(kT * inv_inertia[i] * (1.0 - cr * cr))
        z0, z1 = normal_pair_at(key, i, 0, 0)
        z2, z3 = normal_pair_at(key, i, 0, 1)
        vel[i, 0] = c * vel[i, 0] + spread * z0
        vel[i, 1] = c * vel[i, 1] + spread * z1
        omega[i, 2] = cr * omega[i, 2] + spread_rot * z3
        if dyn.dims == 3:
            z4, z5 = normal_pair_at(key, i, 0, 2)
            vel[i, 2] = c * vel[i, 2] + spread * z2
            omega[i, 0] = cr * omega[i, 0] + spread_rot * z4
            omega[i, 1] = cr * omega[i, 1] + spread_rot * z5


@numba.njit(parallel=True, cache=True)
def _drift(motion, bodies, dyn, h):
    """x += v h (wrapped into the box), q <- exp(omega h/2) q (mobile particles)."""
    pos, vel, omega, box = motion.position, motion.velocity, motion.omega, dyn.box
    for i in numba.prange(pos.shape[0]):
        if bodies.inv_mass[i] == 0.0:
            continue
        for a in range(dyn.dims):
            x = pos[i, a] + vel[i, a] * h
            pos[i, a] = x - box[a] * math.floor(x / box[a])
        _rotate(motion.orientation[i], omega[i, 0], omega[i, 1], omega[i, 2], h)


@numba.njit(cache=True)
def _moved(pos, reference, dyn):
    """Largest displacement since the last neighbour-list build."""
    largest = 0.0
    for i in range(pos.shape[0]):
        d2 = 0.0
        for a in range(dyn.dims):
            d = minimum_image(pos[i, a] - reference[i, a], dyn.box[a], dyn.inv_box[a])
            d2 += d * d
        largest = max(largest, d2)
    return math.sqrt(largest)


#: advance(motion, bodies, dynamics, couplings, potential force, contact, friction slope, weight, first step, steps)
#: -> (status, steps, neighbour builds, contact proposals, rejections, sum of rejection probabilities)
_ADVANCE = types.Tuple([types.int64] * 5 + [types.float64])(
    MOTION, BODIES, DYNAMICS, COUPLINGS, SCALAR_KERNEL, CONTACT_KERNEL, FRICTION_KERNEL, SCALAR_KERNEL, types.int64, types.int64
)


@numba.njit(_ADVANCE, cache=True)
def advance(motion, bodies, dyn, couplings, pot_force, contact, slope, weight, first_step, steps):
    """Advance the motion in place by ``steps`` steps from step ``first_step``; returns (status, steps
    done, neighbour builds) and the pairwise contact step's tally (proposals, rejections, sum of the
    rejection probabilities 1 - min(1, alpha)). Kernels: pair potential force(r / sigma_ik, params),
    contact(u, w, r, mu, kT, params) -> (f/u, sqrt D) of the law's calculus, slope(u, w, r, params) =
    df/du, weight(r / sigma_ik, params).

    status: OK, NOT_FINITE (a velocity became inf or NaN) or OVERLAP (r < overlap_limit sigma_ik).
    Forces at the current positions are recomputed on entry, so chunked runs and restarts are
    bit-identical to one long run.
    """
    pos, vel, omega = motion.position, motion.velocity, motion.omega
    size, dims, skin = pos.shape[0], dyn.dims, dyn.skin
    cutoff = WCA_RANGE * 2.0 * bodies.radius.max() + skin
    lists = build_neighbors(pos, dyn.box, dims, cutoff)
    slots = np.zeros((lists[1].size, PAIR_FIELDS))
    reference = pos.copy()
    builds, proposals, rejections, rejection = 1, 0, 0, 0.0
    explicit = dyn.friction and not dyn.pairwise
    terms, again = np.zeros((TERMS if explicit else 1, size, 3)), np.zeros((TERMS, size, 3))  # the pairwise step needs the force alone
    new = (np.empty((size, 3)), np.empty((size, 3)))
    for n in range(-1, steps):
        step = first_step + max(n, 0)
        if n >= 0:
            _half_kick(motion, bodies, dyn, terms[0])
            _drift(motion, bodies, dyn, 0.5 * dyn.dt)
            _solvent(motion, bodies, dyn, stream_key(dyn.seed, step, SOLVENT))
            _drift(motion, bodies, dyn, 0.5 * dyn.dt)
            if _moved(pos, reference, dyn) > 0.5 * skin:
                lists = build_neighbors(pos, dyn.box, dims, cutoff)
                slots = np.zeros((lists[1].size, PAIR_FIELDS))
                reference[:] = pos
                builds += 1
        key = stream_key(dyn.seed, step, CONTACT)
        switches = (key, explicit and n >= 0, dyn.noise, True)
        closest = pair_slots((pos, vel, omega), bodies, dyn, couplings, pot_force, contact, weight, lists, switches, slots)
        gather(bodies.radius, lists, slots, terms)
        if n < 0:  # forces at the initial positions for the first half kick
            continue
        if closest < dyn.overlap_limit:
            return OVERLAP, n, builds, proposals, rejections, rejection
        velocities = (vel, omega)
        if explicit:
            _contact_kick(motion, bodies, dyn, terms, new)
            if dyn.noise and dyn.scheme != _ITO:
                pair_slots(
                    (pos, new[0], new[1]), bodies, dyn, couplings, pot_force, contact, weight, lists, (key, True, True, False), slots
                )
                gather(bodies.radius, lists, slots, again)
                _correct(new, bodies, dyn, terms, again)
            velocities = new
        elif dyn.friction:
            tally = contact_step(motion, bodies, dyn, couplings, (contact, slope, weight), lists, key)
            proposals, rejections, rejection = proposals + tally[0], rejections + tally[1], rejection + tally[2]
        if not (np.isfinite(velocities[0]).all() and np.isfinite(velocities[1]).all()):
            return NOT_FINITE, n, builds, proposals, rejections, rejection
        if explicit:
            vel[:] = new[0]
            omega[:] = new[1]
        _half_kick(motion, bodies, dyn, terms[0])
    return OK, steps, builds, proposals, rejections, rejection
