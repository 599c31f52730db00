"""The derived D reproduces the paper's closed forms exactly (symbolic equality)."""

import sympy as sp
from fricgen.derive import derive_noise
from fricgen.derive.law.symbols import kT, mu, u, w
from fricgen.derive.noise.derivation import Calculus

g, k, b = sp.symbols("gamma_f kappa_f beta_f", positive=True)


def _same(x, y):
    return sp.simplify(sp.expand(sp.powsimp(sp.expand(x - y)))) == 0


def _branches(d):
    return [e for e, _ in d.args] if isinstance(d, sp.Piecewise) else [d]


def paper_constant(a):
    """(F-31) with a = kT nu."""
    return w * k * sp.sqrt(sp.pi) / sp.sqrt(2 * a) * sp.exp(u**2 / (2 * a)) * sp.erfc(u / sp.sqrt(2 * a))


def paper_coulomb_newton(a):
    """(F-33): (inner branch u < w kappa/gamma, outer branch)."""
    c = w * k / g
    inner = g * (1 - sp.exp((u**2 - c**2) / (2 * a))) + w * k * sp.sqrt(sp.pi) / sp.sqrt(2 * a) * sp.exp(u**2 / (2 * a)) * sp.erfc(
        c / sp.sqrt(2 * a)
    )
    return inner, paper_constant(a), c


def test_linear_is_f29_for_every_calculus(laws):
    for c in Calculus:
        assert derive_noise(laws["linear"], c).amplitude == w * g


def test_constant_is_f31(laws):
    for c in (Calculus.ITO, Calculus.STRATONOVICH):
        model = derive_noise(laws["coulomb"], c)
        assert _same(model.amplitude, paper_constant(model.variance_scale))


def test_coulomb_newton_is_f33(laws):
    for c in (Calculus.ITO, Calculus.STRATONOVICH):
        model = derive_noise(laws["coulomb_newton"], c)
        inner, outer, threshold = paper_coulomb_newton(model.variance_scale)
        d = model.amplitude
        assert isinstance(d, sp.Piecewise) and d.args[0][1] == (u < threshold)
        assert _same(d.args[0][0], inner) and _same(d.args[1][0], outer)


def test_hk_is_f_over_u_without_kT(laws):
    """The paper's (F-23) writes kT f/u; the zero-current condition gives f/u."""
    for name in ("linear", "coulomb_newton", "viscous_cubic", "smooth_coulomb"):
        law = laws[name]
        d = derive_noise(law, "hk").amplitude
        assert not d.has(kT)
        assert all(_same(x, y) for x, y in zip(_branches(d), _branches(sp.piecewise_fold((law.friction / u).rewrite(sp.Piecewise)))))


def test_viscous_cubic_closed_form(laws):
    model = derive_noise(laws["viscous_cubic"], "ito")
    assert _same(model.amplitude, w * (g + b * (u**2 + 2 * kT * mu)))


def test_integral_form_for_smooth_coulomb(laws):
    model = derive_noise(laws["smooth_coulomb"], "ito")
    assert not model.closed_form and model.amplitude.has(sp.Integral)
