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
    """``[law]``: the catalogue law ``name`` with ``parameters`` overriding its defaults, the
    ``calculus`` of its noise amplitude D (ito, stratonovich, hk), integrated by the calculus' own
    scheme (docs/physics.md#integrators-that-match-the-calculus) unless ``scheme`` names another and
    ``force_scheme`` is set (a wrong thermostat: for negative controls only). ``contact_scheme`` is
    "pairwise" (Metropolis-adjusted pair by pair: Maxwell–Boltzmann exact at any dt) or "explicit"
    (the first-order kick, where a wrong D shows in the temperatures; docs/physics.md#the-pairwise-contact-step).
    ``contact_noise = false`` drops the frictional noise of every mode (the inconsistent model),
    ``friction = false`` the contact entirely.

    Contact modes (docs/physics-modes.md): the law ``name`` acts on the mode its law file names (sliding by
    default); ``rolling`` and ``spinning`` name laws for those modes (their files must say so), with
    ``rolling_parameters`` and ``spinning_parameters`` overriding their defaults. One law per mode, all
    in ``calculus``; spinning exists in 3-D only. ``rolling_noise = false`` (``spinning_noise = false``)
    drops the noise of that mode's law alone and keeps the others' (a negative control per mode). The
    laws' modes are checked where the kernels are loaded (fricgen.langevin.simulation.mode_laws)."""

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
    """``[thermostat]``: ``kT``, solvent friction ``gamma`` (kT t0 / sigma^2) and ``gamma_rot`` (kT t0)
    of (F-39, 40), 0 for none (the paper's 3 pi and pi); time step ``dt`` in t0."""

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
    """``[active]``: ``force`` F0 (kT / sigma) along each particle's body axis e1."""

    SECTION = "active"
    force: float = 0.0

    def __post_init__(self):
        self.require(math.isfinite(self.force), "force", f"must be finite, got {self.force}", "give F0 in kT/sigma")
        self.require_bounded("force", self.force)


@dataclass(frozen=True)
class Bulk(Section):
    """``[bulk]``: ``force`` = [Fx, Fy(, Fz)] (kT / sigma) on every mobile particle; () for none."""

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
    """A Langevin run: the sections above, the WCA strength ``epsilon`` (kT) of the pair
    ``potential`` (F-34), the noise ``seed``, and numerics: the neighbour-list ``skin`` (sigma) and
    ``overlap_limit`` (a run stops when r < overlap_limit sigma_ik: it exploded)."""

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
        return dataclasses.asdict(self)
