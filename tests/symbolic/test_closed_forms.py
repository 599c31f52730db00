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


# --- exponential polynomials: sum_c P_c(u) exp(c u) (fricgen.derive.noise.closed_forms) ---------------------

ks, kd, us = sp.symbols("kappa_s kappa_d u_s", positive=True)


def stribeck_by_hand(a):
    """(F-22) of w (kappa_d + (kappa_s - kappa_d) e^{-u/u_s}) completed by hand: the constant part is (F-31), and
    int_u^oo e^{-s/u_s - s^2/2a} ds = e^{a/(2 u_s^2)} sqrt(pi a/2) erfc((u + a/u_s)/sqrt(2a))."""
    shifted = sp.exp(a / (2 * us**2)) * sp.sqrt(sp.pi * a / 2) * sp.erfc((u + a / us) / sp.sqrt(2 * a))
    return paper_constant(a).subs(k, kd) + w * (ks - kd) * sp.exp(u**2 / (2 * a)) / a * shifted


def test_stribeck_is_closed_and_equals_the_form_by_hand(laws):
    for c in (Calculus.ITO, Calculus.STRATONOVICH):
        model = derive_noise(laws["stribeck"], c)
        assert model.closed_form and not model.amplitude.has(sp.Integral), model.reason
        assert _same(model.amplitude, stribeck_by_hand(model.variance_scale))


def test_stribeck_prints_through_erfcx_without_overflow(laws):
    """exp(u^2/2a) erfc(.) becomes erfcx(.) exp(-u/u_s): nothing grows like exp(u^2/2a) in the printed D."""
    from fricgen.derive.backends.printing import erfcx, stabilize

    printed = stabilize(derive_noise(laws["stribeck"], "ito").amplitude)
    assert printed.has(erfcx) and not printed.has(sp.erfc)
    assert all(sp.degree(sp.expand(e.args[0]), sp.Symbol("u")) <= 1 for e in printed.atoms(sp.exp))


def test_the_exponential_polynomial_family():
    from fricgen.derive.noise.closed_forms import exponential_polynomial, tail

    x = sp.Symbol("x", positive=True)
    groups = exponential_polynomial(u**2 * sp.exp(-u / us + 3) + sp.cosh(2 * u) + kd)
    assert set(groups) == {-1 / us, 2, -2, 0} and _same(groups[-1 / us], u**2 * sp.exp(3))
    for no in (sp.tanh(u), u ** sp.Rational(1, 2) * sp.exp(-u), sp.exp(-(u**2)), sp.exp(u) / (1 + u)):
        assert exponential_polynomial(no) is None and tail(no, x, kT) is None
    # the tail of u^2 e^{-u} against e^{-s^2/2a} differentiates back to the integrand
    a = kT * mu
    integral = tail(u**2 * sp.exp(-u), x, a)
    assert _same(sp.diff(integral, x), -(x**2) * sp.exp(-x) * sp.exp(-(x**2) / (2 * a)))


def test_branches_of_exponential_polynomials_verify_in_closed_form():
    """A Piecewise whose branches are each of the family (here u e^{-u/u_s}, capped at u_c) is closed, proven
    (residual exactly 0, D continuous at u_c) and its printed kernel matches mpmath."""
    from fricgen.derive import make_law, verify

    law = make_law(
        "capped",
        "Piecewise((w*gamma_f*u*exp(-u/u_s), u < u_c), (w*gamma_f*u_c*exp(-u_c/u_s), True))",
        {"gamma_f": {"default": 3.0}, "u_s": {"default": 0.7}, "u_c": {"default": 0.4}},
        weight="wca",
        calculi=("ito", "stratonovich", "hk"),
    )
    for c in ("stratonovich",):
        model = derive_noise(law, c)
        assert model.closed_form and isinstance(model.amplitude, sp.Piecewise), model.reason
        report = verify(model)
        assert report.verified, (c, report.checks, report.details)
        assert float(report.details["kernel_max_rel_error"]) < 1e-13
