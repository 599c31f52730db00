"""Compiled Langevin dynamics of frictional spheres (F-35..40) in 2-D and 3-D.

One code path with 3-vectors: in 2-D, z = 0, spins are along z and the contact noise acts along
the single tangent t = z x r_hat (PHYSICS.md, 2-D reduction). One step of length dt:

Splitting B A O A C B (BAOAB with the contact kick C next to the last half kick):
B: v += (dt/2) F/m with F = -dU/dr (WCA by default) + F0 e1 + F_bulk; A: x += v dt/2 and the
orientation turns by omega dt/2; O: the solvent part, exact; C: friction and contact noise.

1. pair pass at (x, v, omega): conservative force, deterministic friction
   F_i = (f/u) u_perp, tau_i = R_i r_hat x F_i (F-5..8), and the contact noise impulse
   sqrt(D) sqrt(2 kT dt) P z (3-D) or sqrt(D) sqrt(2 kT dt) z t (2-D), with z keyed on
   (seed, step, min(i,k), max(i,k)); F_k = -F_i, tau_k = (R_k/R_i) tau_i.
2. contact kick v += dt F_friction/m + impulse/m (same for omega with torques), with the
   contact noise amplitude evaluated as the calculus demands: Euler–Maruyama at the start (Itô),
   stochastic Heun, the average of start and predicted end (Stratonovich), or the predicted end
   point (Hänggi–Klimontovich); the predicted point is the Euler–Maruyama kick, same z.
3. solvent: exact Ornstein–Uhlenbeck update v <- c v + sqrt(kT (1 - c^2)/m) xi, c = exp(-gamma dt/m)
   (and gamma_R, I for omega): no time-step bias of the solvent part.
4. drift: x += v dt/2, orientation q <- exp(omega dt/4) q (lab-frame angular velocity), twice.

Immobile (wall) particles have inverse mass and inertia 0: they never move, and enter the contact
mobility mu_ik = 1/m_i + 1/m_k + R_i^2/I_i + R_k^2/I_k with zero terms.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types

from .neighbors import build_neighbors, minimum_image
from .rng import CONTACT, SOLVENT, normal_pair

# Kernels enter as first-class functions (explicit signatures, emitted so by derive.emit): the
# engine is compiled once for every law and cached on disk.
_F, _I, _B = types.float64, types.int64, types.boolean
_V, _M, _L = types.Array(_F, 1, "C"), types.Array(_F, 2, "C"), types.Array(_I, 1, "C")
SCALAR_KERNEL = types.FunctionType(_F(_F, _V))  # weight(r, params), potential force(r, params)
CONTACT_KERNEL = types.FunctionType(types.UniTuple(_F, 2)(_F, _F, _F, _F, _F, _V))  # (f/u, sqrt(D))

WCA_RANGE = 2.0 ** (1.0 / 6.0)
ITO, STRATONOVICH, HK = 0, 1, 2

# status codes of advance()
OK, NOT_FINITE, OVERLAP = 0, 1, 2


@numba.njit(inline="always", cache=True)
def _cross(a0, a1, a2, b0, b1, b2):
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@numba.njit(
    _F(
        _M,
        _M,
        _M,
        _V,
        _V,
        _V,
        _V,
        _I,
        _L,
        _L,
        SCALAR_KERNEL,
        _V,
        CONTACT_KERNEL,
        SCALAR_KERNEL,
        _V,
        _B,
        _F,
        _F,
        _I,
        _I,
        _B,
        _B,
        _B,
        _M,
        _M,
        _M,
        _M,
        _M,
    ),
    parallel=True,
    cache=True,
)
def pair_pass(
    pos,
    vel,
    omega,
    radius,
    inv_mass,
    inv_inertia,
    box,
    dims,
    start,
    neighbors,
    pot_force,
    pot_params,
    contact,
    weight,
    law_params,
    has_weight,
    kT,
    dt,
    seed,
    step,
    friction_on,
    noise_on,
    conservative,
    out_force,
    out_fric,
    out_tfric,
    out_kick,
    out_tkick,
):
    """Per-particle sums over neighbours (fixed index order); returns the smallest r/sigma_ik."""
    size = pos.shape[0]
    closest = np.empty(size)
    noise_scale = math.sqrt(2.0 * kT * dt)
    for i in numba.prange(size):
        fx = fy = fz = 0.0
        gx = gy = gz = 0.0
        tx = ty = tz = 0.0
        kx = ky = kz = 0.0
        sx = sy = sz = 0.0
        nearest = np.inf
        ri = radius[i]
        for slot in range(start[i], start[i + 1]):
            k = neighbors[slot]
            dx = minimum_image(pos[k, 0] - pos[i, 0], box[0])
            dy = minimum_image(pos[k, 1] - pos[i, 1], box[1])
            dz = minimum_image(pos[k, 2] - pos[i, 2], box[2]) if dims == 3 else 0.0
            r2 = dx * dx + dy * dy + dz * dz
            sigma = ri + radius[k]
            if r2 >= (WCA_RANGE * sigma) ** 2:
                continue
            r = math.sqrt(r2)
            nearest = min(nearest, r / sigma)
            nx, ny, nz = dx / r, dy / r, dz / r
            if conservative:
                magnitude = pot_force(r / sigma, pot_params) / sigma  # -dU/dr, scaled to sigma_ik
                fx -= magnitude * nx
                fy -= magnitude * ny
                fz -= magnitude * nz
            if not friction_on:
                continue
            rk = radius[k]
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
            ffx, ffy, ffz = ratio * ux, ratio * uy, ratio * uz
            gx += ffx
            gy += ffy
            gz += ffz
            qx, qy, qz = _cross(nx, ny, nz, ffx, ffy, ffz)
            tx += ri * qx
            ty += ri * qy
            tz += ri * qz
            if noise_on:
                lo, hi = min(i, k), max(i, k)
                amplitude = root * noise_scale
                if dims == 3:
                    z0, z1 = normal_pair(seed, step, CONTACT, lo, hi, 0)
                    z2 = normal_pair(seed, step, CONTACT, lo, hi, 1)[0]
                    sign = 1.0 if i < k else -1.0
                    zn = z0 * nx + z1 * ny + z2 * nz
                    ex = sign * amplitude * (z0 - zn * nx)
                    ey = sign * amplitude * (z1 - zn * ny)
                    ez = sign * amplitude * (z2 - zn * nz)
                else:
                    z0 = normal_pair(seed, step, CONTACT, lo, hi, 0)[0]
                    ex, ey, ez = -amplitude * z0 * ny, amplitude * z0 * nx, 0.0
                kx += ex
                ky += ey
                kz += ez
                qx, qy, qz = _cross(nx, ny, nz, ex, ey, ez)
                sx += ri * qx
                sy += ri * qy
                sz += ri * qz
        closest[i] = nearest
        if conservative:
            out_force[i, 0], out_force[i, 1], out_force[i, 2] = fx, fy, fz
        out_fric[i, 0], out_fric[i, 1], out_fric[i, 2] = gx, gy, gz
        out_tfric[i, 0], out_tfric[i, 1], out_tfric[i, 2] = tx, ty, tz
        out_kick[i, 0], out_kick[i, 1], out_kick[i, 2] = kx, ky, kz
        out_tkick[i, 0], out_tkick[i, 1], out_tkick[i, 2] = sx, sy, sz
    return closest.min() if size else np.inf


@numba.njit(_F(_F, _V), cache=True)
def no_weight(r, params):
    """w = 1 for laws without a distance weight (friction acts within the potential's range)."""
    return 1.0


@numba.njit(inline="always", cache=True)
def _body_x(q):
    """e1 = R(q) (1, 0, 0) for a unit quaternion q = (s, x, y, z)."""
    s, x, y, z = q[0], q[1], q[2], q[3]
    return 1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + s * z), 2.0 * (x * z - s * y)


@numba.njit(inline="always", cache=True)
def _rotate(q, wx, wy, wz, dt):
    """q <- exp(omega dt/2) q: exact rotation by the lab-frame angle omega dt."""
    angle = math.sqrt(wx * wx + wy * wy + wz * wz) * dt
    if angle == 0.0:
        return
    c, s = math.cos(0.5 * angle), math.sin(0.5 * angle) / (angle / dt)
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
def _contact_kick(vel, omega, inv_mass, inv_inertia, dims, dt, fric, tfric, kick, tkick, vnew, wnew):
    """Euler–Maruyama contact kick (the Itô step and the predictor of the other schemes)."""
    for i in numba.prange(vel.shape[0]):
        for a in range(3):
            vnew[i, a] = vel[i, a] + inv_mass[i] * (dt * fric[i, a] + kick[i, a])
            wnew[i, a] = omega[i, a] + inv_inertia[i] * (dt * tfric[i, a] + tkick[i, a])
        if dims == 2:
            vnew[i, 2] = 0.0
            wnew[i, 0] = wnew[i, 1] = 0.0


@numba.njit(parallel=True, cache=True)
def _correct(scheme, vnew, wnew, inv_mass, inv_inertia, dims, dt, fric, tfric, kick, tkick, fric2, tfric2, kick2, tkick2):
    """Replace the predictor's contact terms: Heun averages start and end, HK takes the end-point noise."""
    for i in numba.prange(vnew.shape[0]):
        for a in range(3):
            if scheme == STRATONOVICH:
                dv = 0.5 * (dt * (fric2[i, a] - fric[i, a]) + kick2[i, a] - kick[i, a])
                dw = 0.5 * (dt * (tfric2[i, a] - tfric[i, a]) + tkick2[i, a] - tkick[i, a])
            else:
                dv = kick2[i, a] - kick[i, a]
                dw = tkick2[i, a] - tkick[i, a]
            vnew[i, a] += inv_mass[i] * dv
            wnew[i, a] += inv_inertia[i] * dw


@numba.njit(parallel=True, cache=True)
def _solvent(vel, omega, inv_mass, inv_inertia, dims, dt, kT, gamma, gamma_rot, seed, step):
    """Exact Ornstein–Uhlenbeck update v <- c v + sqrt(kT (1 - c^2)/m) xi (mobile particles)."""
    for i in numba.prange(vel.shape[0]):
        if inv_mass[i] == 0.0:
            continue
        c = math.exp(-gamma * inv_mass[i] * dt)
        spread = math.sqrt(kT * inv_mass[i] * (1.0 - c * c))
        cr = math.exp(-gamma_rot * inv_inertia[i] * dt)
        spread_rot = math.sqrt(kT * inv_inertia[i] * (1.0 - cr * cr))
        z0, z1 = normal_pair(seed, step, SOLVENT, i, 0, 0)
        z2, z3 = normal_pair(seed, step, SOLVENT, i, 0, 1)
        z4, z5 = normal_pair(seed, step, SOLVENT, i, 0, 2)
        vel[i, 0] = c * vel[i, 0] + spread * z0
        vel[i, 1] = c * vel[i, 1] + spread * z1
        if dims == 3:
            vel[i, 2] = c * vel[i, 2] + spread * z2
            omega[i, 0] = cr * omega[i, 0] + spread_rot * z4
            omega[i, 1] = cr * omega[i, 1] + spread_rot * z5
        omega[i, 2] = cr * omega[i, 2] + spread_rot * z3


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


@numba.njit(
    types.UniTuple(_I, 3)(
        _M,
        _M,
        _M,
        _M,
        _V,
        _V,
        _V,
        _V,
        _I,
        _I,
        _I,
        _F,
        _F,
        _F,
        _F,
        _F,
        _V,
        _I,
        _I,
        _B,
        _B,
        SCALAR_KERNEL,
        _V,
        CONTACT_KERNEL,
        SCALAR_KERNEL,
        _V,
        _B,
        _F,
        _F,
    ),
    cache=True,
)
def advance(
    pos,
    vel,
    omega,
    quat,
    radius,
    inv_mass,
    inv_inertia,
    box,
    dims,
    steps,
    first_step,
    dt,
    kT,
    gamma,
    gamma_rot,
    active,
    bulk,
    seed,
    scheme,
    friction_on,
    noise_on,
    pot_force,
    pot_params,
    contact,
    weight,
    law_params,
    has_weight,
    skin,
    overlap_limit,
):
    """Advance the state in place by ``steps`` steps; returns (status, steps done, neighbour builds).

    status: OK, NOT_FINITE (a velocity became inf or NaN) or OVERLAP (r < overlap_limit sigma_ik).
    Forces at the current positions are recomputed on entry, so chunked runs and restarts are
    bit-identical to one long run.
    """
    size = pos.shape[0]
    cutoff = WCA_RANGE * 2.0 * radius.max() + skin if size else 1.0
    start, neighbors = build_neighbors(pos, box, dims, cutoff)
    reference = pos.copy()
    builds = 1
    force, fric, tfric = np.zeros((size, 3)), np.zeros((size, 3)), np.zeros((size, 3))
    kick, tkick = np.zeros((size, 3)), np.zeros((size, 3))
    fric2, tfric2 = np.zeros((size, 3)), np.zeros((size, 3))
    kick2, tkick2 = np.zeros((size, 3)), np.zeros((size, 3))
    vnew, wnew = np.empty((size, 3)), np.empty((size, 3))
    pair_pass(
        pos,
        vel,
        omega,
        radius,
        inv_mass,
        inv_inertia,
        box,
        dims,
        start,
        neighbors,
        pot_force,
        pot_params,
        contact,
        weight,
        law_params,
        has_weight,
        kT,
        dt,
        seed,
        first_step,
        False,
        False,
        True,
        force,
        fric,
        tfric,
        kick,
        tkick,
    )
    for n in range(steps):
        step = first_step + n
        _half_kick(vel, quat, inv_mass, dims, dt, active, bulk, force)
        _drift(pos, quat, vel, omega, inv_mass, box, dims, 0.5 * dt)
        _solvent(vel, omega, inv_mass, inv_inertia, dims, dt, kT, gamma, gamma_rot, seed, step)
        _drift(pos, quat, vel, omega, inv_mass, box, dims, 0.5 * dt)
        displacement = 0.0
        for i in range(size):
            d2 = 0.0
            for a in range(dims):
                d = minimum_image(pos[i, a] - reference[i, a], box[a])
                d2 += d * d
            displacement = max(displacement, d2)
        if math.sqrt(displacement) > 0.5 * skin:
            start, neighbors = build_neighbors(pos, box, dims, cutoff)
            reference[:] = pos
            builds += 1
        closest = pair_pass(
            pos,
            vel,
            omega,
            radius,
            inv_mass,
            inv_inertia,
            box,
            dims,
            start,
            neighbors,
            pot_force,
            pot_params,
            contact,
            weight,
            law_params,
            has_weight,
            kT,
            dt,
            seed,
            step,
            friction_on,
            noise_on,
            True,
            force,
            fric,
            tfric,
            kick,
            tkick,
        )
        if closest < overlap_limit:
            return OVERLAP, n, builds
        _contact_kick(vel, omega, inv_mass, inv_inertia, dims, dt, fric, tfric, kick, tkick, vnew, wnew)
        if friction_on and noise_on and scheme != ITO:
            pair_pass(
                pos,
                vnew,
                wnew,
                radius,
                inv_mass,
                inv_inertia,
                box,
                dims,
                start,
                neighbors,
                pot_force,
                pot_params,
                contact,
                weight,
                law_params,
                has_weight,
                kT,
                dt,
                seed,
                step,
                True,
                True,
                False,
                force,
                fric2,
                tfric2,
                kick2,
                tkick2,
            )
            _correct(scheme, vnew, wnew, inv_mass, inv_inertia, dims, dt, fric, tfric, kick, tkick, fric2, tfric2, kick2, tkick2)
        if not (np.isfinite(vnew).all() and np.isfinite(wnew).all()):
            return NOT_FINITE, n, builds
        vel[:] = vnew
        omega[:] = wnew
        _half_kick(vel, quat, inv_mass, dims, dt, active, bulk, force)
    return OK, steps, builds
