"""fricgen bcd: profile CSV, plot and JSON summary; bad input gets one clear message."""

import json

import numpy as np

from fricgen.app.cli import main


def test_bcd_writes_profile_plot_and_summary(tmp_path, capsys):
    out = tmp_path / "rods"
    args = ["bcd", "--n", "20", "--time", "0.5", "--equilibrate", "2", "--dt", "1e-4", "--bins", "20", "--out", str(out), "--json"]
    assert main(args) == 0
    summary = json.loads(capsys.readouterr().out)
    assert {"max_abs_dev", "l1_dev_over_rho", "chi2_per_dof", "steps", "seconds", "contact_ratio"} <= summary.keys()
    assert summary["steps"] == 5000 and summary["l1_dev_over_rho"] < 0.1
    table = np.genfromtxt(out / "profile.csv", delimiter=",", names=True)
    assert table.dtype.names[:4] == ("x", "rho", "rho_err", "rho2_contact") and table.size == 20
    np.testing.assert_allclose(table["x"], (np.arange(20) + 0.5) / 20)
    assert (out / "profile.png").stat().st_size > 10_000


def test_bcd_with_the_metropolis_test_reports_its_rejections(tmp_path, capsys):
    """--drift-scheme metropolis: the fraction of steps rejected, in the summary and the printed line; the other
    schemes have none."""
    args = ["bcd", "--n", "140", "--sigma", "0.5", "--dt", "1e-3", "--time", "0.2", "--equilibrate", "0.1", "--out"]
    assert main([*args, str(tmp_path / "m"), "--drift-scheme", "metropolis"]) == 0
    assert "of the steps rejected" in capsys.readouterr().out
    assert main([*args, str(tmp_path / "j"), "--drift-scheme", "metropolis", "--json"]) == 0
    assert 0.1 < json.loads(capsys.readouterr().out)["rejected_fraction"] < 0.3  # dense rings at 1e-3: about 0.2
    assert main([*args, str(tmp_path / "e"), "--json"]) == 0
    assert "rejected_fraction" not in json.loads(capsys.readouterr().out)


def test_bcd_sticky_reports_the_representation_error(tmp_path, capsys):
    args = ["bcd", "--n", "20", "--gamma", "1", "--time", "0.1", "--equilibrate", "0.5", "--dt", "2e-5", "--out", str(tmp_path), "--json"]
    assert main(args) == 0
    summary = json.loads(capsys.readouterr().out)
    assert 0 < summary["representation_error_max"] < 0.05 and "contact_ratio" not in summary


def test_bcd_baxter_limit_compares_the_bonded_density(tmp_path, capsys):
    """--eps 0: the sticky boundary against the exact Baxter profile, its bonded density as the contact."""
    args = ["bcd", "--n", "20", "--gamma", "10", "--eps", "0", "--time", "0.2", "--equilibrate", "0.2", "--out", str(tmp_path), "--json"]
    assert main(args) == 0
    summary = json.loads(capsys.readouterr().out)
    assert "representation_error_max" not in summary and abs(summary["contact_ratio"] - 1) < 5 * summary["contact_ratio_err"]
    assert summary["l1_dev_over_rho"] < 0.1 and summary["config"]["eps"] == 0


def test_bcd_in_another_generated_field(tmp_path, capsys):
    args = ["bcd", "--field", "ratchet", "--field-param", "a=1.5", "--n", "20", "--time", "0.2", "--dt", "1e-4", "--out", str(tmp_path)]
    assert main([*args, "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["config"]["field"] == "ratchet" and summary["config"]["field_params"] == {"a": 1.5}
    assert summary["l1_dev_over_rho"] < 0.1


def test_bcd_with_a_generated_pair_potential(tmp_path, capsys):
    wca = ["--pair", "wca", "--pair-param", "sigma=0.55", "--pair-range", "0.12"]
    assert main(["bcd", *wca, "--n", "20", "--time", "0.1", "--dt", "2e-5", "--out", str(tmp_path), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["config"]["pair"] == "wca" and "contact_ratio" not in summary and summary["l1_dev_over_rho"] < 0.1


def test_bcd_refuses_bad_input(tmp_path, capsys):
    assert main(["bcd", "--n", "300", "--out", str(tmp_path / "x")]) == 2
    assert "close packing" in capsys.readouterr().err
    assert main(["bcd", "--time", "-1", "--out", str(tmp_path / "y")]) == 2
    assert "--time" in capsys.readouterr().err
    assert main(["bcd", "--field", "sawtooth", "--out", str(tmp_path / "z")]) == 2
    assert "no generated potential 'sawtooth'" in capsys.readouterr().err
    assert main(["bcd", "--field-param", "b=1", "--out", str(tmp_path / "w")]) == 2
    assert "no parameter(s) ['b']" in capsys.readouterr().err
    assert main(["bcd", "--pair", "wca", "--pair-range", "0.01", "--out", str(tmp_path / "v")]) == 2
    assert "not zero beyond" in capsys.readouterr().err
    assert not any((tmp_path / name).exists() for name in "xyzwv")
