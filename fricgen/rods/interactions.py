"""The interactions of rods: the external field and the neighbour force, from generated kernels.

The field is any generated external potential U(x; U0, lambda, ...) (derive/law/potentials.py: periodic
with period lambda, checked symbolically when it is generated), the cosine (B-21) by default. The
neighbour interaction is the sticky contact of the delta_eps representation (B-31/32; gamma = 0:
hard rods) or any generated pair potential of range below 2 sigma (B-28). The stability condition
of a continuous force is mu max|f| dt << eps (B-33; docs/physics.md#brownian-cluster-dynamics).
"""

from __future__ import annotations

from collections.abc import Callable
from types import ModuleType

import numpy as np

from ..errors import ConfigError
from ..kernels import load_potential
from .config import RodModel


def _parameters(module: ModuleType, given: dict[str, float], fixed: dict[str, float], key: str) -> np.ndarray:
    """Parameter values of a generated module in the order of its PARAMETERS: ``fixed`` (where it has
    them), else ``given`` (the configuration's ``key``), else its defaults."""
    unknown = sorted(set(given) - set(module.PARAMETERS))
    if unknown:
        raise ConfigError(key, f"{module.NAME!r} has no parameter(s) {unknown}; its parameters are {module.PARAMETERS}", "fix the names")
    values = dict(zip(module.PARAMETERS, module.DEFAULTS)) | given | fixed
    return np.array([float(values[name]) for name in module.PARAMETERS])


def on_arrays(kernel: Callable[[float, np.ndarray], float], params: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    """A scalar generated kernel f(x, params) as a function of arrays of x (the exact theory's input)."""
    return np.vectorize(lambda x: kernel(float(x), params), otypes=[float])


def field_kernels(model: RodModel) -> tuple[ModuleType, np.ndarray]:
    """The generated external potential of a configuration and its parameter values: U0 and lambda
    from U0 and wavelength, the others from field_params or its defaults.

    Parameters
    ----------
    model : RodModel
        The rods' model (``field``, ``U0`` [kT], ``wavelength``, ``field_params``).

    Returns
    -------
    tuple[ModuleType, np.ndarray]
        The generated module (``energy``, ``force``, ``force_field``) and its parameter values.

    Raises
    ------
    ConfigError
        When ``field`` names a pair potential, or a parameter is unknown or out of range.
    """
    module = load_potential(model.field)
    if not hasattr(module, "force_field"):
        raise ConfigError(
            "field", f"{model.field!r} is a pair potential, not an external field U(x)", "name an external field, e.g. cosine"
        )
    return module, _parameters(module, model.field_params, {"U0": model.U0, "lambda": model.wavelength}, "model.field_params")


def field_energy(model: RodModel) -> Callable[[np.ndarray], np.ndarray]:
    """U(x) of the configuration's field, for arrays of positions.

    Parameters
    ----------
    model : RodModel
        The rods' model.

    Returns
    -------
    Callable[[np.ndarray], np.ndarray]
        A function from positions [lambda] to energies [kT].
    """
    module, params = field_kernels(model)
    return on_arrays(module.energy, params)


def pair_kernels(model: RodModel) -> tuple[ModuleType, np.ndarray, float]:
    """The interaction of neighbours beyond the hard core: the sticky contact (B-32, a = eps; gamma = 0:
    V = 0, hard rods) unless ``pair`` names another generated pair potential (B-28), with kT from the
    config; that one is checked to vanish on [sigma + a, 2 sigma] (neighbours only interact).

    Parameters
    ----------
    model : RodModel
        The rods' model.

    Returns
    -------
    tuple[ModuleType, np.ndarray, float]
        The generated module, its parameter values and the range a of the gap (V = 0 for
        r ≥ σ + a) [lambda].

    Raises
    ------
    ConfigError
        When ``pair`` names an external field, or its potential does not vanish beyond σ + a.
    """
    c = model
    if c.pair is None:
        return load_potential("sticky"), np.array([c.gamma, c.p, c.eps, c.sigma, c.kT]), c.eps
    module = load_potential(c.pair)
    if hasattr(module, "force_field"):
        raise ConfigError("pair", f"{c.pair!r} is an external field, not a pair potential V(r)", "name a pair potential, e.g. wca")
    params = _parameters(module, c.pair_params, {"kT": c.kT} if "kT" in module.PARAMETERS else {}, "model.pair_params")
    beyond = c.sigma + c.pair_range + (c.sigma - c.pair_range) * np.linspace(0.0, 1.0, 401)[1:] ** 2
    if any(module.energy(r, params) != 0.0 or module.force(r, params) != 0.0 for r in beyond):
        raise ConfigError(
            "pair_range",
            f"pair potential {c.pair!r} is not zero beyond sigma + pair_range = {c.sigma + c.pair_range:g}",
            "raise pair_range",
        )
    return module, params, c.pair_range


def sticky_force_max(gamma: float, p: float, eps: float, kT: float = 1.0, samples: int = 4001) -> float:
    """``max |f_p(r)|`` over the interaction range (B-32): the maximum over s = σ + ε − r in (0, ε].

    Parameters
    ----------
    gamma : float
        Baxter's stickiness γ [lambda].
    p : float
        The exponent of the δ_ε representation (B-31).
    eps : float
        Its range ε [lambda].
    kT : float
        The thermal energy [kT].
    samples : int
        Grid points in s.

    Returns
    -------
    float
        The largest force magnitude [kT/lambda].
    """
    s = np.linspace(eps / samples, eps, samples)
    return float(np.max(kT * gamma * p * s ** (p - 1) / (eps ** (p + 1) / (p + 1) + gamma * s**p)))


def best_exponent(eps: float, gamma: float = 1.0) -> float:
    """The exponent p > 1 minimising ``max |f_p|`` for given eps (the paper's Fig. 5: p ~ 2.95 at 0.05).

    Parameters
    ----------
    eps : float
        The range ε of the δ_ε representation [lambda].
    gamma : float
        Baxter's stickiness γ [lambda].

    Returns
    -------
    float
        The exponent p [1].
    """
    from scipy.optimize import minimize_scalar

    return float(minimize_scalar(lambda p: sticky_force_max(gamma, p, eps), bounds=(1.01, 20.0), method="bounded").x)


def stability_ratio(model: RodModel, dt: float) -> float:
    """μ max|f| dt / a of (B-33) for the neighbour force of range a (sticky: a = ε); the force is
    resolved when this is ≪ 1.

    Parameters
    ----------
    model : RodModel
        The rods' model.
    dt : float
        The time step [lambda^2/D].

    Returns
    -------
    float
        The ratio [1] (0 for hard rods).
    """
    if model.hard_rods or model.sticky_boundary:  # the boundary (eps = 0) has no force to resolve
        return 0.0
    module, params, reach = pair_kernels(model)
    largest = max(abs(module.force(r, params)) for r in model.sigma + reach * np.linspace(0.0, 1.0, 4001))
    return model.mu * largest * dt / reach
