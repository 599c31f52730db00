"""The single-particle part of a step, B A O A, in one pass over the particles.

Each particle, independently of all others (docs/physics.md#integrators-that-match-the-calculus):

- B: v += (dt/2) (F + F0 e1 + F_bulk) / m, e1 the body axis before the drift;
- A: x += v dt/2 (wrapped into the box), q <- exp(omega dt/4) q;
- O: the solvent's exact Ornstein–Uhlenbeck update v <- c v + s xi with c = exp(-gamma dt/m) and
  s = sqrt(kT (1 - c^2)/m) (gamma_R and I for omega), xi standard normals keyed on (key, i);
- A: as above, with the new v and omega.

One parallel region per step for all four (the engine's other regions are the pair passes), and
per-particle constants c, s computed once per call of the engine (:func:`solvent_coefficients`).
In 2-D both rotations turn about z and are applied as one, by (omega_1 + omega_2) dt/2.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..rng import ziggurat_normal
from .neighbors import squared_displacement

#: Columns of the solvent coefficients: c and s of translation, of rotation.
DAMP, SPREAD, DAMP_ROT, SPREAD_ROT = 0, 1, 2, 3


@numba.njit(cache=True)
def solvent_coefficients(bodies, dyn):
    """(N, 4) array of c = exp(-gamma dt/m), s = sqrt(kT (1 - c^2)/m) and their rotational twins."""
    out = np.zeros((bodies.inv_mass.size, 4))
    for i in range(out.shape[0]):
        c = math.exp(-dyn.gamma * bodies.inv_mass[i] * dyn.dt)
        cr = math.exp(-dyn.gamma_rot * bodies.inv_inertia[i] * dyn.dt)
        out[i, DAMP], out[i, SPREAD] = c, math.sqrt(dyn.kT * bodies.inv_mass[i] * (1.0 - c * c))
        out[i, DAMP_ROT], out[i, SPREAD_ROT] = cr, math.sqrt(dyn.kT * bodies.inv_inertia[i] * (1.0 - cr * cr))
    return out


@numba.njit(inline="always", cache=True)
def body_axis(quat, i):
    """e1 = R(q) (1, 0, 0) for the unit quaternion q = quat[i] = (s, x, y, z)."""
    s, x, y, z = quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3]
    return 1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + s * z), 2.0 * (x * z - s * y)


@numba.njit(inline="always", cache=True)
def rotate(quat, i, wx, wy, wz, dt):
    """q <- exp(omega dt/2) q for q = quat[i]: exact rotation by the lab-frame angle omega dt. (Indices,
    not the row quat[i]: a view's reference count costs more than the rotation's arithmetic.)"""
    rate = math.sqrt(wx * wx + wy * wy + wz * wz)
    if rate == 0.0:
        return
    c, s = math.cos(0.5 * rate * dt), math.sin(0.5 * rate * dt) / rate
    a0, a1, a2, a3 = c, s * wx, s * wy, s * wz
    b0, b1, b2, b3 = quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3]
    q0 = a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3
    q1 = a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2
    q2 = a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1
    q3 = a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0
    scale = 1.0 / math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3] = q0 * scale, q1 * scale, q2 * scale, q3 * scale


@numba.njit(inline="always", cache=True)
def _drift(pos, vel, i, dims, box, h):
    for a in range(dims):
        x = pos[i, a] + vel[i, a] * h
        pos[i, a] = x - box[a] * math.floor(x / box[a])


@numba.njit(inline="always", cache=True)
def _kick(vel, quat, inv_mass, dyn, force, i):
    """B of particle i: v += (dt/2) (F + F0 e1 + F_bulk) / m. (Arrays, not the records: a parfor
    loses writes into an array taken from a record inside the loop.)"""
    active, bulk = dyn.active, dyn.bulk
    e0, e1, e2 = body_axis(quat, i) if active != 0.0 else (0.0, 0.0, 0.0)
    scale = 0.5 * dyn.dt * inv_mass[i]
    vel[i, 0] += scale * (force[i, 0] + active * e0 + bulk[0])
    vel[i, 1] += scale * (force[i, 1] + active * e1 + bulk[1])
    if dyn.dims == 3:
        vel[i, 2] += scale * (force[i, 2] + active * e2 + bulk[2])


@numba.njit(parallel=True, cache=True)
def half_kick(motion, bodies, dyn, force):
    """B of every particle (the last part of a step); returns whether all velocities and spins are finite."""
    vel, omega, quat, inv_mass = motion.velocity, motion.omega, motion.orientation, bodies.inv_mass
    bad = 0
    for i in numba.prange(vel.shape[0]):
        _kick(vel, quat, inv_mass, dyn, force, i)
        for a in range(3):
            if not (math.isfinite(vel[i, a]) and math.isfinite(omega[i, a])):
                bad += 1
    return bad == 0


@numba.njit(parallel=True, cache=True)
def kick_drift_solvent(motion, bodies, dyn, force, solvent, key, reference):
    """B A O A of every particle (module docstring) with forces ``force`` and the noise of ``key``;
    returns the largest displacement from ``reference`` (positions at the neighbour-list build)."""
    pos, vel, omega, quat = motion.position, motion.velocity, motion.omega, motion.orientation
    dims, box, h = dyn.dims, dyn.box, 0.5 * dyn.dt
    moved = np.zeros(pos.shape[0])
    inv_mass, inv_box = bodies.inv_mass, dyn.inv_box  # bound here: taken from a record inside the loop, they would cost reference counts
    for i in numba.prange(pos.shape[0]):
        _kick(vel, quat, inv_mass, dyn, force, i)
        if inv_mass[i] == 0.0:
            continue  # immobile: no drift and no solvent
        _drift(pos, vel, i, dims, box, h)
        spin = omega[i, 2]
        if dims == 3:
            rotate(quat, i, omega[i, 0], omega[i, 1], omega[i, 2], h)
        c, s, cr, sr = solvent[i, DAMP], solvent[i, SPREAD], solvent[i, DAMP_ROT], solvent[i, SPREAD_ROT]
        first = 6 * i
        vel[i, 0] = c * vel[i, 0] + s * ziggurat_normal(key, first)
        vel[i, 1] = c * vel[i, 1] + s * ziggurat_normal(key, first + 1)
        omega[i, 2] = cr * omega[i, 2] + sr * ziggurat_normal(key, first + 2)
        if dims == 3:
            vel[i, 2] = c * vel[i, 2] + s * ziggurat_normal(key, first + 3)
            omega[i, 0] = cr * omega[i, 0] + sr * ziggurat_normal(key, first + 4)
            omega[i, 1] = cr * omega[i, 1] + sr * ziggurat_normal(key, first + 5)
            rotate(quat, i, omega[i, 0], omega[i, 1], omega[i, 2], h)
        else:
            rotate(quat, i, 0.0, 0.0, spin + omega[i, 2], h)
        _drift(pos, vel, i, dims, box, h)
        moved[i] = squared_displacement(pos, reference, i, box, inv_box, dims)
    return math.sqrt(moved.max()) if pos.shape[0] else 0.0
