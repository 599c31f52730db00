"""The pairwise contact step: friction and its noise integrated pair by pair, Metropolis-adjusted.

Friction and the frictional noise of a pair (i, k) act only on its contact mode, the relative
tangential velocity u_perp (1 component in 2-D, 2 in 3-D). An impulse J on i (-J on k, torques R_i
n x J and R_k n x J) changes u_perp by -mu J and no velocity component orthogonal to that mode in
the mass metric, and at kT the mode is Gaussian with variance mu kT per component, independent of
the rest. So the pairs in contact are updated one after another (Shardlow's splitting), each by a
Metropolis-Hastings step of its mode with that Gaussian as target: the step leaves the
Maxwell-Boltzmann distribution invariant exactly, at any dt (docs/physics.md#the-pairwise-contact-step).

The proposal integrates the mode's SDE, du = a dt + mu sqrt(2 kT D) dW with the Itô-equivalent drift
a = [-mu f + theta mu^2 kT D'] u_hat of the scheme's calculus (theta = 0, 1/2, 1); D' comes from the
ODE of the calculus, (u D - f) / (nu kT) with nu = (1 - theta) mu, or (u f' - f) / u^2 for HK (D = f/u).
A Gaussian (Euler–Maruyama) proposal would be rejected at a rate ~ dt^0.5 even for the right D: it
misses the skewness that a noise amplitude varying with u gives the true step. So the mode, written
as a complex number x = u_perp . (e1 + i e2) (real in 2-D), moves by the map y = x + (e^(g W) - 1)/g,
g the conjugate of grad ln sqrt(D(|x|)), which makes the noise additive to first order (a local
Lamperti transform, conformal in the 2-component mode), with W Gaussian: mean a (1 - e^(-lambda dt))
/ lambda (less g s2 / 2, the map's own mean shift, where the mode has one component) and variance
s2 = mu kT (1 - e^(-2 lambda dt)) per component, lambda = mu D (the Ornstein–Uhlenbeck step of the
linear law, exact there, and stable for stiff contacts). For the right D the rejection rate then falls like dt^1.5 (dt^1 where f or D has a
kink), for a wrong D like dt^0.5. Without contact noise there is no target to adjust to: the mode
relaxes deterministically, u_perp <- e^(-mu (f/u) dt) u_perp (exact for the linear law, never
reversing the sliding).

Pairs of one colour (greedy edge colouring of the pairs in contact, taken in (i, k) order) share no
particle and run in parallel; the colours run one after another. The noise of a pair is keyed on
(seed, step, CONTACT, i, k) (rng.pair_key; ziggurat normals): results are bit-identical for any thread count, neighbour-list skin or
chunking.

The rolling and spinning modes (docs/physics-modes.md) take the same step (contact_step_modes): x is
v_roll . (e1 + i e2) (3-D), R_eff (w_iz - w_kz) (2-D) or v_spin (one component), mu the mode's mobility
R_eff^2 (1/I_i + 1/I_k), the impulse acts along C_m^T on the spins only, and the noise comes from the
ROLLING and SPINNING streams. A pair's modes are updated one after the other, each from the velocities
the previous one left.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from fricgen.derive.calculus import Calculus

from ..rng import pair_key, uniform, ziggurat_normal
from .neighbors import offsets, separation, sort_by_key
from .pairs import cross

#: theta of each scheme (Calculus.index): where the calculus evaluates D within a step.
THETA = np.array([float(c.theta) for c in Calculus])
#: Per pair in contact: unit normal n (from i to k), distance r, weight w, contact mobility mu.
GEOMETRY = 6
_ONE, _WORD = np.uint64(1), 64


@numba.njit(parallel=True, cache=True)
def find_contacts(pos, bodies, dyn, couplings, weight, lists, touching):
    """The pairs i < k that ``touching`` marks (within WCA reach, not both immobile; set by
    fricgen.langevin.forces at these positions), in (i, k) order: (pairs (M, 2), geometry (M, GEOMETRY))."""
    radius, inv_mass, inv_inertia = bodies
    start, neighbors = lists[0], lists[1]
    box, inv_box, dims, size = dyn.box, dyn.inv_box, dyn.dims, pos.shape[0]
    law = couplings.law  # bound here: taken from the tuple in the loop, each weight call would cost two atomic reference counts
    counts = np.zeros(size, dtype=np.int64)
    for i in numba.prange(size):
        for slot in range(start[i], start[i + 1]):
            counts[i] += touching[slot]
    first = offsets(counts)
    pairs, geometry = np.empty((first[size], 2), dtype=np.int64), np.empty((first[size], GEOMETRY))
    for i in numba.prange(size):
        p = first[i]
        for slot in range(start[i], start[i + 1]):
            if not touching[slot]:
                continue
            k = neighbors[slot]
            dx, dy, dz = separation(pos, i, k, box, inv_box, dims)
            r = math.sqrt(dx * dx + dy * dy + dz * dz)
            sigma = radius[i] + radius[k]
            geometry[p, 0], geometry[p, 1], geometry[p, 2], geometry[p, 3] = dx / r, dy / r, dz / r, r
            geometry[p, 4] = weight(r / sigma, law) / sigma if couplings.has_weight else 1.0
            geometry[p, 5] = inv_mass[i] + inv_mass[k] + radius[i] ** 2 * inv_inertia[i] + radius[k] ** 2 * inv_inertia[k]
            pairs[p, 0], pairs[p, 1] = i, k
            p += 1
    return pairs, geometry


@numba.njit(cache=True)
def colour_classes(pairs, size):
    """Greedy edge colouring in pair order: (order, first), the pairs of colour c being
    order[first[c]:first[c + 1]], in pair order; no two pairs of a colour share a particle."""
    degree = np.zeros(size, dtype=np.int64)
    for p in range(pairs.shape[0]):
        degree[pairs[p, 0]] += 1
        degree[pairs[p, 1]] += 1
    words = (2 * degree.max()) // _WORD + 1 if size else 1  # greedy needs at most 2 max(degree) - 1 colours
    used = np.zeros((size, words), dtype=np.uint64)
    colour = np.empty(pairs.shape[0], dtype=np.int64)
    counts = np.zeros(words * _WORD, dtype=np.int64)
    for p in range(pairs.shape[0]):
        i, k = pairs[p, 0], pairs[p, 1]
        word = 0
        while ~(used[i, word] | used[k, word]) == 0:
            word += 1
        free, bit = ~(used[i, word] | used[k, word]), 0
        while ((free >> np.uint64(bit)) & _ONE) == 0:
            bit += 1
        used[i, word] |= _ONE << np.uint64(bit)
        used[k, word] |= _ONE << np.uint64(bit)
        colour[p] = word * _WORD + bit
        counts[colour[p]] += 1
    first = offsets(counts[: colour.max() + 1 if pairs.shape[0] else 0])
    return sort_by_key(colour, first), first


@numba.njit(inline="always", cache=True)
def _expm1(z, comps):
    """e^z - 1 of a complex z without cancellation (z real for a one-component mode)."""
    if comps == 1:
        return complex(math.expm1(z.real), 0.0)
    grow, half = math.expm1(z.real), math.sin(0.5 * z.imag)
    return complex(grow * math.cos(z.imag) - 2.0 * half * half, (grow + 1.0) * math.sin(z.imag))


@numba.njit(inline="always", cache=True)
def _log1p(z, comps):
    """The principal log(1 + z) of a complex z without cancellation (z real and > -1 for a one-component mode)."""
    if comps == 1:
        return complex(math.log1p(z.real), 0.0)
    return complex(0.5 * math.log1p(z.real * (2.0 + z.real) + z.imag * z.imag), math.atan2(z.imag, 1.0 + z.real))


@numba.njit(inline="always", cache=True)
def _inverse(z):
    """1 / z of a complex z != 0."""
    scale = 1.0 / (z.real * z.real + z.imag * z.imag)
    return complex(z.real * scale, -z.imag * scale)


@numba.njit(inline="always", cache=True)
def mode_step(x, w, r, mu, dyn, params, law, comps):
    """The proposal from the mode x = v_m . (e1 + i e2) (module docstring; ``comps`` = 1 or 2 components,
    x real for one): returns (f/u, m, s2, g) with y = x + (e^(g W) - 1) / g, W = m + sqrt(s2) (xi1 + i xi2),
    g the conjugate of grad ln sqrt(D)."""
    contact, slope, theta, kT, dt = law[0], law[1], THETA[dyn.scheme], dyn.kT, dyn.dt
    u = abs(x.real) if comps == 1 else math.sqrt(x.real * x.real + x.imag * x.imag)
    ratio, amplitude = contact(u, w, r, mu, kT, params)
    if theta == 1.0:  # D'/u with D = f/u
        slope_over_u = (slope(u, w, r, params) - ratio) / (u * u) if u > 0.0 else 0.0
    else:
        slope_over_u = (amplitude - ratio) / ((1.0 - theta) * mu * kT)
    rate = mu * amplitude
    decay = math.expm1(-rate * dt)  # e^(-lambda dt) - 1
    span = -decay / rate if rate > 0.0 else dt  # (1 - e^(-lambda dt)) / lambda
    s2 = -mu * kT * decay * (2.0 + decay)  # mu kT (1 - e^(-2 lambda dt))
    g = (0.5 * slope_over_u / amplitude if amplitude > 0.0 else 0.0) * x.conjugate()
    m = (-mu * ratio + theta * mu * mu * kT * slope_over_u) * x * span
    if comps == 1:  # one component: the map's mean shift g s2 / 2
        m -= 0.5 * g * s2
    return ratio, m, s2, g


@numba.njit(inline="always", cache=True)
def _log_proposal(xi2, g_w, comps):
    """log q(y|x) + comps log(sqrt(s2)) + const for |xi|^2 of the standard normal xi and g W of the move."""
    return -0.5 * xi2 - comps * g_w.real


@numba.njit(inline="always", cache=True)
def _tangents(nx, ny, nz, dims):
    """Orthonormal tangents (e1, e2) of the contact plane; in 2-D e1 = z x n and e2 = 0."""
    if dims == 2:
        return (-ny, nx, 0.0), (0.0, 0.0, 0.0)
    ax, ay = (1.0, 0.0) if abs(nx) < 0.9 else (0.0, 1.0)
    along = ax * nx + ay * ny
    tx, ty, tz = ax - along * nx, ay - along * ny, -along * nz
    norm = math.sqrt(tx * tx + ty * ty + tz * tz)
    tx, ty, tz = tx / norm, ty / norm, tz / norm
    return (tx, ty, tz), cross(nx, ny, nz, tx, ty, tz)


@numba.njit(inline="always", cache=True)
def _propose(x, w, r, mu, dyn, params, law, key, comps):
    """(y, 1 - min(1, alpha)) of the Metropolis–Hastings move of a mode of ``comps`` components from x,
    drawn with the pair's key (rng.pair_key: draws 0 and 1 the normals, 2 the uniform); y = x if the
    move leaves the map's principal strip (a proposal to stay) or D = 0."""
    kT = dyn.kT
    _, m, s2, g = mode_step(x, w, r, mu, dyn, params, law, comps)
    if not s2 > 0.0:
        return x, 0.0
    xi = complex(ziggurat_normal(key, 0), ziggurat_normal(key, 1) if comps == 2 else 0.0)
    move = m + math.sqrt(s2) * xi
    g_w = g * move
    if abs(g_w.imag) >= math.pi:
        return x, 1.0
    y = x + (_expm1(g_w, comps) * _inverse(g) if g != 0.0 else move)
    _, m_back, s2_back, g_back = mode_step(y, w, r, mu, dyn, params, law, comps)
    z = g_back * (x - y)
    if not (s2_back > 0.0 and (comps == 2 or 1.0 + z.real > 0.0)):  # one component: x has no preimage from y
        return x, 1.0
    back = _log1p(z, comps) * _inverse(g_back) if g_back != 0.0 else x - y
    log_alpha = (x.real * x.real + x.imag * x.imag - y.real * y.real - y.imag * y.imag) / (2.0 * mu * kT)
    shift = back - m_back
    xi2_back = (shift.real * shift.real + shift.imag * shift.imag) / s2_back
    log_alpha += _log_proposal(xi2_back, g_back * back, comps) - _log_proposal(xi.real * xi.real + xi.imag * xi.imag, g_w, comps)
    log_alpha += 0.5 * comps * math.log(s2 / s2_back)
    if log_alpha >= 0.0:
        return y, 0.0
    alpha = math.exp(log_alpha)
    if not alpha == alpha:  # NaN
        return x, 1.0
    return (y if uniform(key, 2) < alpha else x), 1.0 - alpha


@numba.njit(inline="always", cache=True)
def contact_mode(vel, omega, i, k, ri, rk, nx, ny, nz, dims):
    """(x, e1x, e1y, e1z, e2x, e2y, e2z): the contact mode x = u_perp . (e1 + i e2) of pair (i, k) with
    radii (ri, rk) and unit normal n, and the tangents; u_perp = P (v_k - v_i) - (R_i w_i + R_k w_k) x n
    (F-4), P drops out. Flat: Numba's array analysis fails on nested tuples that a function inlined
    into a parallel loop returns."""
    wx, wy, wz = ri * omega[i, 0] + rk * omega[k, 0], ri * omega[i, 1] + rk * omega[k, 1], ri * omega[i, 2] + rk * omega[k, 2]
    cx, cy, cz = cross(wx, wy, wz, nx, ny, nz)
    ux, uy, uz = vel[k, 0] - vel[i, 0] - cx, vel[k, 1] - vel[i, 1] - cy, vel[k, 2] - vel[i, 2] - cz
    (ax, ay, az), (bx, by, bz) = _tangents(nx, ny, nz, dims)
    return complex(ux * ax + uy * ay + uz * az, ux * bx + uy * by + uz * bz), ax, ay, az, bx, by, bz


@numba.njit(inline="always", cache=True)
def update_pair(vel, omega, bodies, dyn, params, law, key, pairs, geometry, p):
    """Pair p's step (module docstring) on the velocities ``vel`` and spins ``omega`` in place; returns
    (the proposal's rejection probability 1 - min(1, alpha), rejected). ``vel`` and ``omega`` come
    as arrays, not in their record, and the radii, inverse masses and inertias are indexed in ``bodies``
    where they are used: an array bound to a name within the pair loop and used after a kernel call
    costs two atomic reference-count operations per pair."""
    i, k = pairs[p, 0], pairs[p, 1]
    nx, ny, nz, r, w, mu = geometry[p, 0], geometry[p, 1], geometry[p, 2], geometry[p, 3], geometry[p, 4], geometry[p, 5]
    ri, rk = bodies.radius[i], bodies.radius[k]
    x, ax, ay, az, bx, by, bz = contact_mode(vel, omega, i, k, ri, rk, nx, ny, nz, dyn.dims)
    rejection, rejected = 0.0, False
    if dyn.noise:
        y, rejection = _propose(x, w, r, mu, dyn, params, law, pair_key(key, i, k), dyn.dims - 1)
        rejected = y == x and rejection > 0.0
    else:
        y = x * math.exp(-mu * mode_step(x, w, r, mu, dyn, params, law, dyn.dims - 1)[0] * dyn.dt)
    if y == x:
        return rejection, rejected
    jp, jq = (x.real - y.real) / mu, (x.imag - y.imag) / mu  # impulse on i: u_perp -> u_perp - mu J
    jx, jy, jz = jp * ax + jq * bx, jp * ay + jq * by, jp * az + jq * bz
    tx, ty, tz = cross(nx, ny, nz, jx, jy, jz)
    for particle, sign, arm in ((i, 1.0, ri), (k, -1.0, rk)):
        scale, turn = sign * bodies.inv_mass[particle], arm * bodies.inv_inertia[particle]
        vel[particle, 0] += scale * jx
        vel[particle, 1] += scale * jy
        vel[particle, 2] += scale * jz
        omega[particle, 0] += turn * tx
        omega[particle, 1] += turn * ty
        omega[particle, 2] += turn * tz
    return rejection, rejected


@numba.njit(parallel=True, cache=True)
def _sweep(motion, bodies, dyn, params, law, key, pairs, geometry, classes):
    """update_pair for every pair, colour after colour, the pairs of a colour in parallel; returns each
    pair's (rejection probability, rejected)."""
    order, first = classes
    vel, omega = motion.velocity, motion.omega
    rejection, rejected = np.zeros(pairs.shape[0]), np.zeros(pairs.shape[0], dtype=np.bool_)
    for colour in range(first.size - 1):
        for j in numba.prange(first[colour], first[colour + 1]):
            p = order[j]
            rejection[p], rejected[p] = update_pair(vel, omega, bodies, dyn, params, law, key, pairs, geometry, p)
    return rejection, rejected


#: The engine's ids of the rolling and spinning modes (docs/physics-modes.md).
ROLL, SPIN = 1, 2


@numba.njit(inline="always", cache=True)
def rolling_mode(omega, i, k, reff, nx, ny, nz, dims, mode):
    """(x, e1x, e1y, e1z, e2x, e2y, e2z, components) of the rolling (``mode`` ROLL) or spinning (SPIN) mode
    of pair (i, k): v_roll = R_eff (w_i - w_k) x n as x = v_roll . (e1 + i e2) (3-D), R_eff (w_iz - w_kz)
    (2-D, one component), v_spin = R_eff (w_i - w_k) . n (one component; e1 = n)."""
    dx, dy, dz = omega[i, 0] - omega[k, 0], omega[i, 1] - omega[k, 1], omega[i, 2] - omega[k, 2]
    if mode == SPIN:
        return complex(reff * (dx * nx + dy * ny + dz * nz), 0.0), nx, ny, nz, 0.0, 0.0, 0.0, 1
    if dims == 2:
        return complex(reff * dz, 0.0), 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1
    cx, cy, cz = cross(dx, dy, dz, nx, ny, nz)
    (ax, ay, az), (bx, by, bz) = _tangents(nx, ny, nz, dims)
    return complex(reff * (cx * ax + cy * ay + cz * az), reff * (cx * bx + cy * by + cz * bz)), ax, ay, az, bx, by, bz, 2


@numba.njit(inline="always", cache=True)
def update_rolling(omega, bodies, dyn, params, law, key, pairs, geometry, p, mode):
    """Pair p's step of its rolling (``mode`` ROLL) or spinning (SPIN) mode, the law's kernels, weight and noise flags
    ``law`` = (contact, slope, weight, has_weight, noise) with parameters ``params``: the Metropolis-adjusted move of x (as for sliding)
    with the mode's mobility mu_m = R_eff^2 (1/I_i + 1/I_k), then the impulse J = (y - x) / mu_m along
    C_m^T: omega_i += R_eff/I_i n x J, omega_k -= R_eff/I_k n x J (rolling; R_eff J along z in 2-D),
    omega_i += R_eff/I_i J n, omega_k -= R_eff/I_k J n (spinning). Only spins change. Returns (the
    rejection probability, rejected)."""
    i, k = pairs[p, 0], pairs[p, 1]
    nx, ny, nz, r = geometry[p, 0], geometry[p, 1], geometry[p, 2], geometry[p, 3]
    ri, rk = bodies.radius[i], bodies.radius[k]
    reff = ri * rk / (ri + rk)
    mu = reff * reff * (bodies.inv_inertia[i] + bodies.inv_inertia[k])
    w = law[2](r / (ri + rk), params) / (ri + rk) if law[3] else 1.0
    x, ax, ay, az, bx, by, bz, comps = rolling_mode(omega, i, k, reff, nx, ny, nz, dyn.dims, mode)
    rejection, rejected = 0.0, False
    if law[4]:
        y, rejection = _propose(x, w, r, mu, dyn, params, law, pair_key(key, i, k), comps)
        rejected = y == x and rejection > 0.0
    else:
        y = x * math.exp(-mu * mode_step(x, w, r, mu, dyn, params, law, comps)[0] * dyn.dt)
    if y == x:
        return rejection, rejected
    jp, jq = (y.real - x.real) / mu, (y.imag - x.imag) / mu
    jx, jy, jz = jp * ax + jq * bx, jp * ay + jq * by, jp * az + jq * bz  # J in the lab frame (along e1 = n or z for one component)
    if mode == ROLL and dyn.dims == 3:
        jx, jy, jz = cross(nx, ny, nz, jx, jy, jz)
    for particle, sign in ((i, reff), (k, -reff)):
        turn = sign * bodies.inv_inertia[particle]
        omega[particle, 0] += turn * jx
        omega[particle, 1] += turn * jy
        omega[particle, 2] += turn * jz
    return rejection, rejected


@numba.njit(parallel=True, cache=True)
def _sweep_modes(motion, bodies, dyn, couplings, law, modes, keys, pairs, geometry, classes):
    """The modes of every pair, colour after colour, the pairs of a colour in parallel: sliding (where its law
    acts), then rolling, then spinning, each from the velocities the previous one left (the modes couple,
    docs/physics-modes.md); returns (pair rejection-probability sums, rejections)."""
    order, first = classes
    vel, omega = motion.velocity, motion.omega
    rejection, rejected = np.zeros(pairs.shape[0]), np.zeros(pairs.shape[0], dtype=np.int64)
    rolling = (modes[0], modes[1], modes[2], couplings.rolling_weight, dyn.noise and couplings.rolling_noise)
    spinning = (modes[3], modes[4], modes[5], couplings.spinning_weight, dyn.noise and couplings.spinning_noise)
    roll_params, spin_params = couplings.rolling_law, couplings.spinning_law
    for colour in range(first.size - 1):
        for j in numba.prange(first[colour], first[colour + 1]):
            p = order[j]
            total, count = 0.0, 0
            if couplings.sliding:
                a, b = update_pair(vel, omega, bodies, dyn, couplings.law, law, keys[0], pairs, geometry, p)
                total, count = total + a, count + b
            if couplings.rolling:
                a, b = update_rolling(omega, bodies, dyn, roll_params, rolling, keys[1], pairs, geometry, p, ROLL)
                total, count = total + a, count + b
            if couplings.spinning:
                a, b = update_rolling(omega, bodies, dyn, spin_params, spinning, keys[2], pairs, geometry, p, SPIN)
                total, count = total + a, count + b
            rejection[p], rejected[p] = total, count
    return rejection, rejected


@numba.njit(cache=True)
def contact_step_modes(motion, bodies, dyn, couplings, law, modes, lists, touching, keys):
    """The pairwise step of every mode of all pairs in contact: ``law`` = (contact, slope, weight) of the
    sliding law, ``modes`` those of the rolling and spinning laws (records.MODE_KERNELS), ``keys`` the
    step's keys of the CONTACT, ROLLING and SPINNING streams. Returns (proposals, rejections, sum of
    rejection probabilities) over the modes."""
    pairs, geometry = find_contacts(motion.position, bodies, dyn, couplings, law[2], lists, touching)
    classes = colour_classes(pairs, motion.position.shape[0])
    rejection, rejected = _sweep_modes(motion, bodies, dyn, couplings, law, modes, keys, pairs, geometry, classes)
    total, count = 0.0, 0
    for p in range(pairs.shape[0]):  # in pair order: the same sum on any number of threads
        total += rejection[p]
        count += rejected[p]
    rolling, spinning = couplings.rolling and couplings.rolling_noise, couplings.spinning and couplings.spinning_noise
    noisy = int(couplings.sliding) + int(rolling) + int(spinning)  # the modes proposed with their noise
    return pairs.shape[0] * noisy if dyn.noise else 0, count, total


@numba.njit(cache=True)
def contact_step(motion, bodies, dyn, couplings, law, lists, touching, key):
    """The pairwise step of all pairs in contact (``touching``, see find_contacts); ``law`` = (contact,
    slope, weight) kernels, ``key`` the step's CONTACT stream key. Returns (proposals, rejections, sum
    of rejection probabilities)."""
    pairs, geometry = find_contacts(motion.position, bodies, dyn, couplings, law[2], lists, touching)
    classes = colour_classes(pairs, motion.position.shape[0])
    rejection, rejected = _sweep(motion, bodies, dyn, couplings.law, law, key, pairs, geometry, classes)
    total, count = 0.0, 0
    for p in range(pairs.shape[0]):  # in pair order: the same sum on any number of threads
        total += rejection[p]
        count += rejected[p]
    return pairs.shape[0] if dyn.noise else 0, count, total
