"""The kernel ABI: the signatures fricgen.derive.driver prints are the Numba types declared in fricgen.kernels,
and every generated kernel is compiled for exactly its type (so engines compiled for the types take
any law's or potential's kernels as first-class functions)."""

import numba
import numpy as np
import pytest
from numba.core.dispatcher import Dispatcher
from numba.core.sigutils import normalize_signature

from fricgen.derive.driver import CONTACT_SIGNATURE, GENERATED, SIGNATURES
from fricgen.kernels import (
    CONTACT_KERNEL,
    FIELD_KERNEL,
    FRICTION_KERNEL,
    NOISE_KERNEL,
    SCALAR_KERNEL,
    load_law_kernels,
    load_potential,
    no_weight,
)

#: tabulate_<c>(mobilities, kT, params) -> params with the noise tables appended (called by Simulation
#: at its start, not by the compiled engine).
TABLE_BUILDER = numba.types.float64[::1](numba.types.float64[::1], numba.types.float64, numba.types.float64[::1])
#: The ABI type of each argument list of fricgen.derive.driver.SIGNATURES ("w, r, params": the private
#: factor h(w, r) of a tabulated law, f = h g(u), inlined into its noise kernels).
BY_ARGUMENTS = {
    "r, params": SCALAR_KERNEL,
    "w, r, params": numba.types.FunctionType(numba.types.float64(numba.types.float64, numba.types.float64, numba.types.float64[::1])),
    "x, params": SCALAR_KERNEL,
    "u, w, r, params": FRICTION_KERNEL,
    "u, w, r, mu, kT, params": NOISE_KERNEL,
    "xs, params, out": FIELD_KERNEL,
}


def abi_of(name: str):
    """The ABI type a generated kernel of this name must have."""
    if name in ("weight", "energy", "force"):
        return SCALAR_KERNEL
    if name in ("friction", "friction_over_u", "friction_slope"):
        return FRICTION_KERNEL
    if name.startswith(("noise_amplitude_", "noise_sqrt_")):
        return NOISE_KERNEL
    if name.startswith("contact_"):
        return CONTACT_KERNEL
    if name == "force_field":
        return FIELD_KERNEL
    if name.startswith("tabulate_"):
        return numba.types.FunctionType(TABLE_BUILDER)
    raise AssertionError(f"generated kernel {name} has no ABI type: add it to fricgen.kernels and to this test")


def parse(signature: str):
    """A signature string as Numba's njit reads it, as a typing Signature."""
    arguments, result = normalize_signature(signature)
    return result(*arguments)


def generated_modules(kind: str) -> list[str]:
    return sorted(p.stem for p in (GENERATED / kind).glob("*.py") if p.stem != "__init__")


def kernels_of(module) -> dict:
    """The public compiled kernels defined in a generated module (helpers such as _gaussian_tail are
    private; erfcx is imported from fricgen.generated.special)."""
    return {
        name: value
        for name, value in vars(module).items()
        if isinstance(value, Dispatcher) and not name.startswith("_") and value.py_func.__module__ == module.__name__
    }


def test_every_printed_signature_has_an_abi_type():
    assert set(SIGNATURES) == set(BY_ARGUMENTS)


@pytest.mark.parametrize("arguments", sorted(SIGNATURES))
def test_printed_signatures_are_the_abi(arguments):
    assert parse(SIGNATURES[arguments]) == BY_ARGUMENTS[arguments].signature


def test_printed_contact_signature_is_the_abi():
    assert parse(CONTACT_SIGNATURE) == CONTACT_KERNEL.signature


@pytest.mark.parametrize("name", generated_modules("laws"))
def test_law_kernels_are_compiled_for_exactly_their_abi_type(name):
    law = load_law_kernels(name)
    kernels = kernels_of(law.module)
    expected = {"friction", "friction_over_u", "friction_slope"} | {
        f"{k}_{c}" for c in law.calculi for k in ("noise_amplitude", "noise_sqrt", "contact")
    }
    expected |= {f"tabulate_{c}" for c in law.calculi if hasattr(law.module, f"tabulate_{c}")}  # laws with noise tables
    assert set(kernels) == expected | ({"weight"} if law.has_weight else set())
    for kernel_name, kernel in kernels.items():
        signature = abi_of(kernel_name).signature
        assert kernel.nopython_signatures == [signature], kernel_name
        assert kernel.signatures == [signature.args], kernel_name


@pytest.mark.parametrize("name", generated_modules("potentials"))
def test_potential_kernels_are_compiled_for_exactly_their_abi_type(name):
    module = load_potential(name)
    kernels = kernels_of(module)
    assert {"energy", "force"} <= set(kernels) <= {"energy", "force", "force_field"}
    for kernel_name, kernel in kernels.items():
        signature = abi_of(kernel_name).signature
        assert kernel.nopython_signatures == [signature], kernel_name


def test_no_weight_is_a_scalar_kernel():
    assert no_weight.nopython_signatures == [SCALAR_KERNEL.signature]
    assert no_weight(0.5, np.zeros(1)) == 1.0


def test_one_compiled_engine_takes_any_law_through_the_abi():
    """A function compiled once for CONTACT_KERNEL calls the contact kernels of different laws."""

    @numba.njit(numba.types.UniTuple(numba.float64, 2)(CONTACT_KERNEL, numba.float64[::1]))
    def engine(contact, params):
        return contact(0.3, 2.0, 1.0, 7.0, 1.0, params)

    for name in ("linear", "coulomb_newton"):
        law = load_law_kernels(name)
        params = law.parameters()
        assert engine(law.contact("ito"), params) == law.contact("ito")(0.3, 2.0, 1.0, 7.0, 1.0, params)
    assert len(engine.nopython_signatures) == 1
