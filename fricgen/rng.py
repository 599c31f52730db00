"""Counter-based Gaussian random numbers: a pure function of (seed, step, stream, i, k).

No generator state: the noise of a pair is the same whichever particle computes it, in whatever
neighbour order and on however many threads, and a restarted run continues bit-identically.
Keys are mixed with chained SplitMix64 finalisers (Steele, Lea, Flood 2014); normals come from
the Box–Muller transform of two 53-bit uniforms (two normals per key). The cheaper ``ziggurat_normal``
(one normal per index from one SplitMix64 output, Marsaglia & Tsang's ziggurat) serves engines that
need one normal per particle and step, or per pair (with ``pair_key``); ``uniform`` gives 53-bit uniforms (Metropolis tests).

The physics: docs/physics.md#counter-based-noise.
"""

from __future__ import annotations

import fricgen.compiled  # noqa: F401  (first: sets Numba up before anything imports it)

# isort: split

import math

import numba
import numpy as np

_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
_S30, _S27, _S31, _S11 = np.uint64(30), np.uint64(27), np.uint64(31), np.uint64(11)
_TWO_53 = 1.0 / 9007199254740992.0

#: The one registry of streams: independent noise sources keyed on the same (seed, step, i, k).
#: Every engine takes its stream ids from here. Ids are distinct within an engine (the Langevin
#: engine's 1-4, 6, 7, the rods' 4-5 never meet in one run); their values are fixed, since a seed must
#: keep reproducing earlier runs bit for bit.
SOLVENT = 1  # Langevin: Ornstein–Uhlenbeck solvent kicks, per particle
CONTACT = 2  # Langevin: frictional contact noise, per pair
INITIAL = 3  # initial velocities, spins and orientations; rods: the free-rod start (fricgen.rods.mc.free_rods)
WALL_ROUGHNESS = 4  # Langevin: Gaussian heights of rough slab walls
BCD = 4  # rods: Brownian trial forces, per replica and rod
MONTE_CARLO = 5  # rods: Metropolis proposals and acceptances of the equilibrium start
ROLLING = 6  # Langevin: rolling-friction noise, per pair (docs/physics-modes.md)
SPINNING = 7  # Langevin: spinning-friction noise, per pair


@numba.njit(inline="always", cache=True)
def _mix(z):
    z = z + _GOLDEN
    z = (z ^ (z >> _S30)) * _M1
    z = (z ^ (z >> _S27)) * _M2
    return z ^ (z >> _S31)


@numba.njit(inline="always", cache=True)
def stream_key(seed, step, stream):
    """The key of one noise stream at one step (computed once per step)."""
    z = _mix(np.uint64(seed))
    z = _mix(z ^ np.uint64(step))
    return _mix(z ^ np.uint64(stream))


@numba.njit(inline="always", cache=True)
def pair_key(base, i, k):
    """The key of pair (i, k) in stream key ``base``: its draws are ziggurat_normal(key, j) and
    uniform(key, j), each j once."""
    return _mix(_mix(base ^ np.uint64(i)) ^ np.uint64(k))


@numba.njit(inline="always", cache=True)
def normal_pair_at(base, i, k, counter):
    """Two independent standard normals (Box–Muller) for (stream key, i, k) and a small counter (0, 1, 2, ...)."""
    a = _mix(pair_key(base, i, k) ^ np.uint64(counter))
    b = _mix(a)
    u1 = (float(a >> _S11) + 0.5) * _TWO_53  # in (0, 1): log is finite
    u2 = float(b >> _S11) * _TWO_53
    radius = math.sqrt(-2.0 * math.log(u1))
    return radius * math.cos(2.0 * math.pi * u2), radius * math.sin(2.0 * math.pi * u2)


@numba.njit(inline="always", cache=True)
def normal_pair(seed, step, stream, i, k, counter):
    """Two independent standard normals keyed on (seed, step, stream, i, k) and a counter."""
    return normal_pair_at(stream_key(seed, step, stream), i, k, counter)


@numba.njit(cache=True)
def normals(seed, step, stream, count):
    """``count`` normals of particle index i = 0..count-1, one each (for tests and initial states)."""
    out = np.empty(count)
    for i in range(count):
        out[i] = normal_pair(seed, step, stream, i, 0, 0)[0]
    return out


@numba.njit(inline="always", cache=True)
def _word(key, i):
    """Output i of the SplitMix64 sequence that starts from state ``key``: 64 random bits for (key, i)."""
    return _mix(np.uint64(key) + np.uint64(i) * _GOLDEN)


@numba.njit(inline="always", cache=True)
def uniform(key, i):
    """A uniform number in [0, 1) for (key, i), 53 bits."""
    return float(_word(key, i) >> _S11) * _TWO_53


@numba.njit(inline="always", cache=True)
def fold_key(key, index):
    """The key of sub-stream ``index`` (e.g. a replica) of a stream key."""
    return _mix(key ^ np.uint64(index))


_ZIG_R = 3.6541528853610088


def _ziggurat_tables(layers=256, r=_ZIG_R):
    """Marsaglia & Tsang (2000): layers of equal area v under f(x) = exp(-x^2/2), x >= 0.

    Edges x_1 = r > x_2 > ... > x_255 > x_256 = 0 with x_{i+1} = f^-1(f(x_i) + v / x_i); layer i >= 1
    is [0, x_i] x [f(x_i), f(x_{i+1})], layer 0 the base [0, r] x [0, f(r)] plus the tail x > r, of
    area v = r f(r) + sqrt(pi/2) erfc(r / sqrt 2), drawn as a box of width x_0 = v / f(r). r closes
    the recursion, f(x_255) + v / x_255 = 1, to 4e-15. Returns (w, k, f): x = u w_i for a 53-bit
    integer u, accepted at once when u < k_i (x < x_{i+1}), and f_i = f(x_i).
    """
    v = r * math.exp(-0.5 * r * r) + math.sqrt(math.pi / 2) * math.erfc(r / math.sqrt(2))
    edges = np.zeros(layers + 1)
    edges[0], edges[1] = v / math.exp(-0.5 * r * r), r
    for i in range(1, layers - 1):
        edges[i + 1] = math.sqrt(-2.0 * math.log(math.exp(-0.5 * edges[i] ** 2) + v / edges[i]))
    scale = 2.0**53
    k = np.array([math.floor(scale * edges[i + 1] / edges[i]) for i in range(layers)], dtype=np.uint64)
    f = np.array([math.exp(-0.5 * x * x) for x in edges])  # libm, as the edges: numpy's SIMD exp differs by CPU in the last bit
    return edges[:layers] / scale, k, f


_ZIG_W, _ZIG_K, _ZIG_F = _ziggurat_tables()
#: ((w, k, f), r): the tables and the tail start of ziggurat_normal, for its ports (the LAMMPS plugin's C++).
ZIGGURAT = ((_ZIG_W, _ZIG_K, _ZIG_F), _ZIG_R)
_LAYER, _SIGN = np.uint64(255), np.uint64(256)


@numba.njit(inline="always", cache=True)
def _next(state):
    """The next SplitMix64 output after ``state`` and the advanced state."""
    state = state + _GOLDEN
    return _mix(state), state


@numba.njit(cache=True)
def _ziggurat_slow(z):
    """The ziggurat's rare branches for the 64-bit word z; further words continue SplitMix64 from z."""
    state = z
    while True:
        layer, u = z & _LAYER, z >> _S11
        x = float(u) * _ZIG_W[layer]
        if layer == 0:  # tail beyond r: x = r + e1 / r with 2 e2 > (e1 / r)^2 (Marsaglia 1964)
            if u >= _ZIG_K[0]:
                while True:
                    a, state = _next(state)
                    b, state = _next(state)
                    x = -math.log((float(a >> _S11) + 1.0) * _TWO_53) / _ZIG_R
                    if -2.0 * math.log((float(b >> _S11) + 1.0) * _TWO_53) > x * x:
                        break
                x += _ZIG_R
        elif u >= _ZIG_K[layer]:  # the wedge: accept when f_i + a (f_{i+1} - f_i) < f(x), a uniform
            a, state = _next(state)
            if _ZIG_F[layer] + float(a >> _S11) * _TWO_53 * (_ZIG_F[layer + 1] - _ZIG_F[layer]) >= math.exp(-0.5 * x * x):
                z, state = _next(state)
                continue
        return -x if z & _SIGN else x


@numba.njit(inline="always", cache=True)
def ziggurat_normal(key, i):
    """A standard normal for (key, i), exact (ziggurat, 256 layers): one SplitMix64 output
    z = _word(key, i) gives the layer (bits 0-7), the sign (bit 8) and u (bits 11-63);
    x = u w_layer is returned when u < k_layer (99 %), otherwise ``_ziggurat_slow`` decides."""
    z = _word(key, i)
    layer, u = z & _LAYER, z >> _S11
    if u < _ZIG_K[layer]:
        x = float(u) * _ZIG_W[layer]
        return -x if z & _SIGN else x
    return _ziggurat_slow(z)
