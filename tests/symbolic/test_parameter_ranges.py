"""Parameter ranges: a law file declares the admissible values of each parameter, f >= 0, real and
finite is established for all of them (proven by SymPy, else checked on grids), and a law whose f
fails somewhere in its ranges is refused with the parameter values (fricgen.derive.law.ranges)."""

import math
from pathlib import Path

import pytest
import sympy as sp

import fricgen.derive.law.ranges
from fricgen.derive import LawError, load_law, make_law, save_law
from fricgen.derive.law.law_files import law_text
from fricgen.derive.law.lawdata import POSITIVE, Interval, LawFileError, parse_range
from fricgen.derive.law.laws import Parameter
from fricgen.derive.law.ranges import CHECKED_NUMERICALLY, PROVEN, range_values

#: The velocity-weakening law with ranges that keep f >= 0 (kappa_d <= 2 <= kappa_s); not in the catalogue.
FIXTURE = Path(__file__).with_name("fixtures") / "weakening.toml"
WEAKENING = "w*(kappa_s - kappa_d*(1 - exp(-u/u_s)))"


def weakening_parameters(kappa_s=None, kappa_d=None):
    parameters = {"kappa_s": {"default": 2.0}, "kappa_d": {"default": 1.0}, "u_s": {"default": 0.5}}
    for name, interval in (("kappa_s", kappa_s), ("kappa_d", kappa_d)):
        if interval is not None:
            parameters[name]["range"] = interval
    return parameters


def refused(expected: str, call, *args, **kwargs) -> str:
    with pytest.raises(LawFileError) as caught:
        call(*args, **kwargs)
    message = str(caught.value)
    assert "\n" not in message and expected in message, message
    return message


# --- the notation --------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "interval"),
    [
        ("[0, 2]", Interval(0.0, 2.0, True, True)),
        ("(0, inf)", POSITIVE),
        ("[1, 3)", Interval(1.0, 3.0, True, False)),
        (" ( 0.5 , 1e3 ] ", Interval(0.5, 1000.0, False, True)),
        ("[2, +inf)", Interval(2.0, math.inf, True, False)),
    ],
)
def test_ranges_are_intervals_with_open_or_closed_ends(text, interval):
    assert parse_range(text, "x") == interval
    assert parse_range(str(interval), "x") == interval  # str writes what parse_range reads
    inside = {i.lower for i in [interval] if i.lower_closed} | {interval.lower + 0.25}
    assert all(x in interval for x in inside)
    assert interval.lower - 1e-9 not in interval and (interval.lower in interval) == interval.lower_closed


def test_the_default_range_is_the_positive_reals_with_a_positive_symbol():
    assert Parameter("g", 1.0).range == POSITIVE and str(POSITIVE) == "(0, inf)"
    assert Parameter("g", 1.0).symbol == sp.Symbol("g", positive=True)
    assert Parameter("g", 1.0, range=Interval(0.0, 2.0, True, True)).symbol == sp.Symbol("g", nonnegative=True)
    assert Parameter("g", 1.0, range=Interval(0.0, 2.0, False, True)).symbol.is_positive


def _file(tmp_path, table: str) -> Path:
    path = tmp_path / "x.toml"
    path.write_text('name = "x"\nfriction = "w*gamma_f*u"\nweight = "wca"\n[parameters.gamma_f]\n' + table)
    return path


@pytest.mark.parametrize(
    ("table", "problem"),
    [
        ("default = 1.0\nrange = [0, 2]\n", 'parameters.gamma_f.range must be a string (an interval such as "[0, 2]"'),
        ('default = 1.0\nrange = "[0; 2]"\n', "parameters.gamma_f.range: cannot read '[0; 2]': write an interval such as"),
        ('default = 1.0\nrange = "0 < gamma_f < 2"\n', "cannot read"),
        ('default = 1.0\nrange = "[-1, 2]"\n', "[-1, 2] reaches below 0: parameters are real numbers >= 0"),
        ('default = 1.0\nrange = "[0, inf]"\n', "an infinite end is open: write [0, inf)"),
        ('default = 1.0\nrange = "[2, 1]"\n', "[2, 1] is empty"),
        ('default = 1.0\nrange = "(1, 1]"\n', "is empty"),
        ('default = 3.0\nrange = "[0, 2]"\n', "parameters.gamma_f: the default 3.0 is outside its range [0, 2]"),
        ('default = 0.0\nrange = "(0, 2]"\n', "the default 0.0 is outside its range (0, 2]"),
        ('default = 2\nrange = "[0, 2)"\n', "the default 2 is outside its range [0, 2)"),
        ("default = 1.0\nmin = 0\n", "unknown key(s) ['min']"),
    ],
)
def test_bad_ranges_in_law_files_are_refused_on_one_line(tmp_path, table, problem):
    message = refused(problem, load_law, _file(tmp_path, table))
    assert message.startswith(str(tmp_path / "x.toml"))


def test_ranges_from_python_are_checked_like_the_file():
    parameters = {**weakening_parameters(), "kappa_d": {"default": 3.0, "range": "[0, 2]"}}
    refused("needs a finite default in its range [0, 2], got 3.0", make_law, "x", WEAKENING, parameters, weight="wca")
    refused("parameter kappa_d: range: cannot read", make_law, "x", WEAKENING, weakening_parameters(kappa_d="0..2"), weight="wca")
    refused("parameter gamma_f needs a finite positive default, got -1.0", make_law, "x", "gamma_f*u", {"gamma_f": {"default": -1.0}})
    law = make_law("x", WEAKENING, weakening_parameters(Interval(2.0, math.inf, True), Interval(0.0, 2.0, True, True)), weight="wca")
    assert law.range_check == PROVEN


# --- f >= 0 over the ranges ----------------------------------------------------------------------


def test_the_weakening_fixture_is_proven_over_its_ranges(tmp_path):
    law = load_law(FIXTURE)
    assert law.range_check == PROVEN
    assert {p.name: str(p.range) for p in law.parameters} == {
        "kappa_s": "[2, inf)",
        "kappa_d": "[0, 2]",
        "u_s": "(0, inf)",
        "epsilon": "(0, inf)",
        "sigma": "(0, inf)",
    }
    assert 'range = "[0, 2]"' in law_text(law) and 'range = "(0, inf)"' not in law_text(law)
    assert load_law(save_law(law, tmp_path)) == law


def test_the_weakening_law_without_ranges_is_refused_at_the_values_that_make_f_negative():
    """The defaults 2, 1, 0.5 are fine, but kappa_d = 3 > kappa_s makes f < 0 for fast sliding (and D < 0)."""
    message = refused("f is negative at", make_law, "weakening", WEAKENING, weakening_parameters(), weight="wca")
    assert "kappa_s=2, kappa_d=3, u_s=0.5" in message
    assert "for every value in the parameters' ranges (kappa_s in (0, inf), kappa_d in (0, inf), u_s in (0, inf))" in message


def test_a_range_of_one_parameter_is_not_enough_when_f_needs_a_relation():
    """kappa_d in [0, 2] alone: kappa_s may still be smaller than kappa_d."""
    message = refused("f is negative at", make_law, "weakening", WEAKENING, weakening_parameters(kappa_d="[0, 2]"), weight="wca")
    assert "kappa_d in [0, 2]" in message


def test_proven_symbolically_or_checked_numerically():
    assert make_law("x", "w*kappa_f*tanh(u/u0)", {"kappa_f": {"default": 5.0}, "u0": {"default": 0.1}}, weight="wca").range_check == PROVEN
    assert (
        make_law("x", "Min(gamma_f*u, w*kappa_f)", {"gamma_f": {"default": 6.0}, "kappa_f": {"default": 5.0}}, weight="wca").range_check
        == PROVEN
    )
    # SymPy does not bound the cosine: f >= 0 is checked on the grids
    law = make_law("x", "w*kappa_f*(1 + cos(u/u0))", {"kappa_f": {"default": 5.0}, "u0": {"default": 0.1}}, weight="wca")
    assert law.range_check == CHECKED_NUMERICALLY


def test_a_law_negative_only_away_from_its_default_is_refused_unless_its_range_excludes_that():
    friction = "w*(2 - c*(1 + sin(u)))"  # >= 0 for c <= 1 only
    message = refused("f is negative at", make_law, "x", friction, {"c": {"default": 0.5}}, weight="wca")
    assert "c=3" in message and "c in (0, inf)" in message
    assert make_law("x", friction, {"c": {"default": 0.5, "range": "(0, 1]"}}, weight="wca").range_check == CHECKED_NUMERICALLY


def test_a_closed_end_is_part_of_the_range():
    message = refused(
        "f is not finite at",
        make_law,
        "x",
        "w*kappa_f*u/u0",
        {"kappa_f": {"default": 1.0}, "u0": {"default": 0.5, "range": "[0, 1]"}},
        weight="wca",
    )
    assert "u0=0" in message
    assert (
        make_law("x", "w*kappa_f*u/u0", {"kappa_f": {"default": 1.0}, "u0": {"default": 0.5, "range": "(0, 1]"}}, weight="wca").range_check
        == PROVEN
    )


def test_without_array_evaluation_every_point_is_checked_at_30_digits(monkeypatch):
    def unavailable(fast, points):
        raise TypeError("no array evaluation")

    monkeypatch.setattr(fricgen.derive.law.ranges, "_ranks", unavailable)
    friction = "w*(2 - c*(1 + sin(u)))"
    refused("f is negative at", make_law, "x", friction, {"c": {"default": 0.5}}, weight="wca")
    assert make_law("x", friction, {"c": {"default": 0.5, "range": "(0, 1]"}}, weight="wca").range_check == CHECKED_NUMERICALLY


def test_range_values_cover_the_range():
    unbounded = Parameter("k", 2.0, range=Interval(2.0, math.inf, True))
    values = range_values(unbounded)
    assert values[0] == 2.0 and values[-1] >= 1e6 and all(v in unbounded.range for v in values)
    bounded = Parameter("k", 1.0, range=Interval(0.0, 2.0, False, True))
    values = range_values(bounded)
    assert 0.0 not in values and values[-1] == 2.0 and 1.0 in values and min(values) < 1e-5
    few = range_values(bounded, 3)
    assert len(few) <= 4 and few[-1] == 2.0 and 1.0 in few
    with pytest.raises(LawError):
        make_law("x", "gamma_f*u", {"gamma_f": {"default": 1.0, "range": 3}})


def test_the_weakening_fixture_verifies_within_its_ranges():
    """verify's numeric checks stay inside the declared ranges (kappa_d in [0, 2]: its default x 3 = 3
    would make f negative), so a law consistent over its ranges verifies in full."""
    from fricgen.derive import derive_noise, verify

    report = verify(derive_noise(load_law(FIXTURE), "ito"))
    assert report.verified, (report.checks, report.details)
