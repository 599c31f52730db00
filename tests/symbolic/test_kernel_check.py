"""The printed kernels, run as plain Python by the Numba backend's accuracy check, without Numba, against the
proof's reference values (fricgen.derive.noise.reference)."""

import dataclasses
import math
import subprocess
import sys

import mpmath
import pytest

from fricgen.derive import derive_noise
from fricgen.derive.backends.numba_kernels.accuracy import python_kernels
from fricgen.derive.backends.special_functions import execute
from fricgen.derive.law.symbols import kT, mu, r, w
from fricgen.derive.noise.reference import KERNEL_CASES, reference_amplitude, reference_points


def test_checking_the_kernels_imports_no_numba():
    code = (
        "import sys\n"
        "from fricgen.derive import catalogue, derive_noise\n"
        "from fricgen.derive.backends.numba_kernels.accuracy import python_kernels\n"
        "kernels = python_kernels(derive_noise(catalogue()['coulomb'], 'ito'))\n"
        "assert kernels['noise_amplitude_ito'](1.0, 1.0, 1.0, 7.0, 1.0, [5.0, 1.0, 1.0]) > 0\n"
        "assert not {'numba', 'fricgen.kernels', 'fricgen.generated.special'} & set(sys.modules)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr


def test_executed_code_may_import_only_what_it_is_given():
    assert execute("import math\nx = math.pi\n", {"math": math})["x"] == math.pi
    with pytest.raises(ImportError, match="numpy"):
        execute("import numpy\n", {"math": math})


def test_every_kernel_of_a_law_runs_as_python(laws):
    model = derive_noise(laws["coulomb_newton"], "stratonovich")
    kernels = python_kernels(model)
    params = [6.0, 5.0, 1.0, 1.0]
    arguments = (0.5, 60.0, 1.0, 7.0, 2.0, params)
    force_over_u, amplitude = kernels["contact_stratonovich"](*arguments)
    assert force_over_u == 6.0 and amplitude == kernels["noise_amplitude_stratonovich"](*arguments)
    assert kernels["weight"](1.0, params) == pytest.approx(24.0)


@pytest.mark.parametrize("calculus", ["ito", "stratonovich"])
def test_the_quadrature_reference_is_the_closed_form(laws, calculus):
    """(F-22) by mpmath.quad equals the closed form of Coulomb–Newton (F-33) to 1e-15."""
    model = derive_noise(laws["coulomb_newton"], calculus)
    values = {**laws["coulomb_newton"].defaults, kT: 2.0, mu: 7.0, w: 60.0, r: 1.0}
    closed = reference_amplitude(model, model.variance_scale, values)
    integral = reference_amplitude(dataclasses.replace(model, closed_form=False), model.variance_scale, values)
    with mpmath.workdps(30):
        for x in (0.0, 1e-3, 1.0, 9.999, 10.0, 10.001, 50.0, 3000.0):
            assert abs(integral(x) / closed(x) - 1) < 1e-15, x


def test_reference_points_span_the_cases_and_the_branch_points(laws):
    model = derive_noise(laws["coulomb_newton"], "ito")
    points = reference_points(model, model.variance_scale)
    assert {p.case for p in points} == {f"kT={t}, mu={m}, w={weight}, r={d}, parameters x{x}" for t, m, weight, d, x in KERNEL_CASES}
    assert all(p.exact is not None and p.exact > 0 for p in points)
    speeds = {p.speed for p in points if p.case.startswith("kT=1.0,")}
    assert 0.0 in speeds and any(abs(x - 5.0 / 6.0) < 1e-15 for x in speeds)  # u = 0 and the slip speed w kappa_f/gamma_f
    assert max(speeds) == pytest.approx(1e3 * math.sqrt(7.0))
