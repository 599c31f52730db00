"""``fricgen noise``: D(u) and f(u) of a catalogue law through its generated kernels.

:class:`NoiseQuery` is the command's input, each number checked once (keys are the flags). The
result is refused (ConfigError, exit status 2) when a value the kernels return is not finite, for
inputs that overflow double precision (``--param gamma_f=1e308``), so JSON output stays JSON, and
when it underflows (a subnormal f or D, or D = 0 where f != 0). ``--mu`` and ``--kT`` must lie within
fricgen.schema.SCALES (1e-6 to 1e6; beyond, kernels with noise tables lose accuracy or, at subnormal
values, never end), parameters are 0 or at least :data:`SMALLEST_PARAMETER` in magnitude.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field

from ...accuracy import check_noise
from ...errors import ConfigError
from ...kernels import LawKernels
from ...schema import Section

#: Smallest magnitude of a law parameter of ``fricgen noise`` besides 0: a product of two stays a
#: normal double (no underflow to subnormal numbers or to 0); an overflow shows as inf and is refused.
SMALLEST_PARAMETER = 1e-150


@dataclass(frozen=True)
class NoiseQuery(Section):
    """Speeds ``u`` (>= 0), the contact as centre distance ``r`` (> 0; w = w(r) from the law's weight)
    or as weight ``w`` (>= 0), contact mobility ``mu`` and ``kT`` (> 0), all finite."""

    u: tuple[float, ...] = field(metadata={"key": "--u"})
    r: float | None = field(default=None, metadata={"key": "--r"})
    w: float | None = field(default=None, metadata={"key": "--w"})
    mu: float = field(default=7.0, metadata={"key": "--mu"})
    kT: float = field(default=1.0, metadata={"key": "--kT"})

    def __post_init__(self):
        self.require(len(self.u) > 0, "u", "needs at least one speed", "give --u U1,U2,...")
        bad = [x for x in self.u if not (math.isfinite(x) and x >= 0)]
        self.require(not bad, "u", f"speeds must be finite and >= 0, got {bad[0] if bad else None}", "give speeds u >= 0")
        self.require(
            self.r is None or (math.isfinite(self.r) and self.r > 0), "r", f"must be positive and finite, got {self.r}", "give r > 0"
        )
        self.require(
            self.w is None or (math.isfinite(self.w) and self.w >= 0), "w", f"must be >= 0 and finite, got {self.w}", "give w >= 0"
        )
        self.require_positive("mu", "kT")
        self.require_scale("mu", "kT")


def default_mobility(mode: str) -> float:
    """The mobility of ``mode`` (sliding, rolling, spinning) between two spheres m = 1, R = 1/2,
    I = (2/5) m R^2 (the engine's :func:`~fricgen.langevin.mobility.mode_mobilities`): sliding
    1/m_i + 1/m_k + R_i^2/I_i + R_k^2/I_k = 7, rolling and spinning R_eff^2 (1/I_i + 1/I_k) = 1.25
    (R_eff = R_i R_k / (R_i + R_k) = 1/4), in 1/m."""
    from ...langevin.mobility import mode_mobilities
    from ...langevin.system import Particles

    return float(mode_mobilities(Particles.spheres(2), mode)[0])


def evaluate(kernels: LawKernels, calculus: str, query: NoiseQuery, parameters: dict[str, float]) -> dict:
    """D and f at each speed of the law ``kernels``, with the contact (w, r, mu, kT) and the law's parameters."""
    law = kernels.name
    params = kernels.parameters(**parameters)
    for name, value in parameters.items():
        if 0 < abs(value) < SMALLEST_PARAMETER:
            raise ConfigError(
                f"--param {name}", f"{value:g} is neither 0 nor at least {SMALLEST_PARAMETER:g} in magnitude", "give a larger value"
            )
    amplitude = kernels.noise_amplitude(calculus)
    if kernels.has_weight and query.r is None and query.w is None:
        raise ConfigError("--r", f"law {law} has a weight w(r): give --r R (centre distance) or --w W (weight value)")
    r = 1.0 if query.r is None else query.r
    w = query.w if query.w is not None else (float(kernels.weight(r, params)) if kernels.has_weight else 1.0)
    if not (math.isfinite(w) and w >= 0):
        raise ConfigError("--r", f"the law's weight w(r = {r:g}) is {w:g}, not a finite value >= 0", "give another --r, or --w")
    d = [float(amplitude(x, w, r, query.mu, query.kT, params)) for x in query.u]
    f = [float(kernels.friction(x, w, r, params)) for x in query.u]
    for name, values in (("D", d), ("f", f)):
        bad = next(((x, v) for x, v in zip(query.u, values) if not math.isfinite(v)), None)
        if bad is not None:
            raise ConfigError(
                name,
                f"is {bad[1]} at u = {bad[0]:g} (w = {w:g}): the result overflows double precision",
                "give smaller --u, --w (or larger --r), --kT or --param values",
            )
    for x, fx, dx in zip(query.u, f, d):
        if 0 < abs(dx) < sys.float_info.min or 0 < abs(fx) < sys.float_info.min or (dx == 0 and fx != 0):
            raise ConfigError(
                "D",
                f"underflows at u = {x:g} (f = {fx:g}, D = {dx:g}): below the smallest normal double",
                "give larger --param, --w (or smaller --r), --u or --kT values",
            )
    check_noise(kernels, calculus, params, [query.mu], query.kT)  # D at these values, at every speed that matters
    return {
        "law": law,
        "mode": kernels.mode,
        "calculus": calculus,
        "u": list(query.u),
        "D": d,
        "f": f,
        "w": w,
        "r": r,
        "mu": query.mu,
        "kT": query.kT,
        "parameters": dict(zip(kernels.parameter_names, params.tolist())),
    }
