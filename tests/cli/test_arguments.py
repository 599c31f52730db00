"""The command line's handling of arguments and outputs: negative numbers as values, errors named by
flags, valid JSON, output folders checked without writing, and thermostat-check's --kT."""

import importlib
import json
import math

import pytest

from fricgen.app.cli import main
from fricgen.app.cli.arguments import join_negative_values
from fricgen.app.run.outputs import check_folder, dumps
from fricgen.errors import ConfigError


def test_a_negative_number_after_a_flag_is_its_value():
    words = ["bcd", "--dt", "-1e-3", "--U0", "-inf", "--n", "-2", "--json", "--out", "-x", "--", "-1"]
    assert join_negative_values(words) == ["bcd", "--dt=-1e-3", "--U0=-inf", "--n=-2", "--json", "--out", "-x", "--", "-1"]
    assert join_negative_values(["noise", "linear", "--u", "-1,2", "--r=1", "-3"]) == ["noise", "linear", "--u=-1,2", "--r=1", "-3"]


def test_json_output_has_null_where_a_number_is_not_finite():
    text = dumps({"chi2": math.inf, "rows": [1.0, math.nan, (2.0, -math.inf)], "n": 3, "name": "x"})
    assert json.loads(text) == {"chi2": None, "rows": [1.0, None, [2.0, None]], "n": 3, "name": "x"}


def test_output_folders_are_checked_without_writing(tmp_path):
    check_folder(tmp_path / "new" / "deeper", "--out")  # creatable
    (tmp_path / "file").write_text("x")
    for folder in (tmp_path / "file", tmp_path / "file" / "sub"):
        with pytest.raises(ConfigError, match="is a file, not a folder") as caught:
            check_folder(folder, "--out")
        assert caught.value.key == "--out"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]


def test_thermostat_check_passes_kT_to_the_check(monkeypatch, capsys):
    module = importlib.import_module("fricgen.app.studies.thermostat_check")  # fricgen.app exports a function of that name
    seen = []

    def fake_run(check, law):
        seen.append(check)
        raise KeyboardInterrupt  # stop before the simulation: the exit status of Ctrl-C

    monkeypatch.setattr(module, "passive_run", fake_run)
    assert main(["thermostat-check", "linear", "--kT", "2.5", "--n", "64", "--phi", "0.5", "--dim", "3"]) == 130
    assert capsys.readouterr().err == "fricgen thermostat-check: interrupted\n"
    check = seen[0]
    assert (check.thermostat.kT, check.size, check.fraction, check.dim) == (2.5, 64, 0.5, 3)


def test_demo_replaces_an_earlier_demo_but_not_another_commands_summary(tmp_path, monkeypatch):
    from fricgen.app.studies import demo

    monkeypatch.setattr(demo, "passive_run", lambda *args, **kwargs: pytest.fail("the check must come first"))
    (tmp_path / "summary.json").write_text(json.dumps({"runs": {"with_contact_noise": {}}}))
    demo.check_demo_folder(tmp_path)  # an earlier demo: replaced
    (tmp_path / "summary.json").write_text(json.dumps({"steps": 600}))
    with pytest.raises(ConfigError, match="summary.json that the demo did not write"):
        demo.run_demo(tmp_path)
