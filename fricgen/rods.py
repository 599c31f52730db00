"""Hard (and sticky) rods in an external field with BCD: configuration, runs, profiles with errors.

The field is any generated external potential U(x; U0, lambda, ...) (derive/potentials.py: periodic
with period lambda, checked symbolically when it is generated), the cosine (B-21) by default.
Units as in the paper: lambda = 1, D = 1, kT = 1 (mu = D / kT). Observables are folded onto one
wavelength: rho(x) (B-25) and rho_2(x, x + sigma) (B-26) at bin centres, with standard errors from
the scatter between independent replicas, each started from an equilibrium configuration sampled
by Monte Carlo (rods_mc).

Time-step error: after a BCD step the rods of a merged cluster touch exactly (gap 0). This atom of
exact contacts holds about 0.7 rho_2(0) s of pair density, s = sqrt(4 D dt) the rms change of a gap
per step (the discrete-monitoring shift of a reflecting wall), taken from the gaps just above
contact. So BCD behaves like rods shortened by O(s): profile and contact density carry an O(sqrt(dt))
bias (measured: the contact density of the uniform fluid at rho_bar sigma = 0.7 is 5 % low at
dt = 1e-5, 2 % at 1e-6).

Contact density (B-26): the pair density at gap g beyond the layer, g in [3 s, 3 s + fit_bins w],
is fitted per bin by ln rho_2(x, g) = a + b g and extrapolated to g = 0; the exact contacts are
not counted. Errors by jackknife over replicas. This holds for hard rods only: within the range of a
sticky or pair interaction the pair density is not exponential in g (deviations() compares it for
hard rods only).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from types import ModuleType

import numpy as np

from . import bcd, rods_mc
from .kernels import load_potential
from .rng import INITIAL, normals
from .rods_theory import RodProfile, rod_profile


@dataclass(frozen=True)
class RodConfig:
    """A BCD run: N rods of length sigma on a ring of length L (an open line for L = inf, started from
    given positions with start_sweeps = 0) in the external potential ``field``
    (generated/potentials/<field>.py; default (U0/2) cos(2 pi x / lambda), B-21) of amplitude U0 and
    period lambda = wavelength, its other parameters from ``field_params`` (else the module's
    defaults), optional drive, and between neighbours either the sticky contact (B-31/32) of
    strength gamma (0: hard rods) or the generated pair potential ``pair`` (B-28) with
    ``pair_params``, zero beyond r = sigma + pair_range (pair_range < sigma). The rods start from
    ``start_sweeps`` Monte Carlo sweeps of the equilibrium ensemble (rods_mc)."""

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
    dt: float = 1e-4
    seed: int = 1
    replicas: int = 1
    bins: int = 100
    gap_width: float = 0.005
    gap_bins: int = 40
    fit_bins: int = 8
    start_sweeps: int = 2000

    def __post_init__(self):
        if self.n < 2 or self.replicas < 1 or self.bins < 1 or self.start_sweeps < 0:
            raise ValueError("need n >= 2 rods, replicas >= 1, bins >= 1 and start_sweeps >= 0")
        for name in ("length", "sigma", "wavelength", "kT", "mu", "dt", "eps", "gap_width"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} must be positive, got {getattr(self, name)}")
        if self.n * self.sigma >= self.length:
            raise ValueError(f"N sigma = {self.n * self.sigma} must be below the ring length L = {self.length} (close packing)")
        if self.open_line and self.start_sweeps > 0:
            raise ValueError("an open line (length = inf) has no equilibrium to start from: set start_sweeps = 0, give positions")
        if not self.open_line and abs(self.length / self.wavelength - round(self.length / self.wavelength)) > 1e-9:
            raise ValueError("the ring length must be a whole number of wavelengths")
        if self.gamma < 0 or self.p <= 1 or self.eps >= self.sigma:
            raise ValueError("need gamma >= 0, p > 1 (continuous force, B-31) and eps < sigma")
        if {"U0", "lambda"} & set(self.field_params):
            raise ValueError("set the field's amplitude and period with U0 and wavelength, not field_params")
        if not all(math.isfinite(v) for v in (*self.field_params.values(), *self.pair_params.values())):
            raise ValueError(f"field and pair parameters must be finite numbers, got {self.field_params}, {self.pair_params}")
        if self.pair is None and (self.pair_params or self.pair_range):
            raise ValueError("pair_params and pair_range need a pair potential (pair)")
        if self.pair is not None and (self.gamma > 0 or not 0 < self.pair_range < self.sigma):
            raise ValueError(f"a pair potential needs gamma = 0 (no sticky contact) and 0 < pair_range < sigma, got {self.pair_range}")

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


def _parameters(module: ModuleType, given: dict[str, float], fixed: dict[str, float]) -> np.ndarray:
    """Parameter values of a generated module in the order of its PARAMETERS: ``fixed`` (where it has
    them), else ``given``, else its defaults."""
    unknown = sorted(set(given) - set(module.PARAMETERS))
    if unknown:
        raise ValueError(f"{module.NAME!r} has no parameter(s) {unknown}; its parameters are {module.PARAMETERS}")
    values = dict(zip(module.PARAMETERS, module.DEFAULTS)) | given | fixed
    return np.array([float(values[name]) for name in module.PARAMETERS])


def _on_arrays(kernel: Callable[[float, np.ndarray], float], params: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    """A scalar generated kernel f(x, params) as a function of arrays of x (the exact theory's input)."""
    return np.vectorize(lambda x: kernel(float(x), params), otypes=[float])


def field_kernels(config: RodConfig) -> tuple[ModuleType, np.ndarray]:
    """The generated external potential of a configuration and its parameter values: U0 and lambda
    from U0 and wavelength, the others from field_params or its defaults."""
    module = load_potential(config.field)
    if not hasattr(module, "force_field"):
        raise ValueError(f"{config.field!r} is a pair potential, not an external field U(x)")
    return module, _parameters(module, config.field_params, {"U0": config.U0, "lambda": config.wavelength})


def field_energy(config: RodConfig) -> Callable[[np.ndarray], np.ndarray]:
    """U(x) of the configuration's field, for arrays of positions."""
    module, params = field_kernels(config)
    return _on_arrays(module.energy, params)


def pair_kernels(config: RodConfig) -> tuple[ModuleType, np.ndarray, float]:
    """The interaction of neighbours beyond the hard core: generated module, parameter values and the
    range a of the gap (V = 0 for r >= sigma + a). The sticky contact (B-32, a = eps; gamma = 0:
    V = 0, hard rods) unless ``pair`` names another generated pair potential (B-28), with kT from the
    config; that one is checked to vanish on [sigma + a, 2 sigma] (neighbours only interact)."""
    c = config
    if c.pair is None:
        return load_potential("sticky"), np.array([c.gamma, c.p, c.eps, c.sigma, c.kT]), c.eps
    module = load_potential(c.pair)
    if hasattr(module, "force_field"):
        raise ValueError(f"{c.pair!r} is an external field, not a pair potential V(r)")
    params = _parameters(module, c.pair_params, {"kT": c.kT} if "kT" in module.PARAMETERS else {})
    beyond = c.sigma + c.pair_range + (c.sigma - c.pair_range) * np.linspace(0.0, 1.0, 401)[1:] ** 2
    if any(module.energy(r, params) != 0.0 or module.force(r, params) != 0.0 for r in beyond):
        raise ValueError(f"pair potential {c.pair!r} is not zero beyond sigma + pair_range = {c.sigma + c.pair_range:g}: raise pair_range")
    return module, params, c.pair_range


def sticky_force_max(gamma: float, p: float, eps: float, kT: float = 1.0, samples: int = 4001) -> float:
    """max |f_p(r)| over the interaction range (B-32): the s = sigma + eps - r in (0, eps] maximum."""
    s = np.linspace(eps / samples, eps, samples)
    return float(np.max(kT * gamma * p * s ** (p - 1) / (eps ** (p + 1) / (p + 1) + gamma * s**p)))


def best_exponent(eps: float, gamma: float = 1.0) -> float:
    """The exponent p > 1 minimising max |f_p| for given eps (the paper's Fig. 5: p ~ 2.95 at 0.05)."""
    from scipy.optimize import minimize_scalar

    return float(minimize_scalar(lambda p: sticky_force_max(gamma, p, eps), bounds=(1.01, 20.0), method="bounded").x)


def stability_ratio(config: RodConfig) -> float:
    """mu max|f| dt / a of (B-33) for the neighbour force of range a (sticky: a = eps); the force is
    resolved when this is << 1 (0 for hard rods)."""
    if config.hard_rods:
        return 0.0
    module, params, reach = pair_kernels(config)
    largest = max(abs(module.force(r, params)) for r in config.sigma + reach * np.linspace(0.0, 1.0, 4001))
    return config.mu * largest * config.dt / reach


@dataclass(frozen=True)
class RodProfiles:
    """Profiles over one wavelength at bin centres x: rho, rho_2 at contact, their standard errors."""

    x: np.ndarray
    rho: np.ndarray
    rho_err: np.ndarray
    contact: np.ndarray
    contact_err: np.ndarray
    steps: int


class RodSimulation:
    """Independent replicas of one ring, started from equilibrium (Monte Carlo) and evolved by BCD.

    ``positions`` (N or replicas x N, ordered, no overlaps): the start instead of evenly spaced rods,
    before the config's Monte Carlo sweeps; required on an open line (length = inf), which has no
    Monte Carlo start and no profiles."""

    def __init__(self, config: RodConfig, positions: np.ndarray | None = None):
        self.config = config
        ratio = stability_ratio(config)
        if ratio > 0.1:
            warnings.warn(f"mu max|f| dt / a = {ratio:.2g} is not << 1 (B-33): reduce dt", stacklevel=2)
        self._field, self._field_params = field_kernels(config)  # energy and force kernels
        self._pair, self._pair_params, self._pair_range = pair_kernels(config)
        self._pair_on = not config.hard_rods
        if positions is None and config.open_line:
            raise ValueError("an open line (length = inf) needs initial positions")
        self.positions = self._initial() if positions is None else self._given(positions)
        self.step, self.sweep = 0, 0
        self.acceptance = self.thermalize(config.start_sweeps)

    def _initial(self) -> np.ndarray:
        """Evenly spaced rods with a small random shift per replica (no overlaps)."""
        c = self.config
        spacing = c.length / c.n
        shift = normals(c.seed, 0, INITIAL, c.replicas) * 0.1 * (spacing - c.sigma)
        base = np.arange(c.n) * spacing
        return np.ascontiguousarray(base[None, :] + shift[:, None] % spacing)

    def _given(self, positions: np.ndarray) -> np.ndarray:
        """A copy of the given start for every replica; ValueError unless ordered without overlaps."""
        c = self.config
        x = np.array(np.broadcast_to(np.asarray(positions, dtype=float), (c.replicas, c.n)), order="C")
        after = np.concatenate([x[:, 1:], x[:, :1] + c.length], axis=1)  # inf on an open line
        if not (np.isfinite(x).all() and np.all(after - x >= c.sigma)):
            raise ValueError(f"initial positions must be finite, ordered and at least sigma = {c.sigma} apart (around the ring)")
        return x

    def thermalize(self, sweeps: int) -> float:
        """Metropolis sweeps (rods_mc) towards the exact equilibrium of the configuration's model, with no
        time step: the wells fill as in equilibrium at once. Returns the acceptance ratio."""
        c = self.config
        acceptance = rods_mc.metropolis_sweeps(
            self.positions,
            c.length,
            c.sigma,
            c.kT,
            self._field.energy,
            self._field_params,
            self._pair.energy,
            self._pair_params,
            c.sigma + self._pair_range,
            self._pair_on,
            sweeps,
            self.sweep,
            c.seed,
        )
        self.sweep += sweeps
        return acceptance

    def equilibrate(self, duration: float, dt: float | None = None) -> None:
        """Run ``duration`` time units without sampling, at time step ``dt`` (default: the config's)."""
        dt = dt or self.config.dt
        self.advance(int(round(duration / dt)), dt=dt)

    def advance(self, steps: int, counts: tuple[np.ndarray, np.ndarray] | None = None, dt: float | None = None) -> None:
        """Advance all replicas by ``steps`` steps of ``dt`` (default: the config's); ``counts`` =
        (rods per replica and bin, gaps per replica, bin and gap bin) accumulate samples."""
        c = self.config
        counts = counts or (np.zeros((c.replicas, c.bins)), np.zeros((c.replicas, c.bins, c.gap_bins)))
        status = bcd.advance_rods(
            self.positions,
            c.length,
            c.sigma,
            c.mu,
            c.diffusion,
            dt or c.dt,
            steps,
            self.step,
            c.seed,
            self._field.force_field,
            self._field_params,
            c.drive,
            self._pair.force,
            self._pair_params,
            self._pair_range,
            self._pair_on,
            c.wavelength,
            c.gap_width,
            *counts,
        )
        if status == bcd.PASSED:
            raise RuntimeError(f"rods overlapped near step {self.step + steps}: a bug or a non-finite force")
        if status == bcd.ALL_IN_CONTACT:
            raise RuntimeError("all rods are in contact (close packing): BCD cannot split the ring")
        self.step += steps

    def run(self, steps: int) -> RodProfiles:
        """Sample ``steps`` steps; the replicas are the independent samples of the errors.

        Within one ring the occupation of the wells changes only by hopping over the barriers (about
        20 time units per rod at U0 = 6), longer than a typical run, so time blocks of one ring are not
        independent; replicas started from independent equilibrium configurations are."""
        c = self.config
        if c.open_line:
            raise ValueError("profiles need a ring of finite length; on an open line use advance() and positions")
        if c.replicas < 2:
            raise ValueError("errors come from the scatter between independent replicas: need replicas >= 2 (8 or more for chi^2)")
        if steps < 1:
            raise ValueError("need at least one step")
        width = c.wavelength / c.bins
        scale = steps * width * c.length / c.wavelength  # sampled length per bin
        rods, gaps = np.zeros((c.replicas, c.bins)), np.zeros((c.replicas, c.bins, c.gap_bins))
        self.advance(steps, (rods, gaps))
        rho = rods / scale
        contact, contact_err = self._contact(gaps / (scale * c.gap_width))
        return RodProfiles(
            (np.arange(c.bins) + 0.5) * width,
            rho.mean(0),
            rho.std(0, ddof=1) / math.sqrt(c.replicas),
            contact,
            contact_err,
            steps,
        )

    def _contact(self, pair_density: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """rho_2 at contact per bin from the gap histograms of the replicas (replicas, bins, gap bins).

        Beyond the BCD layer, g >= g0, the mean pair densities A and B over two windows
        [g0, g0 + d) and [g0 + d, g0 + 2d) fix rho_2(g) = rho_2(0) exp(-k g): k = ln(A / B) / d,
        rho_2(0) = A exp(k g0) (k d) / (1 - exp(-k d)). Errors by jackknife over the replicas."""
        c = self.config
        first = 1 + math.ceil(3 * math.sqrt(4 * c.diffusion * c.dt) / c.gap_width)
        half = c.fit_bins // 2
        if first + 2 * half > c.gap_bins:
            raise ValueError(f"gap_bins = {c.gap_bins} is too few: the contact fit needs {first + 2 * half} gap bins at dt = {c.dt}")
        start, span = (first - 1) * c.gap_width, half * c.gap_width
        windows = pair_density[:, :, first : first + 2 * half].reshape(*pair_density.shape[:2], 2, half).mean(-1)

        def extrapolate(near, far):
            with np.errstate(divide="ignore", invalid="ignore"):
                rate = np.log(near / far) / span
                factor = np.where(np.abs(rate * span) > 1e-12, rate * span / -np.expm1(-rate * span), 1.0)
                return near * np.exp(rate * start) * factor

        samples = windows.shape[0]
        total = windows.sum(0)
        leave_one_out = extrapolate(*np.moveaxis((total[None] - windows) / (samples - 1), -1, 0))
        with np.errstate(invalid="ignore"):  # bins without pairs in a window stay NaN
            error = np.sqrt((samples - 1) * leave_one_out.var(0))
        return extrapolate(*np.moveaxis(total / samples, -1, 0)), error


def extrapolate_to_zero_dt(coarse: RodProfiles, fine: RodProfiles, ratio: float) -> RodProfiles:
    """Remove the O(sqrt(dt)) BCD bias from runs at dt and dt / ratio: X(0) = (r X_fine - X_coarse) / (r - 1),
    r = sqrt(ratio) (Richardson in sqrt(dt); errors added in quadrature)."""
    r = math.sqrt(ratio)

    def combine(a, b):
        return (r * b - a) / (r - 1)

    def error(a, b):
        return np.hypot(r * b, a) / (r - 1)

    return RodProfiles(
        fine.x,
        combine(coarse.rho, fine.rho),
        error(coarse.rho_err, fine.rho_err),
        combine(coarse.contact, fine.contact),
        error(coarse.contact_err, fine.contact_err),
        coarse.steps + fine.steps,
    )


def exact_profile(config: RodConfig) -> RodProfile:
    """The exact equilibrium (rods_theory) of the model a RodConfig simulates, on a ring of its length;
    the grid (600 to 2400 points per wavelength) has sigma on a grid point."""
    if config.open_line:
        raise ValueError("the exact theory is for a ring of finite length, not an open line")
    ratio = config.sigma / config.wavelength
    points = next((m for m in range(600, 2401) if abs(ratio * m - round(ratio * m)) < 1e-9), None)
    if points is None:
        raise ValueError(f"sigma / lambda = {ratio} is not a fraction k / m with 600 <= m <= 2400")

    c = config
    pair = {"gamma": c.gamma, "eps": c.eps, "p": c.p} if c.gamma > 0 else {}
    if c.pair is not None:
        module, params, reach = pair_kernels(c)
        pair = {"pair": _on_arrays(module.energy, params), "pair_range": reach}
    return rod_profile(field_energy(config), c.sigma, c.mean_density, c.wavelength, c.kT, points=points, ring_length=c.length, **pair)


def deviations(measured: RodProfiles, exact: RodProfile, contact: bool = True) -> dict[str, float | None]:
    """Profile vs exact bin means: max |d rho|, L1 / rho_bar, chi^2 per bin. With ``contact`` (hard
    rods): chi^2 per bin of rho_2 at contact and the ratio measured / exact (with its standard error),
    over the bins where the exact contact density exceeds 30 % of its maximum."""
    bins = measured.x.size
    rho = exact.bin_means(bins)
    result = {
        "max_abs_dev": float(np.max(np.abs(measured.rho - rho))),
        "l1_dev_over_rho": float(np.mean(np.abs(measured.rho - rho)) / rho.mean()),
        "chi2_per_dof": float(np.mean(((measured.rho - rho) / measured.rho_err) ** 2)),
    }
    if contact:
        expected = exact.bin_means(bins, "contact")
        where = (expected > 0.3 * expected.max()) & np.isfinite(measured.contact) & (measured.contact_err > 0)
        figures = (None, None, None)  # too few pairs beyond the BCD layer to measure
        if where.sum() >= 2:
            total = expected[where].sum()
            figures = (
                float(np.mean(((measured.contact - expected) / measured.contact_err)[where] ** 2)),
                float(measured.contact[where].sum() / total),
                float(np.sqrt(np.sum(measured.contact_err[where] ** 2)) / total),
            )
        result.update(zip(("contact_chi2_per_dof", "contact_ratio", "contact_ratio_err"), figures))
    return result
