"""The run-time accuracy corpus: laws whose parameters are all in range, at values where the kernels'
fixed quadrature of D is wrong (fricgen.accuracy, docs/trust-model.md).

Two laws of our own (not the red team's held-out ones), each with an exact D to prove the reference right:

- ``bump``: viscous friction with a Gaussian bump, f = gamma_f u + kappa_b exp(-((u - u_b)/delta)^2). At
  the defaults the bump is as wide as the thermal speeds; made narrow (delta = 0.01, far below the
  defaults' scales) it falls between the nodes of the kernels' 10-point panels; at delta = 1e-4
  between those of any sampling that does not know where it lies. Exact:
  D = gamma_f + (kappa_b/a) sigma sqrt(pi/2) exp(c + u^2/(2a)) erfc((u - m)/(sigma sqrt 2)), with
  1/(2 sigma^2) = 1/delta^2 + 1/(2a), m = 2 a u_b/(2a + delta^2), c = m^2/(2 sigma^2) - u_b^2/delta^2.
- ``power``: f = kappa_f u^alpha, alpha in [1, 100]. With a large exponent the integrand of (F-22) peaks
  near the end of the kernels' Gaussian cut (exp(-46)). Exact:
  D = (kappa_f/a) (2a)^((alpha+1)/2) Gamma((alpha+1)/2, u^2/(2a)) e^(u^2/(2a)) / 2.

Rows: law, calculus, parameter values, and None (the check accepts) or a piece of the one-line refusal.
"""

from __future__ import annotations

import mpmath

LAWS = {
    "bump": """name = "bump"
friction = "gamma_f*u + kappa_b*exp(-((u - u_b)/delta)**2)"
calculi = ["ito", "stratonovich"]

[parameters.gamma_f]
default = 1.0

[parameters.kappa_b]
default = 1.0

[parameters.u_b]
default = 1.0
unit = "sigma/t0"

[parameters.delta]
default = 0.5
unit = "sigma/t0"
""",
    "power": """name = "power"
friction = "kappa_f*u**alpha"
calculi = ["ito", "stratonovich"]

[parameters.kappa_f]
default = 1.0

[parameters.alpha]
default = 1.5
range = "[1, 100]"
""",
}

#: The narrow bump: 1/50 of the default width, 100 times as high, at 1.5 sqrt(mu kT) (mu = 7, kT = 1).
NARROW = {"kappa_b": 100.0, "u_b": 4.0, "delta": 0.01}
#: Narrower than any sampling finds unaided (quad alone misses it by 20 %, its estimate 1e-14): found
#: through the breakpoints at the law's parameter values (fricgen.accuracy._hints).
NEEDLE = {"kappa_b": 1e4, "u_b": 4.0, "delta": 1e-4}

ROWS = [
    ("bump", "ito", {}, None),
    ("bump", "stratonovich", {}, None),
    ("bump", "ito", NARROW, "its D is off by"),
    ("bump", "stratonovich", NARROW, "its D is off by"),
    ("bump", "ito", NEEDLE, "its D is off by"),
    ("power", "ito", {"alpha": 12.0}, None),
    ("power", "ito", {"alpha": 60.0}, "its D is off by"),
    ("power", "stratonovich", {"alpha": 80.0}, "its D is off by"),
]


def exact(law: str, values: dict, a: float, u: float) -> mpmath.mpf:
    """The exact D of ``law`` (the module docstring) at ``u`` for a = (1 - theta) mu kT, 30 digits."""
    with mpmath.workdps(30):
        a, u = mpmath.mpf(a), mpmath.mpf(u)
        if law == "power":
            half = (values["alpha"] + 1) / 2
            return values["kappa_f"] / a * (2 * a) ** half * mpmath.gammainc(half, u**2 / (2 * a)) * mpmath.exp(u**2 / (2 * a)) / 2
        delta, peak = mpmath.mpf(values["delta"]), mpmath.mpf(values["u_b"])
        sigma = 1 / mpmath.sqrt(2 / delta**2 + 1 / a)
        m = 2 * a * peak / (2 * a + delta**2)
        c = m**2 / (2 * sigma**2) - peak**2 / delta**2
        bump = sigma * mpmath.sqrt(mpmath.pi / 2) * mpmath.exp(c + u**2 / (2 * a)) * mpmath.erfc((u - m) / (sigma * mpmath.sqrt(2)))
        return values["gamma_f"] + values["kappa_b"] / a * bump
