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

#: Memory per rod and replica (positions and the BCD work arrays) and per histogram bin and replica
#: (counts and the profiles derived from them), in bytes: upper estimates.
BYTES_PER_ROD, BYTES_PER_BIN = 224, 32
#: How a step ends collisions (fricgen.rods.contact): BCD's inelastic merge (O(sqrt(dt))), elastic exchange, Brownian-bridge push.
CONTACT_LAYERS = ("merge", "reflect", "bridge")
#: Where a step evaluates the forces (fricgen.rods.bcd): its start, its noise's midpoint, its start with a Metropolis test.
DRIFT_SCHEMES = ("euler", "lm", "metropolis")


@dataclass(frozen=True)
class RodModel(Section):
    """``[model]``: rods on a ring in an external field, with an interaction of neighbours (B-21, B-28..32).

    Units: wavelength lambda = 1, diffusion coefficient D = 1, kT = 1 (docs/physics.md#units-and-symbols).

    Attributes
    ----------
    n : int
        The number of rods (at least 2).
    length : float
        The ring's length L [lambda]; inf for an open line.
    sigma : float
        The rod length [lambda].
    U0 : float
        The field's amplitude [kT]; the default field is U(x) = (U0/2) cos(2 pi x / lambda) (B-21).
    wavelength : float
        The field's period lambda [lambda].
    field : str
        The external potential (generated/potentials/<field>.py).
    field_params : dict of str to float
        The field's other parameters.
    kT : float
        The thermal energy [kT].
    mu : float
        The mobility [D/kT].
    drive : float
        A constant force on every rod [kT/lambda].
    gamma : float
        The stickiness of the sticky contact (B-31/32) [lambda]; 0: hard rods.
    p : float
        The exponent of the delta_eps representation (B-31) [1].
    eps : float
        Its range [lambda]; 0: Baxter's limit (B-29), a sticky boundary of each gap.
    pair : str or None
        A generated pair potential of neighbours (B-28) instead of the sticky contact.
    pair_params : dict of str to float
        Its parameters.
    pair_range : float
        It vanishes beyond r = sigma + pair_range [lambda] (pair_range < sigma).
    """

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
        self.require_positive("sigma", "wavelength", "kT", "mu")
        self.require_nonnegative("eps")
        self.require(
            self.eps > 0 or (self.gamma > 0 and self.pair is None),
            "eps",
            "eps = 0 (Baxter's sticky boundary) needs gamma > 0 and no pair potential",
            "give gamma > 0, or eps > 0",
        )
        for name in ("U0", "drive", "gamma", "p", "pair_range"):
            self.require(math.isfinite(getattr(self, name)), name, f"must be finite, got {getattr(self, name)}", "give a number")
        self.require(
            self.n * self.sigma < self.length,
            "n",
            f"N sigma = {self.n * self.sigma} must be below the ring length L = {self.length} (close packing)",
            "use fewer or shorter rods",
        )
        whole = self.open_line or abs(self.length / self.wavelength - round(self.length / self.wavelength)) <= 1e-9
        self.require(whole, "length", "the ring length must be a whole number of wavelengths", "change length or wavelength")
        self.require(self.gamma >= 0, "gamma", f"must be >= 0 (0: hard rods), got {self.gamma}", "fix the sticky contact")
        self.require(self.p > 1, "p", f"need p > 1 (a continuous force, B-31), got {self.p}", "fix the sticky contact")
        self.require(self.eps < self.sigma, "eps", f"must be below sigma = {self.sigma}, got {self.eps}", "fix the sticky contact")
        self.require(
            not {"U0", "lambda"} & set(self.field_params),
            "field_params",
            "set the field's amplitude and period with U0 and wavelength, not field_params",
            "remove them here",
        )
        for name in ("field_params", "pair_params"):
            values = getattr(self, name)
            self.require(all(map(math.isfinite, values.values())), name, f"must be finite numbers, got {values}", "fix them")
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
    def sticky_boundary(self) -> bool:
        """Baxter's limit eps = 0 of the sticky contact: a boundary condition of each gap (fricgen.rods.sticky)."""
        return self.gamma > 0 and self.eps == 0

    @property
    def diffusion(self) -> float:
        """The diffusion coefficient D = mu kT [D] (the Einstein relation; 1 in these units)."""
        return self.mu * self.kT

    @property
    def mean_density(self) -> float:
        """The mean density N / L [1/lambda]."""
        return self.n / self.length


@dataclass(frozen=True)
class RodNumerics(Section):
    """``[numerics]``: the time step, the seed, the equilibrium start and the contact layer.

    Attributes
    ----------
    dt : float
        The time step [lambda^2/D]. The default 1e-4 keeps the default study (N = 50, L = 100,
        U0 = 6, 16 rings, 1.25 time units) and the dense one (N = 140) within error with the bridge
        layer; merge needs about 2.5e-6 there.
    seed : int
        The noise seed.
    start_sweeps : int or None
        Monte Carlo sweeps of the equilibrium start (fricgen.rods.mc); None: 2000, or 20 000 for the
        sticky boundary (eps = 0), whose rings relax slowly in Monte Carlo (RodConfig.start_sweeps).
    contact_layer : str
        How a step ends collisions (fricgen.rods.contact): "bridge" (bias O(dt),
        docs/physics-bcd-contact-layer.md), "reflect" (O(dt) away from contact) or BCD's own "merge"
        (O(sqrt(dt)), docs/physics.md#brownian-cluster-dynamics).
    drift_scheme : str
        Where a step evaluates the forces: "euler" (its start), "lm" (Leimkuhler-Matthews: its noise's midpoint,
        where the profile is also sampled) or "metropolis" (its start, then a Metropolis test of the step: the
        exact equilibrium at any dt, no drive); lm, metropolis: bridge layer, hard rods (docs/physics-bcd-metropolis.md).
    """

    SECTION = "numerics"
    dt: float = 1e-4
    seed: int = 1
    start_sweeps: int | None = None
    contact_layer: str = "bridge"
    drift_scheme: str = "euler"

    @property
    def error_order(self) -> float:
        """q of the time-step bias O(dt^q) of the contact layer: 1/2 for merge, 1 for bridge and reflect."""
        return 0.5 if self.contact_layer == "merge" else 1.0

    @property
    def tested(self) -> bool:
        """Whether a Metropolis test accepts or rejects each step (drift_scheme = "metropolis", exact equilibrium)."""
        return self.drift_scheme == "metropolis"

    def __post_init__(self):
        self.require_positive("dt")
        self.require(0 <= self.seed < 2**63, "seed", f"must be an integer in [0, 2^63), got {self.seed}", "give a non-negative integer")
        if self.start_sweeps is not None:
            self.require(self.start_sweeps >= 0, "start_sweeps", f"must be >= 0, got {self.start_sweeps}", "give 0 or more")
            self.require_steps("start_sweeps", self.start_sweeps)
        layer, scheme = self.contact_layer, self.drift_scheme
        self.require(layer in CONTACT_LAYERS, "contact_layer", f"must be one of {', '.join(CONTACT_LAYERS)}, got {layer!r}", "give bridge")
        self.require(scheme in DRIFT_SCHEMES, "drift_scheme", f"must be one of {', '.join(DRIFT_SCHEMES)}, got {scheme!r}", "give lm")
        needs_bridge = f"the {scheme} drift needs the bridge contact layer, got {layer!r}"
        self.require(scheme == "euler" or layer == "bridge", "drift_scheme", needs_bridge, "give contact_layer = bridge, or euler")


@dataclass(frozen=True)
class RodSampling(Section):
    """``[sampling]``: the replicas and the histograms of the density and of the contact density.

    Attributes
    ----------
    replicas : int
        Independent rings (the samples of the errors).
    bins : int
        Density bins per wavelength.
    gap_width : float
        The width of a gap-histogram bin [lambda].
    gap_bins : int
        The number of gap bins.
    fit_bins : int
        Gap bins fitted beyond the BCD layer for the contact density.
    """

    SECTION = "sampling"
    replicas: int = 16
    bins: int = 50
    gap_width: float = 0.005
    gap_bins: int = 40
    fit_bins: int = 8

    def __post_init__(self):
        for name in ("replicas", "bins", "gap_bins"):
            self.require(getattr(self, name) >= 1, name, f"must be >= 1, got {getattr(self, name)}", "give a positive integer")
        self.require(self.fit_bins >= 2, "fit_bins", f"must be >= 2 (two windows of fit_bins / 2), got {self.fit_bins}", "give 8, say")
        self.require_positive("gap_width")


@dataclass(frozen=True)
class RodConfig(Section):
    """A BCD run: the model, its numerics and its sampling (build one with :func:`rod_config`).

    Attributes
    ----------
    model : RodModel
        The physics.
    numerics : RodNumerics
        The time step, seed, start and contact layer.
    sampling : RodSampling
        Replicas and histograms.

    Examples
    --------
    >>> from fricgen.rods import rod_config
    >>> config = rod_config(n=20, length=40.0, U0=4.0, replicas=2)
    >>> config.model.mean_density, config.numerics.dt
    (0.5, 0.0001)
    """

    model: RodModel = field(default_factory=RodModel)
    numerics: RodNumerics = field(default_factory=RodNumerics)
    sampling: RodSampling = field(default_factory=RodSampling)

    def __post_init__(self):
        self.require(
            not (self.model.open_line and self.start_sweeps > 0),
            "numerics.start_sweeps",
            "an open line (length = inf) has no equilibrium to start from",
            "set start_sweeps = 0 and give positions",
        )
        self.require(
            not self.model.sticky_boundary or self.numerics.contact_layer == "bridge",
            "numerics.contact_layer",
            f"the sticky boundary (eps = 0) runs with the bridge layer only, got {self.numerics.contact_layer!r}",
            "give bridge",
        )
        scheme, tested = self.numerics.drift_scheme, self.numerics.tested
        why = "without a drive (its test samples an equilibrium; U only)" if tested else "(rods overlap at its midpoint)"
        self.require(
            scheme == "euler" or (self.model.hard_rods and not (tested and self.model.drive)),
            "numerics.drift_scheme",
            f"the {scheme} drift is for hard rods {why}",
            "give euler",
        )
        m, r = self.model, self.sampling
        needed = r.replicas * (m.n * BYTES_PER_ROD + r.bins * (r.gap_bins + 1) * BYTES_PER_BIN)
        growth = {
            "model.n": m.n / RodModel.n,
            "sampling.replicas": r.replicas / RodSampling.replicas,
            "sampling.bins": r.bins / RodSampling.bins,
            "sampling.gap_bins": r.gap_bins / RodSampling.gap_bins,
        }
        key = max(growth, key=growth.get)  # the size furthest above its default
        what = f"{r.replicas} replicas of {m.n} rods with {r.bins} x {r.gap_bins + 1} histogram bins each"
        self.require_memory(key, needed, what)

    def require_sampling(self) -> None:
        """Sampling profiles needs replicas >= 2 (the errors are their scatter) and enough gap bins
        for the contact density's fit at this dt; ConfigError otherwise."""
        replicas = self.sampling.replicas
        self.require(
            replicas >= 2,
            "sampling.replicas",
            f"must be >= 2 (the errors come from the scatter between independent replicas), got {replicas}",
            "give 16 (replicas >= 2; 8 or more for chi^2)",
        )
        self.require(
            self.contact_fit_bins() <= self.sampling.gap_bins,
            "sampling.gap_bins",
            f"gap_bins = {self.sampling.gap_bins} is too few: the contact fit needs {self.contact_fit_bins()} at dt = {self.numerics.dt:g}",
            "raise it, or gap_width",
        )

    def contact_fit_bins(self) -> int:
        """Gap bins that the contact density needs at this dt (fricgen.rods.simulation).

        bridge: the bin of its local time at contact only. merge, reflect: that bin, the layer of width
        about 3 sqrt(4 D dt) where their pair density is distorted, then two windows of fit_bins / 2;
        with the Metropolis test (exact gaps) no layer.

        Returns
        -------
        int
            The number of gap bins.
        """
        distorted = not self.numerics.tested  # the Metropolis test's gaps are exact from g = 0
        if self.numerics.contact_layer == "bridge" and distorted:
            return 1
        layer = 1 + distorted * math.ceil(3 * math.sqrt(4 * self.model.diffusion * self.numerics.dt) / self.sampling.gap_width)
        return layer + 2 * (self.sampling.fit_bins // 2)

    @property
    def start_sweeps(self) -> int:
        """The Monte Carlo sweeps of the start: numerics.start_sweeps, or by default 2000, and 20 000 for the sticky
        boundary (with 2000 its gamma = 1 profiles were 2-3 errors per bin off, docs/physics-bcd-sticky-boundary.md)."""
        chosen = self.numerics.start_sweeps
        return chosen if chosen is not None else (20_000 if self.model.sticky_boundary else 2000)

    def replace(self, **changes) -> RodConfig:
        """A copy with flat fields changed.

        Parameters
        ----------
        **changes
            Fields by name (of any section), e.g. ``dt`` [lambda^2/D].

        Returns
        -------
        RodConfig
            The checked copy.
        """
        return rod_config(**(self.as_flat() | changes))

    def as_flat(self) -> dict:
        """All fields by name.

        Returns
        -------
        dict
            The keywords of :func:`rod_config`.
        """
        return {f.name: getattr(part, f.name) for part in (self.model, self.numerics, self.sampling) for f in dataclasses.fields(part)}


PARTS = (RodModel, RodNumerics, RodSampling)


def rod_config(**values) -> RodConfig:
    """A RodConfig from flat keywords (each a field of RodModel, RodNumerics or RodSampling).

    Parameters
    ----------
    **values
        Fields by name, e.g. ``n``, ``length`` and ``sigma`` [lambda], ``U0`` [kT],
        ``dt`` [lambda^2/D], ``replicas``; the others keep their defaults.

    Returns
    -------
    RodConfig
        The checked configuration.

    Raises
    ------
    TypeError
        For a keyword that is no field.
    ConfigError
        For a value its section refuses.
    """
    fields = flat_fields(*PARTS)
    unknown = sorted(set(values) - set(fields))
    if unknown:
        raise TypeError(f"rod_config() got unknown field(s) {unknown}; the fields are {sorted(fields)}")
    parts = {part: {name: value for name, value in values.items() if fields[name][0] is part} for part in PARTS}
    return RodConfig(*(part(**parts[part]) for part in PARTS))
