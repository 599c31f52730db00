"""Valid laws whose branches (or limit at rest) SymPy cannot decide: derive_noise falls back to the
integral (F-22), evaluated by quadrature, and says why (NoiseModel.reason), or refuses the calculus in
one line; it never ends in a traceback."""

import mpmath
import pytest
import sympy as sp

from fricgen.derive import LawError, derive_noise, make_law, verify
from fricgen.derive.backends.numba_kernels.accuracy import python_kernels
from fricgen.derive.law.symbols import kT, mu, r, u, w
from fricgen.derive.noise.derivation import split
from fricgen.derive.noise.reference import reference_amplitude

MIN_POWER = "Min(gamma_f*u**1.5, w*kappa_f)"
WEIGHT_IN_R = "gamma_f*u*Piecewise((1, r < 1), (exp(-(r-1)/ell), True))"
SYMBOLIC_EXPONENT = "gamma_f*u**alpha"
#: Three pieces whose branch points p, q SymPy cannot order (p < q is not known).
UNORDERED = "Piecewise((gamma_f*u, u < p), (gamma_f*p + gamma_f*(u - p)/2, u < q), (gamma_f*(p + q)/2, True))"
#: Each law's parameter defaults and weight.
SPECS = {
    MIN_POWER: ({"gamma_f": 3.0, "kappa_f": 2.5}, "wca"),
    WEIGHT_IN_R: ({"gamma_f": 3.0, "ell": 0.1}, None),
    SYMBOLIC_EXPONENT: ({"gamma_f": 3.0, "alpha": 1.5}, None),
    UNORDERED: ({"gamma_f": 3.0, "p": 1.0, "q": 2.0}, None),
}
PHYSICS = {"ode_residual", "zero_current_3d", "zero_current_2d", "noise_covariance", "boundary_condition", "nonnegative_finite"}


def law(friction):
    defaults, weight = SPECS[friction]
    return make_law("test_law", friction, {name: {"default": value} for name, value in defaults.items()}, weight=weight)


def kernel_error(model, cases=((1.0, 7.0, 1.0), (0.3, 2.0, 0.05), (2.0, 7.0, 60.0))) -> float:
    """Largest relative error of the printed noise kernel (run as Python) against reference_amplitude
    (mpmath.quad split at the branch points of f), over u = 0 ... 300 sqrt(kT mu)."""
    kernel = python_kernels(model)[f"noise_amplitude_{model.calculus.value}"]
    worst = 0.0
    for temperature, mobility, weight in cases:
        values = {**model.law.defaults, kT: temperature, mu: mobility, w: weight, r: 1.0}
        params = [float(values[p.symbol]) for p in model.law.parameters]
        with mpmath.workdps(30):
            exact = reference_amplitude(model, model.variance_scale, values)
            for x in [0.0, *(mpmath.sqrt(temperature * mobility) * 10.0**e for e in (-6, -3, -1, -0.5, 0, 0.5, 1, 2, 2.5))]:
                got = kernel(float(x), weight, 1.0, mobility, temperature, params)
                worst = max(worst, float(abs((got - exact(x)) / exact(x))))
    return worst


def one_line(error) -> str:
    message = str(error.value)
    assert message and "\n" not in message and len(message) < 400, message
    return message


def test_branched_parts_free_of_u_are_no_branch_points():
    g, ell = sp.symbols("gamma_f ell", positive=True)
    in_r = sp.Piecewise((1, r < 1), (sp.exp(-(r - 1) / ell), True))
    assert split(g * u * in_r) == ([split(g * u * in_r)[0][0]], "")
    (only,), why = split(g * u * in_r)
    assert only.expr == g * u * in_r and (only.lower, only.upper) == (0, sp.oo) and why == ""
    pieces, why = split(sp.Min(g * u, w * in_r))  # the slip point w in(r)/gamma_f is decided: in(r) > 0
    assert why == "" and [p.expr for p in pieces] == [g * u, w * in_r] and pieces[0].upper == w * in_r / g


@pytest.mark.parametrize(
    ("friction", "why"),
    [(MIN_POWER, "cannot tell which branch holds at u = "), (UNORDERED, "cannot order the branch points p, q")],
)
def test_undecided_branches_leave_f_in_one_piece_and_say_why(friction, why):
    f = law(friction).friction
    (only,), reason = split(f)
    assert only.expr == f and reason.startswith("SymPy cannot decide the branches of ") and why in reason
    model = derive_noise(law(friction), "ito")
    assert not model.closed_form and model.reason == reason
    assert model.amplitude.has(sp.Integral)


@pytest.mark.parametrize("friction", [MIN_POWER, UNORDERED])
def test_undecided_branches_verify_through_quadrature(friction):
    """Every check holds, kernel_accuracy included (its mpmath reference is split at the kinks of f);
    the printed quadrature, cut at the branch points, agrees with mpmath to 1e-9."""
    model = derive_noise(law(friction), "ito")
    report = verify(model)
    assert not report.closed_form
    assert report.verified, (report.checks, report.details)
    assert kernel_error(model) < 1e-9


def test_a_weight_piecewise_in_r_has_a_closed_form_in_every_calculus():
    f = law(WEIGHT_IN_R)
    for calculus in ("ito", "stratonovich", "hk"):
        model = derive_noise(f, calculus)
        assert model.closed_form and model.reason == "" and not model.amplitude.has(u)
        report = verify(model)
        assert report.verified, (calculus, report.checks, report.details)


def test_a_symbolic_exponent_verifies_through_quadrature_in_ito():
    model = derive_noise(law(SYMBOLIC_EXPONENT), "ito")
    assert not model.closed_form and model.reason == "f = gamma_f*u**alpha is not a sum of polynomials in u times exp(c u)"
    report = verify(model)
    assert report.verified, (report.checks, report.details)


@pytest.mark.parametrize(
    ("friction", "why"),
    [(SYMBOLIC_EXPONENT, "Not sure of sign of alpha - 1"), (MIN_POWER, "_eval_nseries method should be added to Min")],
)
def test_hk_without_a_known_limit_at_rest_is_refused_on_one_line(friction, why):
    with pytest.raises(LawError) as caught:
        derive_noise(law(friction), "hk")
    message = one_line(caught)
    assert message.startswith("law test_law (hk): SymPy cannot take the limit of D = f/u = ") and why in message
    assert message.endswith("write exponents as numbers, or leave hk out of the law's calculi")
