"""The pinned command line: fricgen verify."""

import json
import subprocess
import sys


def fricgen(*args):
    return subprocess.run([sys.executable, "-m", "fricgen", *args], capture_output=True, text=True, timeout=600)


def test_verify_json_reports_each_law_and_calculus():
    done = fricgen("verify", "linear", "coulomb_newton", "--calculus", "hk", "--json")
    assert done.returncode == 0, done.stderr
    reports = json.loads(done.stdout)
    assert [(x["law"], x["calculus"]) for x in reports] == [("linear", "hk"), ("coulomb_newton", "hk")]
    for x in reports:
        assert {"law", "calculus", "closed_form", "verified", "checks", "seconds"} <= set(x)
        assert x["verified"] is True and x["closed_form"] is True and all(x["checks"].values())


def test_verify_exits_nonzero_when_a_law_fails():
    done = fricgen("verify", "coulomb", "--calculus", "hk", "--json")
    assert done.returncode == 1
    (report,) = json.loads(done.stdout)
    assert report["verified"] is False and report["checks"]["nonnegative_finite"] is False


def test_unnamed_laws_skip_calculi_they_exclude():
    done = fricgen("verify", "--calculus", "hk")
    assert done.returncode == 0, done.stdout + done.stderr
    assert "skipped coulomb/hk" in done.stderr
    assert "coulomb_newton" in done.stdout and "verified" in done.stdout


def test_unknown_law_is_a_clear_error():
    done = fricgen("verify", "no_such_law")
    assert done.returncode == 2 and "unknown law" in done.stderr and "coulomb_newton" in done.stderr


def test_generate_is_idempotent_and_reports_verification(tmp_path):
    first = fricgen("generate", "linear", "--output", str(tmp_path))
    assert first.returncode == 0, first.stderr
    assert "verified linear/ito" in first.stdout and "written" in first.stdout
    second = fricgen("generate", "linear", "--output", str(tmp_path))
    assert second.returncode == 0 and "written" not in second.stdout and "unchanged" in second.stdout


def test_noise_json_through_the_generated_kernels():
    import numpy as np
    from scipy.special import erfcx

    done = fricgen("noise", "coulomb", "--calculus", "stratonovich", "--u", "0,1,100", "--w", "2", "--mu", "7", "--json")
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    a = 0.5 * 7.0
    u = np.array(result["u"])
    expected = 2 * 5.0 * np.sqrt(np.pi / (2 * a)) * erfcx(u / np.sqrt(2 * a))  # (F-31), kappa_f = 5
    np.testing.assert_allclose(result["D"], expected, rtol=1e-12)


def test_noise_weight_from_the_distance():
    done = fricgen("noise", "linear", "--u", "1", "--r", "1.05", "--param", "gamma_f=2", "--json")
    result = json.loads(done.stdout)
    w = 48 / 1.05**13 - 24 / 1.05**7
    assert abs(result["w"] - w) < 1e-12 * w and abs(result["D"][0] - 2 * w) < 1e-12 * w


def test_noise_errors_are_clear():
    assert "no kernels for the 'hk' calculus" in fricgen("noise", "coulomb", "--calculus", "hk", "--u", "1", "--w", "1").stderr
    assert "give --r R" in fricgen("noise", "coulomb", "--u", "1").stderr
    assert "no parameter" in fricgen("noise", "linear", "--u", "1", "--w", "1", "--param", "kappa_f=1").stderr
    assert "expected comma-separated numbers" in fricgen("noise", "linear", "--u", "a,b", "--w", "1").stderr


def test_thermostat_check_json():
    done = fricgen("thermostat-check", "coulomb_newton", "--time", "10", "--seed", "3", "--json")
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    for key in ("T_trans", "T_rot", "T_trans_err", "T_rot_err", "kl_trans", "kl_rot", "passed"):
        assert key in result
    assert result["passed"] is True and abs(result["T_trans"] - 1) < 4 * result["T_trans_err"]


def test_thermostat_check_fails_without_contact_noise():
    done = fricgen("thermostat-check", "coulomb_newton", "--no-contact-noise", "--time", "10", "--json")
    assert done.returncode == 1 and json.loads(done.stdout)["passed"] is False
    assert "no kernels for the 'hk' calculus" in fricgen("thermostat-check", "coulomb", "--calculus", "hk").stderr
