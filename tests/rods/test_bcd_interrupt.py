"""BCD in chunks: the steps of one call split into compiled calls of CHUNK_STEPS give the same rods
bit for bit, and Ctrl-C stops ``fricgen bcd`` between two of them (exit status 130, nothing written)."""

from __future__ import annotations

import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from fricgen.rods import simulation
from fricgen.rods.config import CONTACT_LAYERS, rod_config
from fricgen.rods.simulation import RodSimulation


@pytest.mark.parametrize("layer", CONTACT_LAYERS)
def test_any_chunking_gives_the_same_rods_bit_for_bit(layer, monkeypatch):
    config = rod_config(n=20, length=20.0, sigma=0.5, dt=1e-4, replicas=2, bins=10, seed=5, contact_layer=layer)
    whole = RodSimulation(config)
    profiles = whole.run(1000)
    monkeypatch.setattr(simulation, "CHUNK_STEPS", 300)  # 300, 300, 300, 100
    chunked = RodSimulation(config)
    pieces = chunked.run(1000)
    assert chunked.step == whole.step == 1000
    assert np.array_equal(chunked.positions, whole.positions)
    assert np.array_equal(pieces.rho, profiles.rho) and np.array_equal(pieces.contact, profiles.contact, equal_nan=True)


def test_the_monte_carlo_start_in_chunks_is_the_same_bit_for_bit(monkeypatch):
    """The start's sweeps run in compiled calls of CHUNK_MOVES moves (so Ctrl-C stops it): any chunking gives
    the same rods and acceptance."""
    config = rod_config(n=20, length=20.0, sigma=0.5, replicas=2, bins=10, seed=5, start_sweeps=250)
    whole = RodSimulation(config)
    monkeypatch.setattr(simulation, "CHUNK_MOVES", 20 * 60)  # 60, 60, 60, 60, 10 sweeps
    chunked = RodSimulation(config)
    assert chunked.sweep == whole.sweep == 250 and chunked.acceptance == pytest.approx(whole.acceptance, rel=1e-12)
    assert np.array_equal(chunked.positions, whole.positions)


def _sigint_as_on_a_terminal():
    """In the child: SIGINT at its default, as under a terminal. A shell's background job inherits it
    ignored, and Python then keeps it ignored (no KeyboardInterrupt): the test would not test Ctrl-C."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def test_ctrl_c_stops_bcd_between_chunks(tmp_path):
    """A run of 2e8 steps per ring (many minutes) ends within seconds of SIGINT, with nothing written."""
    command = [sys.executable, "-m", "fricgen", "bcd", "--replicas", "2"]
    warm = subprocess.run([*command, "--time", "1", "--out", str(tmp_path / "warm")], capture_output=True, text=True)
    assert warm.returncode == 0, warm.stderr  # compiled and cached: the run below starts stepping within seconds
    out = tmp_path / "bcd"
    process = subprocess.Popen(
        [*command, "--time", "20000", "--out", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=_sigint_as_on_a_terminal,
    )
    time.sleep(15)
    assert process.poll() is None, process.communicate()
    sent = time.monotonic()
    process.send_signal(signal.SIGINT)
    try:
        _, stderr = process.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        process.kill()
        process.communicate()
        pytest.fail("fricgen bcd kept running for 60 s after SIGINT")
    assert process.returncode == 130, stderr
    assert time.monotonic() - sent < 20
    assert stderr.strip().endswith("interrupted") and "Traceback" not in stderr
    assert not out.exists() or not any(out.iterdir())
