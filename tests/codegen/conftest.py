import pytest

from fricgen.derive import catalogue, derive_noise
from fricgen.kernels import load_law_kernels


@pytest.fixture(scope="session")
def laws():
    return catalogue()


@pytest.fixture(scope="session")
def models(laws):
    """Derived models of every catalogue law for its calculi (the emitted ones)."""
    return {(name, c): derive_noise(law, c) for name, law in laws.items() for c in law.calculi}


@pytest.fixture(scope="session")
def kernels(laws):
    return {name: load_law_kernels(name) for name in laws}
