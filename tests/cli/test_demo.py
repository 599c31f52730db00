"""The main job, `fricgen demo`: the consistent thermostat at kT, the model without noise clearly not."""

import json
import subprocess
import sys

import pytest

PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    out = tmp_path_factory.mktemp("demo") / "fricgen-demo"
    done = subprocess.run(
        [sys.executable, "-m", "fricgen", "demo", "--out", str(out), "--json"], capture_output=True, text=True, timeout=600
    )
    assert done.returncode == 0, done.stderr
    return out, json.loads(done.stdout), done.stderr


def test_demo_writes_plots_and_the_summary(demo):
    out, summary, _ = demo
    assert sorted(p.name for p in out.iterdir()) == ["histograms.png", "summary.json", "temperatures.png"]
    for name in ("histograms.png", "temperatures.png"):
        data = (out / name).read_bytes()
        assert data.startswith(PNG) and len(data) > 10_000
    assert json.loads((out / "summary.json").read_text()) == summary
    assert summary["law"] == "coulomb_newton" and summary["calculus"] == "ito" and summary["dim"] == 2
    assert summary["phi"] == 0.6 and summary["dt"] == 1e-3 and summary["n"] >= 256 and summary["steps"] >= 5000
    assert set(summary["runs"]) == {"with_contact_noise", "without_contact_noise"} and summary["seconds"] > 0


def test_demo_shows_a_progress_bar(demo):
    _, _, stderr = demo
    assert "fricgen demo" in stderr and "step/s" in stderr and "100%" in stderr


def test_contact_noise_thermalises_at_kT(demo):
    run = demo[1]["runs"]["with_contact_noise"]
    for kind in ("trans", "rot"):
        assert abs(run[f"T_{kind}"] - 1.0) < 4 * run[f"T_{kind}_err"], run
        assert abs(run[f"T_{kind}"] - 1.0) < 0.02 and run[f"kl_{kind}"] < 2e-3
        assert run[f"z_{kind}"] == pytest.approx((run[f"T_{kind}"] - 1.0) / run[f"T_{kind}_err"])
    assert run["passed"] is True and run["contact_noise"] is True


def test_without_contact_noise_the_system_is_not_at_kT(demo):
    run = demo[1]["runs"]["without_contact_noise"]
    for kind in ("trans", "rot"):
        assert (1.0 - run[f"T_{kind}"]) > 5 * run[f"T_{kind}_err"], run
    gap = run["T_trans"] - run["T_rot"]
    assert gap > 5 * (run["T_trans_err"] ** 2 + run["T_rot_err"] ** 2) ** 0.5  # T_trans != T_rot: not an equilibrium
    assert 0.75 < run["T_trans"] < 0.9 and 0.6 < run["T_rot"] < 0.78  # about 0.82 and 0.69 kT
    assert run["passed"] is False and run["contact_noise"] is False
