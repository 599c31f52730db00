"""What a BCD run of rods simulates (model), how (numerics) and what it measures (sampling).

Each part is a frozen dataclass that checks its values once; :class:`RodConfig` holds the three
and checks what ties them together. :func:`rod_config` builds one from flat keywords, the form
that ``fricgen bcd``'s flags take (they are derived from these fields, defaults included).
Units as in the paper: lambda = 1, D = 1, kT = 1 (mu = D / kT).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

from ..schema import Section, flat_fields


@dataclass(frozen=True)
class RodModel(Section):
    """``n`` rods of length ``sigma`` on a ring of length ``length`` (an open line for inf) in the
    external potential ``field`` (generated/potentials/<field>.py; default (U0/2) cos(2 pi x /
    lambda), B-21) of amplitude ``U0`` (kT) and period ``wavelength``, its other parameters from
    ``field_params``; thermal energy ``kT``, mobility ``mu``, a constant ``drive`` (kT / lambda);
    between neighbours either the sticky contact (B-31/32) of stickiness ``gamma`` (0: hard rods),
    exponent ``p`` and range ``eps``, or the generated pair potential ``pair`` (B-28) with
    ``pair_params``, zero beyond r = sigma + ``pair_range`` (pair_range < sigma)."""

    SECTION = "model"
    n: int = 50
    length: float = 100.0
    sigma: float = 0.5
    U0: float = 6.0
    wavelength: float = 1.0
    field: str = "cosine"
    field_params: dict[str, float] = dataclasses.field(default_factory=dict)
    kT: float = 1.0
    mu: float = 1.0
    drive: float = 0.0
    gamma: float = 0.0
    p: float = 3.0
    eps: float = 0.05
    pair: str | None = None
    pair_params: dict[str, float] = dataclasses.field(default_factory=dict)
    pair_range: float = 0.0

    def __post_init__(self):
        self.require(self.n >= 2, "n", f"needs at least 2 rods, got {self.n}", "give n >= 2")
        self.require(self.length > 0 and not math.isnan(self.length), "length", f"must be positive, got {self.length}", "give L > 0")
        self.require_positive("sigma", "wavelength", "kT", "mu", "eps")
        for name in ("U0", "drive", "gamma", "pair_range"):
            self.require(math.isfinite(getattr(self, name)), name, f"must be finite, got {getattr(self, name)}", "give a number")
        self.require(
            self.n * self.sigma < self.length,
            "n",
            f"N sigma = {self.n * self.sigma} must be below the ring length L = {self.length} (close packing)",
            "use fewer or shorter rods",
        )
        whole = self.open_line or abs(self.length / self.wavelength - round(self.length / self.wavelength)) <= 1e-9
        self.require(whole, "length", "the ring length must be a whole number of wavelengths", "change length or wavelength")
        self.require(
            self.gamma >= 0 and self.p > 1 and self.eps < self.sigma,
            "gamma",
            f"need gamma >= 0, p > 1 (continuous force, B-31) and eps < sigma, got {self.gamma}, {self.p}, {self.eps}",
            "fix the sticky contact",
        )
        self.require(
            not {"U0", "lambda"} & set(self.field_params),
            "field_params",
            "set the field's amplitude and period with U0 and wavelength, not field_params",
            "remove them here",
        )
        values = (*self.field_params.values(), *self.pair_params.values())
        self.require(all(map(math.isfinite, values)), "field_params", "field and pair parameters must be finite numbers", "fix them")
        self.require(
            self.pair is not None or not (self.pair_params or self.pair_range),
            "pair_range",
            "pair_params and pair_range need a pair potential (pair)",
            "name one, e.g. pair = wca",
        )
        self.require(
            self.pair is None or (self.gamma == 0 and 0 < self.pair_range < self.sigma),
            "pair_range",
            f"a pair potential needs gamma = 0 (no sticky contact) and 0 < pair_range < sigma, got {self.pair_range}",
            "fix pair_range or gamma",
        )

    @property
    def open_line(self) -> bool:
        """length = inf: rods on an infinite line, no periodic images (rod N-1 has no right neighbour)."""
        return math.isinf(self.length)

    @property
    def hard_rods(self) -> bool:
        """No interaction beyond the hard core (no sticky contact, no pair potential)."""
        return self.gamma == 0 and self.pair is None

    @property
    def diffusion(self) -> float:
        return self.mu * self.kT

    @property
    def mean_density(self) -> float:
        return self.n / self.length


@dataclass(frozen=True)
class RodNumerics(Section):
    """Time step ``dt`` (bias O(sqrt(dt)), docs/physics.md#brownian-cluster-dynamics), noise ``seed``,
    and ``start_sweeps`` Monte Carlo sweeps of the equilibrium start (fricgen.rods.mc)."""

    SECTION = "numerics"
    dt: float = 2.5e-6
    seed: int = 1
    start_sweeps: int = 2000

    def __post_init__(self):
        self.require_positive("dt")
        self.require(0 <= self.seed < 2**63, "seed", f"must be an integer in [0, 2^63), got {self.seed}", "give a non-negative integer")
        self.require(self.start_sweeps >= 0, "start_sweeps", f"must be >= 0, got {self.start_sweeps}", "give 0 or more")


@dataclass(frozen=True)
class RodSampling(Section):
    """``replicas`` independent rings (the samples of the errors), ``bins`` per wavelength, and the gap
    histogram of the contact density: ``gap_bins`` bins of width ``gap_width``, ``fit_bins`` of
    them fitted beyond the BCD layer."""

    SECTION = "sampling"
    replicas: int = 16
    bins: int = 50
    gap_width: float = 0.005
    gap_bins: int = 40
    fit_bins: int = 8

    def __post_init__(self):
        for name in ("replicas", "bins", "gap_bins", "fit_bins"):
            self.require(getattr(self, name) >= 1, name, f"must be >= 1, got {getattr(self, name)}", "give a positive integer")
        self.require_positive("gap_width")


@dataclass(frozen=True)
class RodConfig(Section):
    """A BCD run: the model, its numerics and its sampling."""

    model: RodModel = field(default_factory=RodModel)
    numerics: RodNumerics = field(default_factory=RodNumerics)
    sampling: RodSampling = field(default_factory=RodSampling)

    def __post_init__(self):
        self.require(
            not (self.model.open_line and self.numerics.start_sweeps > 0),
            "numerics.start_sweeps",
            "an open line (length = inf) has no equilibrium to start from",
            "set start_sweeps = 0 and give positions",
        )

    def replace(self, **changes) -> RodConfig:
        """A copy with flat fields changed (e.g. ``dt``)."""
        return rod_config(**(self.as_flat() | changes))

    def as_flat(self) -> dict:
        """All fields by name (the keywords of :func:`rod_config`)."""
        return {f.name: getattr(part, f.name) for part in (self.model, self.numerics, self.sampling) for f in dataclasses.fields(part)}


PARTS = (RodModel, RodNumerics, RodSampling)


def rod_config(**values) -> RodConfig:
    """A RodConfig from flat keywords (each a field of RodModel, RodNumerics or RodSampling)."""
    fields = flat_fields(*PARTS)
    unknown = sorted(set(values) - set(fields))
    if unknown:
        raise TypeError(f"rod_config() got unknown field(s) {unknown}; the fields are {sorted(fields)}")
    parts = {part: {name: value for name, value in values.items() if fields[name][0] is part} for part in PARTS}
    return RodConfig(*(part(**parts[part]) for part in PARTS))
