"""The kernel layer: the kernel ABI, and the one loader of generated kernels, refused when stale.

The ABI is the Numba function type of each kind of generated kernel (derive.emit compiles every
kernel for exactly its type, tests/codegen/test_abi.py checks it); the engines take kernels as
first-class functions of these types, so one compiled engine serves every law and potential:

- ``SCALAR_KERNEL``: ``weight(r, params)``, a potential's ``energy(x, params)`` and ``force(x, params)``;
- ``FRICTION_KERNEL``: ``friction(u, w, r, params)`` and ``friction_over_u(u, w, r, params)``;
- ``NOISE_KERNEL``: ``noise_amplitude_<c>(u, w, r, mu, kT, params)`` and ``noise_sqrt_<c>(...)``;
- ``CONTACT_KERNEL``: ``contact_<c>(u, w, r, mu, kT, params)`` -> ``(f/u, sqrt(D))``;
- ``FIELD_KERNEL``: ``force_field(xs, params, out)`` of an external potential (out[i] = force(xs[i])).

``params`` is a contiguous float64 array. :func:`no_weight` is the weight of laws without one.

Generated kernels carry the hash of their source: a law's kernels that of its law file (and of
derive/potentials.py when its weight is a potential), a potential's that of derive/potentials.py.
If the source was edited since, loading fails with the command that regenerates them. After a
regeneration in the same process (a notebook), the module is reloaded, so the new kernels take
effect at once. SymPy is never imported here.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType

import numba
import numpy as np
from numba import types

from derive.lawdata import CATALOGUE, POSITIVE, Interval, LawFileError, potential_source_hash, read_law_data, source_hash, weight_potential

from .errors import ConfigError, KernelError

# --- the kernel ABI --------------------------------------------------------------------------------

_F = types.float64
_V = types.Array(_F, 1, "C")  # float64[::1]: params, and the positions and forces of force_field

#: weight(r, params), energy(x, params), force(x, params) -> float64.
SCALAR_KERNEL = types.FunctionType(_F(_F, _V))
#: friction(u, w, r, params), friction_over_u(u, w, r, params) -> float64.
FRICTION_KERNEL = types.FunctionType(_F(_F, _F, _F, _V))
#: noise_amplitude_<c>(u, w, r, mu, kT, params) -> D, noise_sqrt_<c>(...) -> sqrt(D).
NOISE_KERNEL = types.FunctionType(_F(_F, _F, _F, _F, _F, _V))
#: contact_<c>(u, w, r, mu, kT, params) -> (f/u, sqrt(D)).
CONTACT_KERNEL = types.FunctionType(types.UniTuple(_F, 2)(_F, _F, _F, _F, _F, _V))
#: force_field(xs, params, out): out[i] = force(xs[i], params).
FIELD_KERNEL = types.FunctionType(types.void(_V, _V, _V))


@numba.njit(SCALAR_KERNEL.signature, cache=True)
def no_weight(r, params):
    """w = 1 for laws without a distance weight (friction acts within the potential's range)."""
    return 1.0


# --- law kernels -----------------------------------------------------------------------------------


@dataclass(frozen=True)
class LawKernels:
    """Compiled kernels of one friction law (see the generated module for the equations).

    Kernel arguments: ``(u, w, r, p)`` for ``friction`` and ``friction_over_u``, ``(r, p)`` for
    ``weight``, ``(u, w, r, mu, kT, p)`` for the noise kernels, with ``p`` from
    :meth:`parameters`.
    """

    name: str
    module: ModuleType

    @property
    def parameter_names(self) -> tuple[str, ...]:
        return self.module.PARAMETERS

    @property
    def calculi(self) -> tuple[str, ...]:
        return self.module.CALCULI

    @property
    def has_weight(self) -> bool:
        return self.module.HAS_WEIGHT

    @property
    def ranges(self) -> dict[str, Interval]:
        """The admissible values of each parameter (from the law file; the positive reals by default)."""
        ranges = getattr(self.module, "RANGES", None) or [()] * len(self.parameter_names)  # () : Interval() = POSITIVE
        return {name: Interval(*bounds) for name, bounds in zip(self.parameter_names, ranges)}

    def parameters(self, **overrides: float) -> np.ndarray:
        """Parameter values (float64 array) from the defaults and named overrides, each checked against
        its range (ConfigError naming the parameter and the range otherwise)."""
        values = dict(zip(self.parameter_names, self.module.DEFAULTS))
        ranges = self.ranges
        for key, value in overrides.items():
            if key not in values:
                names = list(self.parameter_names)
                raise ConfigError(f"law.parameters.{key}", f"law {self.name} has no parameter {key!r}", f"it has {names}")
            allowed = ranges[key]
            if allowed == POSITIVE and not (np.isfinite(value) and value > 0):
                raise ConfigError(f"law.parameters.{key}", f"must be positive and finite, got {value}", "give a positive value")
            if not np.isfinite(value):
                raise ConfigError(f"law.parameters.{key}", f"must be finite and in {allowed}, got {value}", f"give a value in {allowed}")
            if value not in allowed:
                raise ConfigError(
                    f"law.parameters.{key}",
                    f"must be in {allowed}, got {value}",
                    f"give a value in {allowed} (the range law {self.name} declares for {key})",
                )
            values[key] = float(value)
        return np.array([values[n] for n in self.parameter_names], dtype=np.float64)

    def _calculus(self, calculus: str) -> str:
        if calculus not in self.calculi:
            raise KernelError(f"law {self.name} has no kernels for the {calculus!r} calculus; it has {list(self.calculi)}")
        return calculus

    def noise_amplitude(self, calculus: str):
        """D(u, w, r, mu, kT, p) for the calculus."""
        return getattr(self.module, f"noise_amplitude_{self._calculus(calculus)}")

    def noise_sqrt(self, calculus: str):
        """sqrt(D)(u, w, r, mu, kT, p) for the calculus."""
        return getattr(self.module, f"noise_sqrt_{self._calculus(calculus)}")

    def contact(self, calculus: str):
        """(f/u, sqrt(D))(u, w, r, mu, kT, p) for the calculus."""
        return getattr(self.module, f"contact_{self._calculus(calculus)}")

    @property
    def friction(self):
        return self.module.friction

    @property
    def friction_over_u(self):
        return self.module.friction_over_u

    @property
    def weight(self):
        if not self.has_weight:
            raise KernelError(f"law {self.name} has no weight w(r)")
        return self.module.weight


def _import(module_name: str, missing: Callable[[], KernelError], what: str, reload: bool = False) -> ModuleType:
    """Import (or reload) a generated module. Its absence raises ``missing()``; a dependency that cannot
    be imported (numba not installed, a broken generated/special.py) a KernelError that says so."""
    try:
        return importlib.reload(sys.modules[module_name]) if reload else importlib.import_module(module_name)
    except ModuleNotFoundError as error:
        if error.name is None or module_name == error.name or module_name.startswith(error.name + "."):
            raise missing() from error
        raise KernelError(f"{error.name} is not installed: {what} need it ({error}); install it, e.g. pip install {error.name}") from error
    except ImportError as error:
        raise KernelError(f"cannot import {what} ({module_name}): {error}") from error


def load_law_kernels(name: str, catalogue: Path = CATALOGUE) -> LawKernels:
    """Kernels of the catalogue law ``name``; raises KernelError if missing or stale."""
    path = Path(catalogue) / f"{name}.toml"
    if not path.exists():
        available = sorted(p.stem for p in Path(catalogue).glob("*.toml"))
        raise KernelError(f"no law {name!r} in the catalogue {catalogue}; it has {available}")
    try:
        data = read_law_data(path)
        digest = source_hash(data)
    except LawFileError as error:
        raise KernelError(str(error)) from error
    module_name = f"generated.laws.{name}"

    def missing():
        return KernelError(f"no generated kernels for law {name}: run `fricgen generate {name}`")

    module = _import(module_name, missing, f"the kernels of law {name}")
    if module.SOURCE_HASH != digest:
        module = _import(module_name, missing, f"the kernels of law {name}", reload=True)  # regenerated since it was imported?
    if module.SOURCE_HASH != digest:
        changed = str(path) if weight_potential(data) is None else f"{path} or derive/potentials.py (its weight {data['weight']})"
        raise KernelError(
            f"the kernels of law {name} are stale: {changed} changed after they were generated; run `fricgen generate {name}`"
        )
    return LawKernels(name, module)


def load_potential(name: str) -> ModuleType:
    """Generated potential module (energy(x, params), force(x, params), PARAMETERS, DEFAULTS; external
    potentials also force_field(xs, params, out)); raises KernelError if missing or stale."""
    module_name = f"generated.potentials.{name}"

    def missing():
        import generated.potentials

        there = sorted(p.stem for p in Path(generated.potentials.__file__).parent.glob("*.py") if p.stem != "__init__")
        return KernelError(f"no generated potential {name!r} (there are {there}): a new one needs `fricgen generate`")

    module = _import(module_name, missing, f"the kernels of potential {name}")
    digest = potential_source_hash(name)
    if getattr(module, "SOURCE_HASH", None) != digest:
        module = _import(module_name, missing, f"the kernels of potential {name}", reload=True)  # regenerated since it was imported?
    if getattr(module, "SOURCE_HASH", None) != digest:
        raise KernelError(
            f"the kernels of potential {name} are stale: derive/potentials.py changed after they were generated; run `fricgen generate`"
        )
    return module


__all__ = [
    "CONTACT_KERNEL",
    "FIELD_KERNEL",
    "FRICTION_KERNEL",
    "NOISE_KERNEL",
    "SCALAR_KERNEL",
    "KernelError",
    "LawKernels",
    "load_law_kernels",
    "load_potential",
    "no_weight",
]
