import pytest

from derive import catalogue, derive_noise, verify


@pytest.fixture(scope="session")
def laws():
    return catalogue()


@pytest.fixture(scope="session")
def reports(laws):
    """Verification report of every catalogue law for each calculus it supports."""
    return {(name, c): verify(derive_noise(law, c)) for name, law in laws.items() for c in law.calculi}
