"""Compiled Langevin dynamics of frictional spheres (F-35..40) in 2-D and 3-D.

One code path with 3-vectors: in 2-D, z = 0, spins are along z and the contact noise acts along
the single tangent t = z x r_hat (PHYSICS.md, 2-D reduction). A step of length dt is the splitting
B A O A C B:

- B: v += (dt/2) F/m with F = -dU/dr (WCA by default) + F0 e1 (active) + F_bulk;
- A: x += v dt/2 and the orientation turns by omega dt/2 (q <- exp(omega dt/4) q, lab frame);
- O: solvent, exact Ornstein–Uhlenbeck v <- c v + sqrt(kT (1 - c^2)/m) xi, c = exp(-gamma dt/m)
  (gamma_R, I for omega): no time-step bias of the solvent part;
- C: contact kick v += dt F_f/m + J/m (omega likewise with torques), F_f = (f/u) u_perp and
  tau_f = R_i r_hat x F_f (F-5..8), J = sqrt(D) sqrt(2 kT dt) P z (3-D) or sqrt(D) sqrt(2 kT dt) z t
  (2-D) with z keyed on (seed, step, i, k). D is taken where the calculus demands: at the start
  (Itô, Euler–Maruyama), averaged over start and predicted end (Stratonovich, stochastic Heun) or
  at the predicted end (Hänggi–Klimontovich); the prediction is the Euler–Maruyama kick, same z.

Each pair i < k is computed once into its slot of the neighbour list; particle k receives -F and
the same torque direction (tau_k = R_k r_hat x F_i). Per-particle sums run in the sorted order of
the neighbour lists: results do not depend on the thread count. Immobile (wall) particles have
inverse mass and inertia 0: they never move, and drop out of mu_ik = 1/m_i + 1/m_k + R_i^2/I_i +
R_k^2/I_k. Kernels enter as first-class functions with explicit signatures (as derive.emit prints
them): the engine is compiled once for every law and cached on disk.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types

from .neighbors import build_neighbors, minimum_image
from .rng import CONTACT, SOLVENT, normal_pair_at, stream_key

_F, _I, _B, _U = types.float64, types.int64, types.boolean, types.uint64
_V, _M, _L = types.Array(_F, 1, "C"), types.Array(_F, 2, "C"), types.Array(_I, 1, "C")
_T = types.Array(_F, 3, "C")
SCALAR_KERNEL = types.FunctionType(_F(_F, _V))  # weight(r, params), potential force(r, params)
CONTACT_KERNEL = types.FunctionType(types.UniTuple(_F, 2)(_F, _F, _F, _F, _F, _V))  # (f/u, sqrt(D))

WCA_RANGE = 2.0 ** (1.0 / 6.0)
ITO, STRATONOVICH, HK = 0, 1, 2
OK, NOT_FINITE, OVERLAP = 0, 1, 2  # status of advance()

#: Per pair i < k, in the slot of (i, k): conservative force on i (0:3), friction force on i (3:6),
#: r_hat x friction force (6:9), noise impulse on i (9:12), r_hat x noise impulse (12:15).
PAIR_FIELDS = 15
#: terms[j, i, :] of a pass: force, friction, friction torque, noise impulse, noise torque impulse.
TERMS = 5


@numba.njit(inline="always", cache=True)
def _cross(a0, a1, a2, b0, b1, b2):
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@numba.njit(_F(_F, _V), cache=True)
def no_weight(r, params):
    """w = 1 for laws without a distance weight (friction acts within the potential's range)."""
    return 1.0


@numba.njit(
    _F(_M, _M, _M, _V, _V, _V, _V, _V, _I, _L, _L, SCALAR_KERNEL, _V, CONTACT_KERNEL, SCALAR_KERNEL, _V, _B, _F, _F, _U, _B, _B, _B, _M),
    parallel=True,
    cache=True,
)
def pair_slots(pos, vel, omega, radius, inv_mass, inv_inertia, box, inv_box, dims, start, neighbors, pot_force, pot_params,
               contact, weight, law_params, has_weight, kT, dt, noise_key, friction_on, noise_on, conservative, slots):  # fmt: skip
    """Pair quantities of every pair i < k within range, computed once; returns min r / sigma_ik."""
    size = pos.shape[0]
    closest = np.full(size, np.inf)
    noise_scale = math.sqrt(2.0 * kT * dt)
    for i in numba.prange(size):
        ri = radius[i]
        for slot in range(start[i], start[i + 1]):
            k = neighbors[slot]
            if k < i:
                continue
            out = slots[slot]
            out[:] = 0.0
            if inv_mass[i] == 0.0 and inv_mass[k] == 0.0:
                continue  # two immobile (wall) particles: no effect, and mu_ik = 0
            dx = minimum_image(pos[k, 0] - pos[i, 0], box[0], inv_box[0])
            dy = minimum_image(pos[k, 1] - pos[i, 1], box[1], inv_box[1])
            dz = minimum_image(pos[k, 2] - pos[i, 2], box[2], inv_box[2]) if dims == 3 else 0.0
            r2 = dx * dx + dy * dy + dz * dz
            rk = radius[k]
            sigma = ri + rk
            reach = WCA_RANGE * sigma
            if r2 >= reach * reach:
                continue
            r = math.sqrt(r2)
            closest[i] = min(closest[i], r / sigma)
            nx, ny, nz = dx / r, dy / r, dz / r
            if conservative:
                magnitude = pot_force(r / sigma, pot_params) / sigma  # -dU/dr, scaled to sigma_ik
                out[0], out[1], out[2] = -magnitude * nx, -magnitude * ny, -magnitude * nz
            if not friction_on:
                continue
            # u_perp = P (v_k - v_i) - (R_i w_i + R_k w_k) x n   (F-4)
            wx = ri * omega[i, 0] + rk * omega[k, 0]
            wy = ri * omega[i, 1] + rk * omega[k, 1]
            wz = ri * omega[i, 2] + rk * omega[k, 2]
            rvx, rvy, rvz = vel[k, 0] - vel[i, 0], vel[k, 1] - vel[i, 1], vel[k, 2] - vel[i, 2]
            along = rvx * nx + rvy * ny + rvz * nz
            cx, cy, cz = _cross(wx, wy, wz, nx, ny, nz)
            ux, uy, uz = rvx - along * nx - cx, rvy - along * ny - cy, rvz - along * nz - cz
            u = math.sqrt(ux * ux + uy * uy + uz * uz)
            w = weight(r / sigma, law_params) / sigma if has_weight else 1.0
            mu = inv_mass[i] + inv_mass[k] + ri * ri * inv_inertia[i] + rk * rk * inv_inertia[k]
            ratio, root = contact(u, w, r, mu, kT, law_params)
            out[3], out[4], out[5] = ratio * ux, ratio * uy, ratio * uz
            out[6], out[7], out[8] = _cross(nx, ny, nz, out[3], out[4], out[5])
            if noise_on:
                amplitude = root * noise_scale
                if dims == 3:  # P z: one random tangential force (PHYSICS.md)
                    z0, z1 = normal_pair_at(noise_key, i, k, 0)
                    z2 = normal_pair_at(noise_key, i, k, 1)[0]
                    zn = z0 * nx + z1 * ny + z2 * nz
                    out[9], out[10], out[11] = amplitude * (z0 - zn * nx), amplitude * (z1 - zn * ny), amplitude * (z2 - zn * nz)
                else:  # along t = z x n
                    z0 = normal_pair_at(noise_key, i, k, 0)[0]
                    out[9], out[10] = -amplitude * z0 * ny, amplitude * z0 * nx
                out[12], out[13], out[14] = _cross(nx, ny, nz, out[9], out[10], out[11])
    return closest.min() if size else np.inf


@numba.njit(types.none(_V, _L, _L, _L, _M, _T), parallel=True, cache=True)
def gather(radius, start, neighbors, reverse, slots, terms):
    """terms[:, i] = sums over i's pairs in the sorted order of its list (-F and R_k torques for k > i)."""
    for i in numba.prange(radius.size):
        terms[:, i, :] = 0.0
        for slot in range(start[i], start[i + 1]):
            source, sign = (slot, 1.0) if neighbors[slot] > i else (reverse[slot], -1.0)
            values = slots[source]
            for j in range(TERMS):
                scale = radius[i] if j == 2 or j == 4 else sign  # torques: R_i r_hat x F for both partners
                for a in range(3):
                    terms[j, i, a] += scale * values[3 * j + a]


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
def _half_kick(vel, quat, inv_mass, dims, dt, active, bulk, force):
    """v += (dt/2) (F_conservative + F0 e1 + F_bulk) / m."""
    for i in numba.prange(vel.shape[0]):
        e0, e1, e2 = _body_x(quat[i]) if active != 0.0 else (0.0, 0.0, 0.0)
        scale = 0.5 * dt * inv_mass[i]
        vel[i, 0] += scale * (force[i, 0] + active * e0 + bulk[0])
        vel[i, 1] += scale * (force[i, 1] + active * e1 + bulk[1])
        if dims == 3:
            vel[i, 2] += scale * (force[i, 2] + active * e2 + bulk[2])


@numba.njit(parallel=True, cache=True)
def _contact_kick(vel, omega, inv_mass, inv_inertia, dims, dt, terms, vnew, wnew):
    """Euler–Maruyama contact kick (the Itô step and the predictor of the other schemes)."""
    for i in numba.prange(vel.shape[0]):
        for a in range(3):
            vnew[i, a] = vel[i, a] + inv_mass[i] * (dt * terms[1, i, a] + terms[3, i, a])
            wnew[i, a] = omega[i, a] + inv_inertia[i] * (dt * terms[2, i, a] + terms[4, i, a])
        if dims == 2:
            vnew[i, 2] = 0.0
            wnew[i, 0] = wnew[i, 1] = 0.0


@numba.njit(parallel=True, cache=True)
def _correct(scheme, vnew, wnew, inv_mass, inv_inertia, dt, terms, again):
    """Replace the predictor's contact terms: Heun averages start and end, HK takes the end-point noise."""
    for i in numba.prange(vnew.shape[0]):
        for a in range(3):
            if scheme == STRATONOVICH:
                dv = 0.5 * (dt * (again[1, i, a] - terms[1, i, a]) + again[3, i, a] - terms[3, i, a])
                dw = 0.5 * (dt * (again[2, i, a] - terms[2, i, a]) + again[4, i, a] - terms[4, i, a])
            else:
                dv = again[3, i, a] - terms[3, i, a]
                dw = again[4, i, a] - terms[4, i, a]
            vnew[i, a] += inv_mass[i] * dv
            wnew[i, a] += inv_inertia[i] * dw


@numba.njit(parallel=True, cache=True)
def _solvent(vel, omega, inv_mass, inv_inertia, dims, dt, kT, gamma, gamma_rot, key):
    """Exact Ornstein–Uhlenbeck update of v and omega (mobile particles), noise keyed on (key, i)."""
    for i in numba.prange(vel.shape[0]):
        if inv_mass[i] == 0.0:
            continue
        c = math.exp(-gamma * inv_mass[i] * dt)
        spread = math.sqrt(kT * inv_mass[i] * (1.0 - c * c))
        cr = math.exp(-gamma_rot * inv_inertia[i] * dt)
        spread_rot = math.sqrt(kT * inv_inertia[i] * (1.0 - cr * cr))
        z0, z1 = normal_pair_at(key, i, 0, 0)
        z2, z3 = normal_pair_at(key, i, 0, 1)
        vel[i, 0] = c * vel[i, 0] + spread * z0
        vel[i, 1] = c * vel[i, 1] + spread * z1
        omega[i, 2] = cr * omega[i, 2] + spread_rot * z3
        if dims == 3:
            z4, z5 = normal_pair_at(key, i, 0, 2)
            vel[i, 2] = c * vel[i, 2] + spread * z2
            omega[i, 0] = cr * omega[i, 0] + spread_rot * z4
            omega[i, 1] = cr * omega[i, 1] + spread_rot * z5


@numba.njit(parallel=True, cache=True)
def _drift(pos, quat, vel, omega, inv_mass, box, dims, h):
    """x += v h (wrapped into the box), q <- exp(omega h/2) q (mobile particles)."""
    for i in numba.prange(pos.shape[0]):
        if inv_mass[i] == 0.0:
            continue
        for a in range(dims):
            x = pos[i, a] + vel[i, a] * h
            pos[i, a] = x - box[a] * math.floor(x / box[a])
        _rotate(quat[i], omega[i, 0], omega[i, 1], omega[i, 2], h)


@numba.njit(cache=True)
def _moved(pos, reference, box, inv_box, dims):
    """Largest displacement since the last neighbour-list build."""
    largest = 0.0
    for i in range(pos.shape[0]):
        d2 = 0.0
        for a in range(dims):
            d = minimum_image(pos[i, a] - reference[i, a], box[a], inv_box[a])
            d2 += d * d
        largest = max(largest, d2)
    return math.sqrt(largest)


@numba.njit(
    types.UniTuple(_I, 3)(_M, _M, _M, _M, _V, _V, _V, _V, _I, _I, _I, _F, _F, _F, _F, _F, _V, _I, _I, _B, _B,
                          SCALAR_KERNEL, _V, CONTACT_KERNEL, SCALAR_KERNEL, _V, _B, _F, _F),
    cache=True,
)  # fmt: skip
def advance(pos, vel, omega, quat, radius, inv_mass, inv_inertia, box, dims, steps, first_step, dt, kT, gamma, gamma_rot,
            active, bulk, seed, scheme, friction_on, noise_on, pot_force, pot_params, contact, weight, law_params,
            has_weight, skin, overlap_limit):  # fmt: skip
    """Advance the state in place by ``steps`` steps; returns (status, steps done, neighbour builds).

    status: OK, NOT_FINITE (a velocity became inf or NaN) or OVERLAP (r < overlap_limit sigma_ik).
    Forces at the current positions are recomputed on entry, so chunked runs and restarts are
    bit-identical to one long run.
    """
    size = pos.shape[0]
    cutoff = WCA_RANGE * 2.0 * radius.max() + skin
    inv_box = np.zeros(3)
    for a in range(dims):
        inv_box[a] = 1.0 / box[a]
    start, neighbors, reverse = build_neighbors(pos, box, dims, cutoff)
    slots = np.zeros((neighbors.size, PAIR_FIELDS))
    reference = pos.copy()
    builds = 1
    terms, again = np.zeros((TERMS, size, 3)), np.zeros((TERMS, size, 3))
    vnew, wnew = np.empty((size, 3)), np.empty((size, 3))
    for n in range(-1, steps):
        step = first_step + max(n, 0)
        if n >= 0:
            _half_kick(vel, quat, inv_mass, dims, dt, active, bulk, terms[0])
            _drift(pos, quat, vel, omega, inv_mass, box, dims, 0.5 * dt)
            _solvent(vel, omega, inv_mass, inv_inertia, dims, dt, kT, gamma, gamma_rot, stream_key(seed, step, SOLVENT))
            _drift(pos, quat, vel, omega, inv_mass, box, dims, 0.5 * dt)
            if _moved(pos, reference, box, inv_box, dims) > 0.5 * skin:
                start, neighbors, reverse = build_neighbors(pos, box, dims, cutoff)
                slots = np.zeros((neighbors.size, PAIR_FIELDS))
                reference[:] = pos
                builds += 1
        key = stream_key(seed, step, CONTACT)
        closest = pair_slots(pos, vel, omega, radius, inv_mass, inv_inertia, box, inv_box, dims, start, neighbors, pot_force,
                             pot_params, contact, weight, law_params, has_weight, kT, dt, key, friction_on and n >= 0,
                             noise_on, True, slots)  # fmt: skip
        gather(radius, start, neighbors, reverse, slots, terms)
        if n < 0:  # forces at the initial positions for the first half kick
            continue
        if closest < overlap_limit:
            return OVERLAP, n, builds
        _contact_kick(vel, omega, inv_mass, inv_inertia, dims, dt, terms, vnew, wnew)
        if friction_on and noise_on and scheme != ITO:
            pair_slots(pos, vnew, wnew, radius, inv_mass, inv_inertia, box, inv_box, dims, start, neighbors, pot_force, pot_params,
                       contact, weight, law_params, has_weight, kT, dt, key, True, True, False, slots)  # fmt: skip
            gather(radius, start, neighbors, reverse, slots, again)
            _correct(scheme, vnew, wnew, inv_mass, inv_inertia, dt, terms, again)
        if not (np.isfinite(vnew).all() and np.isfinite(wnew).all()):
            return NOT_FINITE, n, builds
        vel[:] = vnew
        omega[:] = wnew
        _half_kick(vel, quat, inv_mass, dims, dt, active, bulk, terms[0])
    return OK, steps, builds
