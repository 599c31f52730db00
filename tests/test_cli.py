"""The pinned command line: fricgen verify."""

import json
import subprocess
import sys


def fricgen(*args):
    return subprocess.run([sys.executable, "-m", "fricgen.cli", *args], capture_output=True, text=True, timeout=600)


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
