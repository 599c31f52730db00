import os

import pytest

from fricgen.derive import catalogue, derive_noise, verify
from fricgen.derive.noise import lemma_cache


@pytest.fixture(scope="session", autouse=True)
def lemma_cache_folder(tmp_path_factory):
    """The proofs run against a fresh lemma cache (fricgen.derive.noise.lemma_cache), not the user's, unless
    FRICGEN_CACHE is set (e.g. to reuse a warm cache while developing). The lemmas are then proven
    once per session: test_phase_space proves them anyway, and the in-process cache shares them."""
    chosen = os.environ.get(lemma_cache.CACHE_ENV)
    if not chosen:
        os.environ[lemma_cache.CACHE_ENV] = str(tmp_path_factory.mktemp("lemma-cache"))
    lemma_cache.clear_memory()
    yield os.environ[lemma_cache.CACHE_ENV]
    if not chosen:
        os.environ.pop(lemma_cache.CACHE_ENV, None)
    lemma_cache.clear_memory()


@pytest.fixture(scope="session")
def laws():
    return catalogue()


@pytest.fixture(scope="session")
def reports(laws):
    """Verification report of every catalogue law for each calculus it supports."""
    return {(name, c): verify(derive_noise(law, c)) for name, law in laws.items() for c in law.calculi}
