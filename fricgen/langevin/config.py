"""What the Langevin engine simulates: typed sections, each checked once when it is created.

The same sections are the ``[law]``, ``[thermostat]``, ``[active]`` and ``[bulk]`` tables of a
``fricgen run`` file (fricgen.app.run.config), so a file, the Python API and a checkpoint carry one
configuration. Units: sigma = 1 (diameter of a sphere of radius 1/2), kT = 1, m = 1,
t0 = sqrt(m sigma^2 / kT) (docs/physics.md#units-and-symbols).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

from fricgen.derive.calculus import CALCULI, Calculus

from ..schema import Section

#: The contact steps: Metropolis-adjusted pair by pair (the default), or the explicit kick.
CONTACT_SCHEMES = ("pairwise", "explicit")
#: Law parameters that the engine sets itself, and what sets them.
OWNED_PARAMETERS = {"sigma": "the radii (sigma_ik = R_i + R_k)", "epsilon": "system.epsilon (the WCA strength)"}


@dataclass(frozen=True)
class Law(Section):
    """``[law]``: the friction laws of the contact, the calculus of their noise and how it is integrated.

    The calculus' own scheme integrates the contact (docs/physics.md#integrators-that-match-the-calculus)
    unless ``scheme`` names another and ``force_scheme`` is set (a wrong thermostat: for negative
    controls only). Contact modes (docs/physics-modes.md): the law ``name`` acts on the mode its law
    file names (sliding by default); ``rolling`` and ``spinning`` name laws for those modes (their files
    must say so). One law per mode, all in ``calculus``; spinning exists in 3-D only. The laws' modes
    are checked where the kernels are bound (:func:`fricgen.langevin.contact_law.bind`).

    Attributes
    ----------
    name : str
        The law (of the built-in catalogue or the user's law folders).
    calculus : str
        The calculus of the noise amplitude D: 'ito', 'stratonovich' or 'hk'.
    friction : bool
        False drops the contact entirely (friction and its noise).
    contact_noise : bool
        False drops the frictional noise of every mode (the inconsistent model).
    parameters : dict of str to float
        Overrides of the law's defaults, in the units of its law file.
    scheme : str or None
        Another calculus whose scheme integrates the contact (with ``force_scheme``).
    force_scheme : bool
        Whether ``scheme`` may differ from ``calculus``.
    contact_scheme : str
        "pairwise" (Metropolis-adjusted pair by pair: Maxwell-Boltzmann exact at any dt) or "explicit"
        (the first-order kick, where a wrong D shows in the temperatures;
        docs/physics.md#the-pairwise-contact-step).
    rolling, spinning : str or None
        The laws of the rolling and spinning modes, if any.
    rolling_parameters, spinning_parameters : dict of str to float
        Overrides of those laws' defaults.
    rolling_noise, spinning_noise : bool
        False drops the noise of that mode's law alone (a negative control per mode).
    """

    SECTION = "law"
    name: str = "coulomb_newton"
    calculus: str = "ito"
    friction: bool = True
    contact_noise: bool = True
    parameters: dict[str, float] = field(default_factory=dict)
    scheme: str | None = None
    force_scheme: bool = False
    contact_scheme: str = "pairwise"
    rolling: str | None = None
    rolling_parameters: dict[str, float] = field(default_factory=dict)
    spinning: str | None = None
    spinning_parameters: dict[str, float] = field(default_factory=dict)
    rolling_noise: bool = True
    spinning_noise: bool = True

    def __post_init__(self):
        self.require(
            self.calculus in CALCULI, "calculus", f"must be one of {CALCULI}, got {self.calculus!r}", 'for example calculus = "ito"'
        )
        self.require(self.scheme in (None, *CALCULI), "scheme", f"must be one of {CALCULI}, got {self.scheme!r}", "leave it out")
        self.require(
            self.contact_scheme in CONTACT_SCHEMES,
            "contact_scheme",
            f"must be one of {CONTACT_SCHEMES}, got {self.contact_scheme!r}",
            'for example contact_scheme = "pairwise"',
        )
        self.require(
            self.integrator == self.calculus or self.force_scheme,
            "scheme",
            f"the noise amplitude D of the {self.calculus} calculus needs the {self.calculus} scheme, not {self.integrator}: "
            "this pairing is not a consistent thermostat",
            "set force_scheme = true only for a negative control",
        )
        for table in ("parameters", "rolling_parameters", "spinning_parameters"):
            for name in getattr(self, table):
                owner = OWNED_PARAMETERS.get(name)
                self.require(owner is None, f"{table}.{name}", f"is set by {owner}", "remove it here")
        for mode in ("rolling", "spinning"):
            self.require(
                getattr(self, mode) is not None or not getattr(self, f"{mode}_parameters"),
                f"{mode}_parameters",
                f"sets parameters of no law: law.{mode} names none",
                f'name the {mode} law (law.{mode} = "...") or remove them',
            )
            self.require(
                getattr(self, mode) is not None or getattr(self, f"{mode}_noise"),
                f"{mode}_noise",
                f"drops the noise of no law: law.{mode} names none",
                f'name the {mode} law (law.{mode} = "...") or remove it; a {mode} law given as law.name has its noise'
                " dropped by contact_noise = false",
            )

    @property
    def integrator(self) -> Calculus:
        """The calculus whose scheme integrates the contact (the law's own unless ``scheme``)."""
        return Calculus(self.scheme or self.calculus)


@dataclass(frozen=True)
class Thermostat(Section):
    """``[thermostat]``: the solvent's Langevin thermostat (F-39, 40) and the time step.

    m dv = F dt - gamma v dt + sqrt(2 kT gamma) dW, and I d(omega) = tau dt - gamma_rot omega dt +
    sqrt(2 kT gamma_rot) dW.

    Attributes
    ----------
    kT : float
        The temperature [kT].
    gamma : float
        Translational solvent friction [kT t0/sigma^2]; the paper's 3 pi; 0 for none.
    gamma_rot : float
        Rotational solvent friction [kT t0]; the paper's pi; 0 for none.
    dt : float
        The time step [t0].
    """

    SECTION = "thermostat"
    kT: float = 1.0
    gamma: float = 3 * math.pi
    gamma_rot: float = math.pi
    dt: float = 1e-3

    def __post_init__(self):
        self.require_positive("kT", "dt")
        self.require_scale("kT")
        self.require_nonnegative("gamma", "gamma_rot")


@dataclass(frozen=True)
class Active(Section):
    """``[active]``: a self-propulsion force along each particle's body axis e1.

    Attributes
    ----------
    force : float
        F0 [kT/sigma]; 0 for passive particles.
    """

    SECTION = "active"
    force: float = 0.0

    def __post_init__(self):
        self.require(math.isfinite(self.force), "force", f"must be finite, got {self.force}", "give F0 in kT/sigma")
        self.require_bounded("force", self.force)


@dataclass(frozen=True)
class Bulk(Section):
    """``[bulk]``: a constant force on every mobile particle (e.g. the pressure gradient of a Poiseuille flow).

    Attributes
    ----------
    force : tuple of float
        [Fx, Fy(, Fz)] [kT/sigma]; () for none.
    """

    SECTION = "bulk"
    force: tuple[float, ...] = ()

    def __post_init__(self):
        self.require(len(self.force) in (0, 2, 3), "force", f"needs 2 or 3 components, got {len(self.force)}", "give [Fx, Fy(, Fz)]")
        self.require(all(map(math.isfinite, self.force)), "force", "must be finite", "give the force in kT/sigma")
        self.require_bounded("force", self.force)

    @property
    def vector(self) -> tuple[float, float, float]:
        """The force as three components (zeros where not given)."""
        return (*self.force, 0.0, 0.0, 0.0)[:3]


@dataclass(frozen=True)
class LangevinConfig(Section):
    """A Langevin run's configuration: the sections above, the pair potential and the numerics.

    Attributes
    ----------
    law : Law
        The ``[law]`` section.
    thermostat : Thermostat
        The ``[thermostat]`` section.
    active : Active
        The ``[active]`` section.
    bulk : Bulk
        The ``[bulk]`` section.
    epsilon : float
        The strength of the pair ``potential`` [kT] (WCA, F-34).
    seed : int
        The noise seed, in [0, 2^63).
    potential : str
        The pair potential (a built-in potential, "wca").
    skin : float
        The neighbour-list skin [sigma].
    overlap_limit : float
        A run stops when r < overlap_limit sigma_ik (it exploded) [1].

    Examples
    --------
    >>> from fricgen.langevin import LangevinConfig, Law, Thermostat
    >>> config = LangevinConfig(law=Law(name="coulomb_newton", calculus="stratonovich"), thermostat=Thermostat(dt=5e-4))
    >>> config.law.integrator.value, config.thermostat.gamma / config.thermostat.gamma_rot
    ('stratonovich', 3.0)
    """

    law: Law = field(default_factory=Law)
    thermostat: Thermostat = field(default_factory=Thermostat)
    active: Active = field(default_factory=Active)
    bulk: Bulk = field(default_factory=Bulk)
    epsilon: float = field(default=1.0, metadata={"key": "system.epsilon"})
    seed: int = field(default=1, metadata={"key": "run.seed"})
    potential: str = "wca"
    skin: float = 0.3
    overlap_limit: float = 0.6

    def __post_init__(self):
        self.require_nonnegative("epsilon")
        self.require(0 <= self.seed < 2**63, "seed", f"must be an integer in [0, 2^63), got {self.seed}", "give a non-negative integer")
        self.require_positive("skin", "overlap_limit")

    def as_dict(self) -> dict:
        """The configuration as nested plain data (the sections as dicts).

        Returns
        -------
        dict
            Field name to value, sections as dicts.
        """
        return dataclasses.asdict(self)
