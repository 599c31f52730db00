"""The run-time check of D: a law's noise kernels against an adaptive quadrature, at the run's parameters.

``fricgen verify`` checks the kernels against mpmath near the parameter defaults
(fricgen.derive.backends.numba_kernels.accuracy). A run fixes its own parameter values, kT and contact
mobilities mu; before it starts, :func:`check_noise` checks the D that the kernels give there, the
noise tables included (docs/trust-model.md):

- speeds: u = 0, u = s 10^(-6 + k/3) below s/30, then 251 equal steps up to U = 8 s (none but U a
  dyadic multiple of sqrt(a), where a table piece ends and is exact), s = sqrt(mu kT) the equilibrium
  spread of each component of the relative tangential speed: P(u > U) = exp(-32) = 1.3e-14 in 3-D (two
  components), erfc(8/sqrt(2)) = 1.2e-15 in 2-D (one);
- contacts: w = w(r) at r = 0.9, 1 and 1.1 (in units of sigma_ik) for a law with a weight, else w = r = 1;
- reference: (F-22) D(u) = (1/a) int_u^oo f(s) exp(-(s^2 - u^2)/(2a)) ds, a = (1 - theta) mu kT, with f
  the law's friction kernel, integrated by scipy.integrate.quad (its error estimate kept) cell by cell
  between the speeds, A_i = I_i + exp(-(u_{i+1}^2 - u_i^2)/(2a)) A_{i+1}, and beyond U over pieces of
  doubling length until the Gaussian factor is below exp(-1500) (a finite f times it is 0 in double
  precision). quad bisects where its error estimate asks (kinks, steps, features down to about 1e-4 s
  wide); a feature narrower than that is missed by any sampling unless the sampling knows where it
  lies: the law's own speed scales are its parameter values, so each p_i, p_i + p_j and |p_i - p_j|
  gets a ladder of breakpoints p (1 +- 4^-k), k = 1 ... 20, that resolves a feature centred there
  down to 1e-12 p wide (:func:`_hints`). HK (nu = 0): D = f/u at u > 0;
- accepted when the reference's error estimate is at most REFERENCE_TOLERANCE and the kernel's D (with
  the parameters alone: the quadrature; with the noise tables appended: the tables) within
  RUN_TOLERANCE of it, relative, at every speed and contact; otherwise KernelError in one line, with
  the parameter values and the error measured.

The result is kept per law (name, file, source hash), calculus, parameter values, mobilities and kT:
a process checks each once.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.integrate import quad

from fricgen.derive.calculus import Calculus

from .errors import KernelError
from .kernels import LawKernels

#: Largest relative error of the kernels' D (quadrature or noise table) that a run accepts.
RUN_TOLERANCE = 1e-6
#: Largest relative error estimate of the reference D: well below RUN_TOLERANCE, so that a pass is a pass.
REFERENCE_TOLERANCE = 1e-9
#: Top of the checked speeds, in units of s = sqrt(mu kT).
TOP = 8.0
#: Equal cells between s/30 and TOP s (prime: no cell end is a dyadic multiple of sqrt(a)).
CELLS = 251
#: Breakpoints on each side of a feature's possible centre (:func:`_hints`): down to 4^-20 = 1e-12 of it.
LADDER = 20
#: Contact distances (in sigma_ik) whose weight w(r) the check takes, for a law with a weight.
DISTANCES = (0.9, 1.0, 1.1)
#: The Gaussian factor's exponent beyond which the integrand is 0 in double precision (f finite).
CUTOFF = 1500.0


@dataclass(frozen=True)
class NoiseAccuracy:
    """What :func:`check_noise` measured: the kernels' largest relative error of D (``error``, and
    where), the reference's largest relative error estimate, the number of values compared and the
    seconds the check took; ``problem``: the one-line refusal, "" when accepted."""

    law: str
    mode: str
    calculus: str
    error: float
    where: str
    reference_error: float
    compared: int
    seconds: float
    problem: str = ""


_CHECKED: dict[tuple, NoiseAccuracy] = {}


def check_noise(kernels: LawKernels, calculus: str, params: np.ndarray, mobilities: Sequence[float], kT: float) -> NoiseAccuracy:
    """The kernels' D of ``calculus`` (noise_amplitude_<calculus>) at the parameter values ``params``
    (with the noise tables appended, as the law module's tabulate_<calculus> returns them, or without),
    for each contact mobility of ``mobilities`` at ``kT``, against the adaptive reference; the report,
    or KernelError (one line: the law, its parameter values, the speed, the error) beyond RUN_TOLERANCE
    or where the reference cannot reach REFERENCE_TOLERANCE."""
    n = len(kernels.parameter_names)
    plain = np.ascontiguousarray(params[:n], dtype=np.float64)
    key = (kernels.name, str(kernels.path), kernels.source_hash, calculus, plain.tobytes(), tuple(map(float, mobilities)), float(kT))
    if key not in _CHECKED:
        _CHECKED[key] = _measure(kernels, calculus, plain, np.ascontiguousarray(params, dtype=np.float64), mobilities, kT)
    report = _CHECKED[key]
    if report.problem:
        raise KernelError(report.problem)
    return report


def _measure(kernels: LawKernels, calculus: str, plain: np.ndarray, params: np.ndarray, mobilities, kT: float) -> NoiseAccuracy:
    start = time.perf_counter()
    amplitude = kernels.noise_amplitude(calculus)
    theta = float(Calculus(calculus).theta)
    versions = [("", plain)] + ([(", noise table", params)] if params.size > plain.size else [])
    worst, where, reference_worst, compared = 0.0, "", 0.0, 0
    for mu in mobilities:
        s = math.sqrt(mu * kT)
        speeds = _speeds(s)
        for w, r in _contacts(kernels, plain):
            reference, estimate = _reference(kernels.friction, w, r, plain, speeds, (1.0 - theta) * mu * kT)
            spot = f"(w = {w:.6g}, r = {r:.6g}, mu = {mu:.6g}, kT = {kT:.6g}"
            bad = np.flatnonzero(~(estimate <= REFERENCE_TOLERANCE))
            if bad.size:
                i = bad[np.argmax(np.nan_to_num(estimate[bad], nan=np.inf))]
                problem = (
                    f"its D cannot be checked to {RUN_TOLERANCE:g}: the adaptive quadrature of (F-22) reaches only"
                    f" {estimate[i]:.2g} at u = {speeds[i]:.6g} {spot})"
                )
                return _report(kernels, calculus, plain, start, math.inf, problem, estimate[i], compared)
            reference_worst = max(reference_worst, float(estimate.max()))
            for how, values in versions:
                for u, exact in zip(speeds, reference):
                    if math.isnan(exact):  # HK at u = 0: D = f/u has no reference value there
                        continue
                    got = amplitude(u, w, r, mu, kT, values)
                    error = abs(got - exact) / exact if exact > 0 else (0.0 if got == 0 else math.inf)
                    compared += 1
                    if not error <= worst:
                        worst, where = error, f"u = {u:.6g} {spot}{how}): kernel {got:.10g}, reference {exact:.10g}"
    problem = ""
    if not worst <= RUN_TOLERANCE:
        problem = f"its D is off by {worst:.2g} at {where}, beyond the run-time tolerance {RUN_TOLERANCE:g}"
    return _report(kernels, calculus, plain, start, worst, problem, reference_worst, compared, where)


def _report(kernels, calculus, plain, start, error, problem, reference_error, compared, where="") -> NoiseAccuracy:
    if problem:
        values = ", ".join(f"{name}={value:.6g}" for name, value in zip(kernels.parameter_names, plain))
        problem = (
            f"law {kernels.name} ({kernels.mode}, {calculus}) at {values}: {problem}; the kernels cannot give D to this accuracy"
            " at these values: choose others (docs/trust-model.md, D at the run's parameters)"
        )
    seconds = time.perf_counter() - start
    return NoiseAccuracy(kernels.name, kernels.mode, calculus, float(error), where, float(reference_error), compared, seconds, problem)


def _speeds(s: float) -> np.ndarray:
    """u = 0, s 10^(-6 + k/3) below s/30, and CELLS equal steps from s/30 to TOP s."""
    low = s * 10.0 ** (-6.0 + np.arange(14) / 3.0)
    return np.concatenate([[0.0], low[low < s / 30], np.linspace(s / 30, TOP * s, CELLS + 1)])


def _contacts(kernels: LawKernels, plain: np.ndarray) -> list[tuple[float, float]]:
    """(w, r) of the contacts checked: w(r) at DISTANCES where the law has a weight (w > 0), else (1, 1)."""
    if not kernels.has_weight:
        return [(1.0, 1.0)]
    return [(w, r) for r in DISTANCES if (w := float(kernels.weight(r, plain))) > 0.0]


def _reference(friction, w: float, r: float, params: np.ndarray, speeds: np.ndarray, a: float) -> tuple[np.ndarray, np.ndarray]:
    """D at ``speeds`` by (F-22) (f/u where a = 0) and the relative error estimate of each value."""
    if a == 0.0:
        inner = speeds[speeds > 0]
        values = np.array([friction(u, w, r, params) / u for u in inner])
        return np.concatenate([[math.nan] * (speeds.size - inner.size), values]), np.zeros(speeds.size)  # no u = 0
    top = speeds[-1]
    ends, length = [top], math.sqrt(a)
    while (ends[-1] - top) * (ends[-1] + top) / (2 * a) < CUTOFF:
        ends.append(ends[-1] + length)
        length *= 2
    hints = _hints(params)
    total, error = _integral(friction, w, r, params, np.array(ends), a, hints)
    values, errors = np.empty(speeds.size), np.empty(speeds.size)
    values[-1], errors[-1] = total, error
    for i in range(speeds.size - 2, -1, -1):
        lo, hi = speeds[i], speeds[i + 1]
        piece, piece_error = _integral(friction, w, r, params, np.array([lo, hi]), a, hints)
        decay = math.exp(-(hi - lo) * (hi + lo) / (2 * a))
        values[i], errors[i] = piece + decay * values[i + 1], piece_error + decay * errors[i + 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        return values / a, np.where(values > 0, errors / values, np.where(errors == 0, 0.0, np.inf))


def _hints(params: np.ndarray) -> np.ndarray:
    """Where f may hold a narrow feature: its parameter values p, p_i + p_j and |p_i - p_j| (> 0), each with a
    ladder p (1 +- 4^-k), k = 1 ... LADDER, of breakpoints closing in on it (widths down to 1e-12 p)."""
    values = [p for p in params if p > 0]
    centres = {*values, *(p + q for p in values for q in values), *(abs(p - q) for p in values for q in values)} - {0.0}
    steps = 4.0 ** -np.arange(1, LADDER + 1)
    return np.unique(np.concatenate([np.concatenate([c * (1 - steps), [c], c * (1 + steps)]) for c in centres] or [np.zeros(0)]))


def _integral(friction, w: float, r: float, params: np.ndarray, ends: np.ndarray, a: float, hints: np.ndarray) -> tuple[float, float]:
    """int_{ends[0]}^{ends[-1]} f(s) exp(-(s^2 - ends[0]^2)/(2a)) ds and its error estimate, piece by piece
    between ``ends``, with the :func:`_hints` inside a piece as breakpoints of its quadrature."""
    x = ends[0]

    def integrand(s):
        weight = math.exp(-(s - x) * (s + x) / (2 * a))
        return 0.0 if weight == 0.0 else friction(s, w, r, params) * weight

    total, error = 0.0, 0.0
    for lo, hi in zip(ends[:-1], ends[1:]):
        inside = hints[(hints > lo) & (hints < hi)]
        value, estimate, *_ = quad(
            integrand, lo, hi, epsabs=0.0, epsrel=1e-12, limit=200 + 2 * inside.size, points=inside if inside.size else None, full_output=1
        )
        total, error = total + value, error + estimate
    return total, error


__all__ = ["REFERENCE_TOLERANCE", "RUN_TOLERANCE", "NoiseAccuracy", "check_noise"]
