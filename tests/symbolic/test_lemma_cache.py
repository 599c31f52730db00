"""The on-disk cache of the law-independent lemmas: keyed, atomic, and never trusted when damaged.

The prover is replaced by a counting stand-in, so these tests prove nothing expensive; that the real
facts are right is test_phase_space's job (it proves them without the cache).
"""

import json

import pytest
import sympy as sp
from fricgen.derive.noise import lemma_cache, phase_space


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """An empty cache folder and a prover that counts its calls (returns the Itô facts)."""
    calls = []

    def prove(dim, calculus):
        calls.append((dim, calculus))
        return phase_space.Lemma(True, sp.Integer(1))

    monkeypatch.setenv(lemma_cache.CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setattr(phase_space, "zero_current_lemma", prove)
    monkeypatch.setattr(phase_space, "covariance_identities", lambda dim: {"sigma_hat": True})
    lemma_cache.clear_memory()
    yield tmp_path / "cache", calls
    lemma_cache.clear_memory()


def entries(folder):
    return sorted(p.name for p in folder.iterdir())


def test_cold_then_warm(cache):
    folder, calls = cache
    assert lemma_cache.zero_current(3, "ito") == phase_space.Lemma(True, 1)
    assert calls == [(3, "ito")]
    (entry,) = entries(folder)
    assert entry.startswith("zero_current_3d_ito-") and entry.endswith(".json")
    lemma_cache.clear_memory()  # a new process
    assert lemma_cache.zero_current(3, "ito") == phase_space.Lemma(True, 1)
    assert calls == [(3, "ito")]  # read, not proven again
    assert lemma_cache.covariance(2) == {"sigma_hat": True}
    lemma_cache.clear_memory()
    assert lemma_cache.covariance(2) == {"sigma_hat": True}
    assert not [name for name in entries(folder) if name.endswith(".tmp")]  # atomic: no leftovers


@pytest.mark.parametrize(
    "damage",
    [
        "{not json",
        "[]",
        json.dumps({"key": "another", "facts": {"holds": True, "nu_over_mu": "1"}}),
        json.dumps({"facts": {"holds": True, "nu_over_mu": "1"}}),
        "KEY:" + json.dumps({"holds": "yes", "nu_over_mu": "1"}),
        "KEY:" + json.dumps({"holds": True, "nu_over_mu": "__import__('os').getcwd()"}),
        "KEY:" + json.dumps({"holds": True, "nu_over_mu": 0.5}),
        "KEY:" + json.dumps({"holds": True}),
    ],
)
def test_damaged_or_foreign_entries_are_proven_again(cache, damage):
    folder, calls = cache
    lemma_cache.zero_current(2, "hk")
    (entry,) = folder.iterdir()
    if damage.startswith("KEY:"):
        damage = json.dumps({"key": lemma_cache.cache_key(), "facts": json.loads(damage[4:])})
    entry.write_text(damage)
    lemma_cache.clear_memory()
    assert lemma_cache.zero_current(2, "hk") == phase_space.Lemma(True, 1)
    assert len(calls) == 2
    assert json.loads(entry.read_text())["facts"] == {"holds": True, "nu_over_mu": "1"}  # rewritten


def test_key_follows_sources_generator_and_sympy(cache, tmp_path, monkeypatch):
    first = lemma_cache.cache_key()
    source = tmp_path / "phase_space.py"
    source.write_text("# a proof\n")
    for change in (
        lambda: monkeypatch.setattr(lemma_cache, "SOURCES", (source,)),
        lambda: source.write_text("# another proof\n"),
        lambda: monkeypatch.setattr(lemma_cache, "GENERATOR_VERSION", lemma_cache.GENERATOR_VERSION + 1),
        lambda: monkeypatch.setattr(lemma_cache.sp, "__version__", "0.0.1"),
    ):
        change()
        lemma_cache.clear_memory()
        second = lemma_cache.cache_key()
        assert second != first
        first = second


def test_line_ends_do_not_change_the_key(cache, tmp_path, monkeypatch):
    source = tmp_path / "phase_space.py"
    monkeypatch.setattr(lemma_cache, "SOURCES", (source,))
    source.write_bytes(b"a\nb\n")
    lf = lemma_cache.cache_key()
    lemma_cache.clear_memory()
    source.write_bytes(b"a\r\nb\r\n")
    assert lemma_cache.cache_key() == lf


def test_a_changed_source_is_a_cache_miss(cache, tmp_path, monkeypatch):
    folder, calls = cache
    lemma_cache.zero_current(2, "ito")
    source = tmp_path / "phase_space.py"
    source.write_text("# edited\n")
    monkeypatch.setattr(lemma_cache, "SOURCES", (source,))
    lemma_cache.clear_memory()
    lemma_cache.zero_current(2, "ito")
    assert len(calls) == 2 and len(entries(folder)) == 2


def test_folder_choice(monkeypatch, tmp_path):
    monkeypatch.setenv(lemma_cache.CACHE_ENV, str(tmp_path / "mine"))
    assert lemma_cache.cache_folder() == tmp_path / "mine"
    monkeypatch.setenv(lemma_cache.CACHE_ENV, "off")
    assert lemma_cache.cache_folder() is None
    monkeypatch.delenv(lemma_cache.CACHE_ENV)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert lemma_cache.cache_folder() == tmp_path / "xdg" / "fricgen"
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert lemma_cache.cache_folder() == tmp_path / "home" / ".cache" / "fricgen"


def test_switched_off_or_unwritable_cache_still_proves(cache, monkeypatch, tmp_path):
    folder, calls = cache
    monkeypatch.setenv(lemma_cache.CACHE_ENV, "off")
    assert lemma_cache.zero_current(3, "stratonovich").holds
    assert lemma_cache.write_entry("x", {}) is None
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    monkeypatch.setenv(lemma_cache.CACHE_ENV, str(blocker / "cache"))
    lemma_cache.clear_memory()
    assert lemma_cache.zero_current(3, "stratonovich").holds
    assert len(calls) == 2 and not folder.exists()
