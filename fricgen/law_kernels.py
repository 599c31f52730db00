"""The compiled kernels of one friction law, as the loader (:mod:`fricgen.kernels`) returns them.

A law's generated module (fricgen.generated.laws.<law>, or a user folder's DIR/generated/) holds the
friction f(u, w, r, p), its weight w(r, p), and per calculus the noise amplitude D(u, w, r, mu, kT, p)
that solves the zero-current condition nu kT dD/du - u D = -f with nu = (1 - theta) mu (F-20;
docs/physics.md#contact-mobility-and-the-calculus). :class:`LawKernels` hands them out by calculus and
builds their parameter array, each value checked against its range. Units (docs/physics.md#units-and-symbols):
u [sigma/t0], r [sigma], w [1], mu [1/m], kT [kT], f [kT/sigma], D [kT t0/sigma^2].
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from types import ModuleType

import numpy as np

from fricgen.derive.law.lawdata import POSITIVE, Interval

from .errors import ConfigError, KernelError


@dataclass(frozen=True)
class LawKernels:
    """The compiled kernels of one friction law (the equations: its generated module's docstring).

    Get one with :func:`fricgen.load_law` or :func:`fricgen.kernels.load_law_kernels`; hand it to
    :class:`fricgen.langevin.Simulation`. Every kernel takes the parameter array ``p`` of
    :meth:`parameters` as its last argument.

    Attributes
    ----------
    name : str
        The law's name (its law file is ``<name>.toml``).
    module : module
        The generated module whose kernels this is.
    path : pathlib.Path or None
        The law file the kernels were generated from (checked fresh when loaded).

    Examples
    --------
    >>> import fricgen
    >>> law = fricgen.load_law("linear")
    >>> law.parameter_names, law.calculi
    (('gamma_f', 'epsilon', 'sigma'), ('ito', 'stratonovich', 'hk'))
    >>> p = law.parameters(gamma_f=2.0)
    >>> law.friction(0.5, 1.0, 1.0, p)  # f = w gamma_f u [kT/sigma]
    1.0
    >>> law.noise_amplitude("ito")(0.5, 1.0, 1.0, 2.2, 1.0, p)  # D = w gamma_f [kT t0/sigma^2]
    2.0
    """

    name: str
    module: ModuleType
    path: Path | None = None

    @property
    def source_hash(self) -> str:
        """The hash of the law file (and of its weight's potential) that the kernels were generated from."""
        return self.module.SOURCE_HASH

    @property
    def parameter_names(self) -> tuple[str, ...]:
        """The names of the law's parameters, in the order of the parameter array."""
        return self.module.PARAMETERS

    @property
    def calculi(self) -> tuple[str, ...]:
        """The calculi ('ito', 'stratonovich', 'hk') the law has noise kernels for."""
        return self.module.CALCULI

    @property
    def has_weight(self) -> bool:
        """Whether the friction depends on the distance through a weight w(r) (else w = 1)."""
        return self.module.HAS_WEIGHT

    @property
    def mode(self) -> str:
        """The contact mode the law acts on: ``MODE`` of the module, sliding where it has none (every
        sliding law's module; docs/physics-modes.md)."""
        return getattr(self.module, "MODE", "sliding")

    @property
    def ranges(self) -> dict[str, Interval]:
        """The admissible values of each parameter (from the law file; the positive reals by default)."""
        ranges = getattr(self.module, "RANGES", None) or [()] * len(self.parameter_names)  # () : Interval() = POSITIVE
        return {name: Interval(*bounds) for name, bounds in zip(self.parameter_names, ranges)}

    def parameters(self, **overrides: float) -> np.ndarray:
        """The parameter array ``p`` of the kernels: the law's defaults, with named overrides.

        Parameters
        ----------
        **overrides : float
            Values by parameter name, in the units the law file gives each parameter; each must lie
            in its range (:attr:`ranges`).

        Returns
        -------
        numpy.ndarray
            float64 values in the order of :attr:`parameter_names`.

        Raises
        ------
        ConfigError
            For an unknown name or a value outside its range, naming both.
        """
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
        """The noise amplitude D(u, w, r, mu, kT, p) [kT t0/sigma^2] of a calculus, solving
        nu kT dD/du - u D = -f with nu = (1 - theta) mu (F-20).

        Parameters
        ----------
        calculus : str
            'ito' (theta = 0), 'stratonovich' (1/2) or 'hk' (1); one of :attr:`calculi`.

        Returns
        -------
        numba function
            D(u [sigma/t0], w [1], r [sigma], mu [1/m], kT [kT], p) -> float.
        """
        return getattr(self.module, f"noise_amplitude_{self._calculus(calculus)}")

    def noise_sqrt(self, calculus: str):
        """sqrt(D)(u, w, r, mu, kT, p) [sqrt(kT t0)/sigma] of a calculus, the factor of the random force.

        Parameters
        ----------
        calculus : str
            One of :attr:`calculi`.

        Returns
        -------
        numba function
            The arguments of :meth:`noise_amplitude`.
        """
        return getattr(self.module, f"noise_sqrt_{self._calculus(calculus)}")

    def contact(self, calculus: str):
        """(f/u [kT t0/sigma^2], D [kT t0/sigma^2])(u, w, r, mu, kT, p) of a calculus, in one call.

        Parameters
        ----------
        calculus : str
            One of :attr:`calculi`.

        Returns
        -------
        numba function
            The arguments of :meth:`noise_amplitude`; returns the pair (f/u, D).
        """
        return getattr(self.module, f"contact_{self._calculus(calculus)}")

    @property
    def friction(self):
        """f(u, w, r, p) [kT/sigma], the friction force's magnitude at slip speed u [sigma/t0]."""
        return self.module.friction

    @property
    def friction_over_u(self):
        """f/u (u, w, r, p) [kT t0/sigma^2], finite as u -> 0 where f vanishes there."""
        return self.module.friction_over_u

    @property
    def friction_slope(self):
        """df/du (u, w, r, p) [kT t0/sigma^2]."""
        return self.module.friction_slope

    @property
    def weight(self):
        """w(r, p) [1], the distance weight of the friction; KernelError for a law without one."""
        if not self.has_weight:
            raise KernelError(f"law {self.name} has no weight w(r)")
        return self.module.weight
