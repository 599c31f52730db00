"""Counter-based Gaussian random numbers: a pure function of (seed, step, stream, i, k).

No generator state: the noise of a pair is the same whichever particle computes it, in whatever
neighbour order and on however many threads, and a restarted run continues bit-identically.
Keys are mixed with chained SplitMix64 finalisers (Steele, Lea, Flood 2014); normals come from
the Box–Muller transform of two 53-bit uniforms (two normals per key).
"""

from __future__ import annotations

import math

import numba
import numpy as np

_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
_S30, _S27, _S31, _S11 = np.uint64(30), np.uint64(27), np.uint64(31), np.uint64(11)
_TWO_53 = 1.0 / 9007199254740992.0

#: Streams: independent noise sources keyed on the same (step, i, k).
SOLVENT, CONTACT, INITIAL = 1, 2, 3


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
def normal_pair_at(base, i, k, counter):
    """Two independent standard normals for (stream key, i, k) and a small counter (0, 1, 2, ...)."""
    z = _mix(_mix(base ^ np.uint64(i)) ^ np.uint64(k)) ^ np.uint64(counter)
    a = _mix(z)
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
