"""Generated law modules carry the parameters' ranges (RANGES), LawKernels.parameters refuses a value
outside them in one line, and the loader tells a missing dependency (numba) from missing kernels."""

import importlib
import math
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

import fricgen.kernels
from fricgen.derive.driver import generate
from fricgen.derive.law.catalogues import LawSearch
from fricgen.derive.law.lawdata import CATALOGUE, POSITIVE, Interval
from fricgen.errors import ConfigError
from fricgen.kernels import KernelError, LawKernels, load_law_kernels, load_potential

#: The velocity-weakening test law (not in the catalogue): kappa_s in [2, inf), kappa_d in [0, 2].
WEAKENING = Path(__file__).resolve().parents[1] / "symbolic" / "fixtures" / "weakening.toml"


@pytest.fixture(scope="module")
def weakening(tmp_path_factory):
    """The weakening law generated into a package of its own (gen_weakening), imported and compiled."""
    root = tmp_path_factory.mktemp("weakening")
    catalogue = root / "catalogue"
    catalogue.mkdir()
    shutil.copy(WEAKENING, catalogue / "weakening.toml")
    written, reports = generate(["weakening"], catalogue=catalogue, output=root / "gen_weakening")
    assert all(report.verified for report in reports)
    sys.path.insert(0, str(root))
    try:
        module = importlib.import_module("gen_weakening.laws.weakening")
        yield LawKernels("weakening", module), (root / "gen_weakening" / "laws" / "weakening.py").read_text()
    finally:
        sys.path.remove(str(root))
        for name in [m for m in sys.modules if m == "gen_weakening" or m.startswith("gen_weakening.")]:
            del sys.modules[name]


def test_the_module_carries_the_ranges_and_how_f_was_checked_over_them(weakening):
    kernels, text = weakening
    assert kernels.module.PARAMETERS == ("kappa_s", "kappa_d", "u_s", "epsilon", "sigma")
    assert "RANGES = ((2.0, math.inf, True, False), (0.0, 2.0, True, True), (0.0, math.inf, False, False)," in text
    assert "# Parameter ranges (RANGES): f >= 0 and finite over them, proven" in text
    assert kernels.ranges["kappa_d"] == Interval(0.0, 2.0, True, True) and kernels.ranges["u_s"] == POSITIVE


@pytest.mark.parametrize(
    ("overrides", "message"),
    [
        ({"kappa_d": 3.0}, "law.parameters.kappa_d: must be in [0, 2], got 3.0; give a value in [0, 2] (the range law weakening declares"),
        ({"kappa_d": -0.5}, "law.parameters.kappa_d: must be in [0, 2], got -0.5"),
        ({"kappa_s": 1.0}, "law.parameters.kappa_s: must be in [2, inf), got 1.0"),
        ({"kappa_d": math.inf}, "law.parameters.kappa_d: must be finite and in [0, 2], got inf"),
        ({"kappa_d": math.nan}, "law.parameters.kappa_d: must be finite and in [0, 2], got nan"),
        ({"u_s": 0.0}, "law.parameters.u_s: must be positive and finite, got 0.0; give a positive value"),
        ({"kappa_f": 1.0}, "law.parameters.kappa_f: law weakening has no parameter 'kappa_f'"),
    ],
)
def test_values_outside_their_range_are_refused_on_one_line(weakening, overrides, message):
    kernels, _ = weakening
    with pytest.raises(ConfigError) as caught:
        kernels.parameters(**overrides)
    assert str(caught.value).startswith(message) and "\n" not in str(caught.value)
    assert caught.value.key == f"law.parameters.{next(iter(overrides))}"


def test_the_amplitude_is_finite_and_nonnegative_at_the_corners_of_the_ranges(weakening):
    kernels, _ = weakening
    for corner in ({"kappa_s": 2.0, "kappa_d": 2.0}, {"kappa_s": 2.0, "kappa_d": 0.0}, {"kappa_s": 1e6, "kappa_d": 2.0, "u_s": 1e-6}):
        params = kernels.parameters(**corner)
        for calculus in kernels.calculi:
            amplitude = kernels.noise_amplitude(calculus)
            values = [amplitude(x, 60.0, 1.0, 7.0, 1.0, params) for x in np.concatenate([[0.0], np.geomspace(1e-6, 1e4, 60)])]
            assert all(math.isfinite(d) and d >= 0 for d in values), (corner, calculus)


def test_catalogue_laws_have_the_default_ranges():
    kernels = load_law_kernels("coulomb_newton")
    assert kernels.ranges == dict.fromkeys(kernels.parameter_names, POSITIVE)
    assert kernels.module.RANGES[0] == (0.0, math.inf, False, False)


@pytest.fixture
def failing_import(monkeypatch):
    """importlib.import_module, as the loader calls it, raising ``error`` for generated modules."""
    real = importlib.import_module

    def install(error):
        def fake(name, package=None):
            if name.startswith("fricgen.generated."):
                raise error
            return real(name, package)

        monkeypatch.setattr(fricgen.kernels.importlib, "import_module", fake)

    return install


def test_a_missing_numba_is_reported_as_such(failing_import):
    failing_import(ModuleNotFoundError("No module named 'numba'", name="numba"))
    with pytest.raises(KernelError, match=r"^numba is not installed: the kernels of law linear need it .*pip install numba"):
        load_law_kernels("linear")
    with pytest.raises(KernelError, match=r"^numba is not installed: the kernels of potential wca need it"):
        load_potential("wca")


def test_missing_kernels_are_still_missing_kernels(failing_import, tmp_path):
    failing_import(ModuleNotFoundError("No module named 'fricgen.generated.laws.linear'", name="fricgen.generated.laws.linear"))
    with pytest.raises(KernelError, match="no generated kernels for law linear: run `fricgen generate linear`"):
        load_law_kernels("linear", LawSearch.only(CATALOGUE))


def test_another_import_error_is_reported_with_its_cause(failing_import):
    failing_import(ImportError("cannot import name 'erfcx' from 'fricgen.generated.special'"))
    expected = r"cannot import the kernels of law coulomb \(fricgen.generated.laws.coulomb\): cannot import name 'erfcx'"
    with pytest.raises(KernelError, match=expected):
        load_law_kernels("coulomb")
