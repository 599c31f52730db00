"""The on-disk cache of the law-independent lemmas: keyed, atomic, and never trusted when damaged.

The prover is replaced by a counting stand-in, so these tests prove nothing expensive; that the real
facts are right is the job of test_modes and test_phase_space (they prove them without the cache).
"""

import json
import os
import threading

import pytest
import sympy as sp

from fricgen.derive.calculus import Calculus
from fricgen.derive.noise import lemma_cache, mode_proofs
from fricgen.derive.noise.mode_proofs import FACTS, Lemma


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """An empty cache folder and a prover that counts its calls (returns the facts of the calculus:
    the lemma holds with nu/mu = 1 - theta)."""
    calls = []

    def prove(mode, dim, calculus):
        calls.append((dim, calculus))
        ratio = 1 - Calculus(calculus).theta
        return Lemma(True, sp.Rational(ratio.numerator, ratio.denominator))

    monkeypatch.setenv(lemma_cache.CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setattr(mode_proofs, "zero_current", prove)
    monkeypatch.setattr(mode_proofs, "mode_facts", lambda mode, dim: dict.fromkeys(FACTS, True))
    lemma_cache.clear_memory()
    yield tmp_path / "cache", calls
    lemma_cache.clear_memory()


def entries(folder):
    return sorted(p.name for p in folder.iterdir())


def test_cold_then_warm(cache):
    folder, calls = cache
    assert lemma_cache.lemma("sliding", 3, "ito") == Lemma(True, 1)
    assert calls == [(3, "ito")]
    (entry,) = entries(folder)
    assert entry.startswith("zero_current_sliding_3d_ito-") and entry.endswith(".json")
    lemma_cache.clear_memory()  # a new process
    assert lemma_cache.lemma("sliding", 3, "ito") == Lemma(True, 1)
    assert calls == [(3, "ito")]  # read, not proven again
    assert lemma_cache.facts("rolling", 2) == dict.fromkeys(FACTS, True)
    lemma_cache.clear_memory()
    assert lemma_cache.facts("rolling", 2) == dict.fromkeys(FACTS, True)
    assert len(calls) == 1
    assert not [name for name in entries(folder) if name.endswith(".tmp")]  # atomic: no leftovers


def _entry_text(name: str, facts: dict, key: str | None = None) -> str:
    """An entry as write_entry writes it (its sha256 right), for the facts given."""
    key = lemma_cache.cache_key() if key is None else key
    return json.dumps({"key": key, "name": name, "facts": facts, "sha256": lemma_cache._digest(key, name, facts)})


@pytest.mark.parametrize(
    "damage",
    [
        "{not json",
        "[]",
        json.dumps({"key": "another", "facts": {"holds": True, "nu_over_mu": "0"}}),
        json.dumps({"facts": {"holds": True, "nu_over_mu": "0"}}),
        "KEY:" + json.dumps({"holds": "yes", "nu_over_mu": "0"}),
        "KEY:" + json.dumps({"holds": True, "nu_over_mu": "__import__('os').getcwd()"}),
        "KEY:" + json.dumps({"holds": True, "nu_over_mu": 0.5}),
        "KEY:" + json.dumps({"holds": True}),
        "UNSIGNED",  # the right facts, but no sha256 over them
        "TAMPERED",  # the right sha256, another payload
        "OTHERNAME",  # a whole entry of another lemma, renamed
    ],
)
def test_damaged_or_foreign_entries_are_proven_again(cache, damage):
    folder, calls = cache
    lemma_cache.lemma("sliding", 2, "hk")
    (entry,) = folder.iterdir()
    good = {"holds": True, "nu_over_mu": "0"}
    if damage.startswith("KEY:"):
        damage = _entry_text("zero_current_sliding_2d_hk", json.loads(damage[4:]))
    elif damage == "UNSIGNED":
        damage = json.dumps({"key": lemma_cache.cache_key(), "name": "zero_current_sliding_2d_hk", "facts": good})
    elif damage == "TAMPERED":
        data = json.loads(_entry_text("zero_current_sliding_2d_hk", good))
        damage = json.dumps({**data, "facts": {"holds": True, "nu_over_mu": "1"}})
    elif damage == "OTHERNAME":
        damage = _entry_text("zero_current_sliding_2d_ito", good)
    entry.write_text(damage)
    lemma_cache.clear_memory()
    assert lemma_cache.lemma("sliding", 2, "hk") == Lemma(True, 0)
    assert len(calls) == 2
    assert json.loads(entry.read_text())["facts"] == good  # rewritten


@pytest.mark.parametrize(
    ("name", "facts"),
    [
        ("zero_current_sliding_3d_ito", {"holds": True, "nu_over_mu": "0"}),  # the HK ratio under Itô: D = f/u would verify
        ("zero_current_sliding_3d_ito", {"holds": True, "nu_over_mu": "1/2"}),
        ("zero_current_sliding_3d_ito", {"holds": True, "nu_over_mu": None}),
        ("zero_current_sliding_3d_ito", {"holds": False, "nu_over_mu": "1"}),  # a negative fact is no source of truth either
        ("facts_sliding_3d", {}),  # no fact at all: "all true" would be vacuous
        ("facts_sliding_3d", dict.fromkeys(FACTS[1:], True)),  # one of the facts missing
        ("facts_sliding_3d", {**dict.fromkeys(FACTS, True), "extra": True}),
        ("facts_sliding_3d", {**dict.fromkeys(FACTS[1:], True), "other": True}),
        ("facts_sliding_3d", {**dict.fromkeys(FACTS, True), "isotropic": 1}),
        ("facts_sliding_3d", {**dict.fromkeys(FACTS, True), "dissipation": False}),
    ],
)
def test_vacuous_or_wrong_facts_are_proven_again(cache, name, facts):
    """An entry whose sha256 is right (a cache written by hand, or by a broken version) is still used
    only if it states what the proof establishes."""
    folder, calls = cache
    folder.mkdir()
    path = folder / f"{name}-{lemma_cache.cache_key()[:16]}.json"
    path.write_text(_entry_text(name, facts))
    if name.startswith("zero_current"):
        assert lemma_cache.lemma("sliding", 3, "ito") == Lemma(True, 1)
        assert calls == [(3, "ito")]
    else:
        assert lemma_cache.facts("sliding", 3) == dict.fromkeys(FACTS, True)
    stored = json.loads(path.read_text())["facts"]
    assert json.dumps(stored, sort_keys=True) != json.dumps(facts, sort_keys=True)  # rewritten with the proven facts


def test_the_proven_facts_are_read_back(cache):
    folder, calls = cache
    folder.mkdir()
    for calculus in ("ito", "stratonovich", "hk"):
        ratio = str(1 - Calculus(calculus).theta)
        name = f"zero_current_sliding_3d_{calculus}"
        (folder / f"{name}-{lemma_cache.cache_key()[:16]}.json").write_text(_entry_text(name, {"holds": True, "nu_over_mu": ratio}))
        assert lemma_cache.lemma("sliding", 3, calculus).holds
    assert calls == []


@pytest.mark.parametrize("kind", ["fifo", "folder", "dangling", "huge"])
def test_an_entry_that_is_not_a_small_regular_file_is_a_miss_never_a_wait(cache, kind):
    """A FIFO in place of an entry would block a plain open() forever: the read is non-blocking,
    bounded in time (a thread with a deadline) and in size."""
    folder, calls = cache
    folder.mkdir()
    path = folder / f"zero_current_sliding_3d_ito-{lemma_cache.cache_key()[:16]}.json"
    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "folder":
        path.mkdir()
    elif kind == "dangling":
        path.symlink_to(folder / "nowhere")
    else:
        path.write_text(" " * (lemma_cache.MAX_ENTRY + 1) + _entry_text("zero_current_sliding_3d_ito", {"holds": True, "nu_over_mu": "1"}))
    result = []
    reader = threading.Thread(target=lambda: result.append(lemma_cache.read_entry("zero_current_sliding_3d_ito")), daemon=True)
    reader.start()
    reader.join(10)
    assert not reader.is_alive(), "read_entry waited on a non-regular file"
    assert result == [None]
    if kind != "folder":
        assert lemma_cache.lemma("sliding", 3, "ito").holds and calls == [(3, "ito")]


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
    lemma_cache.lemma("sliding", 2, "ito")
    source = tmp_path / "phase_space.py"
    source.write_text("# edited\n")
    monkeypatch.setattr(lemma_cache, "SOURCES", (source,))
    lemma_cache.clear_memory()
    lemma_cache.lemma("sliding", 2, "ito")
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
    assert lemma_cache.lemma("sliding", 3, "stratonovich").holds
    assert lemma_cache.write_entry("x", {}) is None
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    monkeypatch.setenv(lemma_cache.CACHE_ENV, str(blocker / "cache"))
    lemma_cache.clear_memory()
    assert lemma_cache.lemma("sliding", 3, "stratonovich").holds
    assert len(calls) == 2 and not folder.exists()


def test_a_refuted_fact_is_not_stored(cache, monkeypatch):
    """Only what the proof established is kept: a lemma that fails is proven again next time."""
    folder, calls = cache
    monkeypatch.setattr(mode_proofs, "zero_current", lambda *args: calls.append(args) or Lemma(False, None))
    assert not lemma_cache.lemma("rolling", 3, "ito")
    lemma_cache.clear_memory()
    assert not lemma_cache.lemma("rolling", 3, "ito")
    assert len(calls) == 2 and (not folder.exists() or entries(folder) == [])
