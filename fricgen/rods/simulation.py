"""Rods in an external field with BCD: runs of independent replicas, profiles with errors.

Units as in the paper: lambda = 1, D = 1, kT = 1 (mu = D / kT). Observables are folded onto one
wavelength: rho(x) (B-25) and rho_2(x, x + sigma) (B-26) at bin centres, with standard errors from
the scatter between independent replicas, each started from an equilibrium configuration sampled
by Monte Carlo (fricgen.rods.mc).

Time-step error depends on the contact layer (RodNumerics.contact_layer, fricgen.rods.contact;
docs/physics-bcd-contact-layer.md). BCD's own "merge": the rods of a merged cluster touch exactly (gap 0)
after a step. This atom of exact contacts holds about 0.7 rho_2(0) s of pair density, s = sqrt(4 D dt)
the rms change of a gap per step (the discrete-monitoring shift of a reflecting wall), taken from the
gaps just above contact. So BCD behaves like rods shortened by O(s): profile and contact density carry
an O(sqrt(dt)) bias (measured: the contact density of the uniform fluid at rho_bar sigma = 0.7 is 5 %
low at dt = 1e-5, 2 % at 1e-6). "bridge" pushes a pair apart by its bridge's excursion below contact:
O(dt), no layer. "reflect" (elastic exchange): O(dt) away from contact, O(sqrt(dt)) within s of it.

Contact density (B-26). bridge: the local time of the gaps at contact, E[dL] = 2 D rho_2(x, sigma+) dt,
from the expected push given each step's end points (no fit). merge and reflect: the pair density at gap
g beyond the layer, g in [3 s, 3 s + fit_bins w], is fitted per bin by ln rho_2(x, g) = a + b g and
extrapolated to g = 0; the exact contacts are not counted. The Metropolis-adjusted bridge (drift_scheme
"metropolis", fricgen.rods.adjusted) samples the exact equilibrium: the same fit from g = 0. Errors by jackknife over replicas. This
holds for hard rods only: within the range of a sticky or pair interaction the pair density is not
exponential in g and the force acts at contact (deviations() compares it for hard rods only).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ConfigError, SimulationError
from . import bcd, mc
from .comparison import RodProfiles, compressibility
from .config import CONTACT_LAYERS, DRIFT_SCHEMES, RodConfig
from .interactions import field_kernels, pair_kernels
from .records import Ring, Stepping
from .stability import warn_step
from .sticky import LONG_STEP

#: Steps per compiled call of :meth:`RodSimulation.advance` (about 0.1 s per replica at N = 50): a
#: compiled loop cannot be interrupted, so Ctrl-C takes effect between calls. The noise is keyed on
#: the step, so any chunking gives the same trajectory bit for bit.
CHUNK_STEPS = 20_000
#: Monte Carlo moves per rod ring and compiled call of :meth:`RodSimulation.thermalize` (about 0.1 s per
#: replica), so that Ctrl-C stops the start too; a sweep is keyed on its index, so any chunking gives
#: the same start bit for bit.
CHUNK_MOVES = 1_000_000


class RodSimulation:
    """Independent replicas of one ring, started from equilibrium (Monte Carlo) and evolved by Brownian
    cluster dynamics (BCD; docs/physics.md#brownian-cluster-dynamics).

    Parameters
    ----------
    config : RodConfig
        The run.
    positions : numpy.ndarray, optional
        The start [lambda] (N or replicas x N, ordered, no overlaps) instead of free hard rods in
        equilibrium, before the config's Monte Carlo sweeps; required on an open line (length = inf),
        which has no Monte Carlo start and no profiles.
    """

    def __init__(self, config: RodConfig, positions: np.ndarray | None = None):
        self.config = config
        model = config.model
        warn_step(model, config.numerics.dt, config.numerics.tested)
        self._field, field_params = field_kernels(model)  # energy and force kernels
        self._pair, pair_params, pair_range = pair_kernels(model)
        self.ring = Ring(model.length, model.sigma, model.mu, model.kT, model.diffusion, model.drive, model.wavelength,
                         field_params, pair_params, pair_range, not (model.hard_rods or model.sticky_boundary),
                         model.gamma if model.sticky_boundary else 0.0)  # fmt: skip
        if positions is None and model.open_line:
            raise ConfigError("positions", "an open line (length = inf) needs initial positions", "give them")
        self.positions = self._initial() if positions is None else self._given(positions)
        self.step, self.sweep = 0, 0
        self.rejected = np.zeros(config.sampling.replicas, dtype=np.int64)  # steps the Metropolis test rejected
        self.acceptance = self.thermalize(config.start_sweeps)

    def _initial(self) -> np.ndarray:
        """Rods with Gamma-distributed gaps (fricgen.rods.mc.free_rods) whose long density waves have the exact
        theory's chi, shape = chi_0 / chi: the fluctuations that the Monte Carlo sweeps relax only over ~1e4
        sweeps (free hard rods, shape 1, where the theory cannot be solved: a sigma / lambda off its grids)."""
        m = self.config.model
        try:
            shape = m.mean_density * (1 - m.mean_density * m.sigma) ** 2 / compressibility(self.config)
        except ConfigError:
            shape = 1.0
        return mc.free_rods(m.n, m.length, m.sigma, self.config.sampling.replicas, self.config.numerics.seed, shape)

    def _given(self, positions: np.ndarray) -> np.ndarray:
        """A copy of the given start for every replica; ConfigError unless ordered without overlaps."""
        m = self.config.model
        x = np.array(np.broadcast_to(np.asarray(positions, dtype=float), (self.config.sampling.replicas, m.n)), order="C")
        after = np.concatenate([x[:, 1:], x[:, :1] + m.length], axis=1)  # inf on an open line
        ordered = np.isfinite(x).all() and np.all(after - x >= m.sigma)
        if not ordered:
            raise ConfigError("positions", f"must be finite, ordered and at least sigma = {m.sigma} apart (around the ring)", "fix them")
        return x

    def thermalize(self, sweeps: int) -> float:
        """Metropolis sweeps (fricgen.rods.mc) towards the exact equilibrium of the model, with no time step.

        Parameters
        ----------
        sweeps : int
            The number of sweeps.

        Returns
        -------
        float
            The acceptance ratio [1].
        """
        seed = self.config.numerics.seed
        chunk = max(1, CHUNK_MOVES // self.config.model.n)
        accepted = 0.0
        for done in range(0, sweeps, chunk):
            count = min(chunk, sweeps - done)
            field, pair = self._field.energy, self._pair.energy
            accepted += count * mc.metropolis_sweeps(self.positions, self.ring, field, pair, count, self.sweep, seed)
            self.sweep += count
        return accepted / max(1, sweeps)

    def equilibrate(self, duration: float, dt: float | None = None) -> None:
        """Run without sampling.

        Parameters
        ----------
        duration : float
            The time [lambda^2/D].
        dt : float, optional
            The time step [lambda^2/D]; None: the config's.
        """
        dt = dt or self.config.numerics.dt
        self.advance(int(round(duration / dt)), dt=dt)

    def advance(self, steps: int, counts: tuple[np.ndarray, np.ndarray] | None = None, dt: float | None = None) -> None:
        """Advance all replicas.

        Parameters
        ----------
        steps : int
            The number of steps.
        counts : tuple of numpy.ndarray, optional
            (rods per replica and bin, gaps per replica, bin and gap bin), accumulated in place.
        dt : float, optional
            The time step [lambda^2/D]; None: the config's.
        """
        numerics, sampling = self.config.numerics, self.config.sampling
        shape = (sampling.replicas, sampling.bins)
        counts = counts or (np.zeros(shape), np.zeros((*shape, sampling.gap_bins)))
        layer, drift = CONTACT_LAYERS.index(numerics.contact_layer), DRIFT_SCHEMES.index(numerics.drift_scheme)
        for done in range(0, steps, CHUNK_STEPS):
            chunk = min(CHUNK_STEPS, steps - done)
            stepping = Stepping(dt or numerics.dt, chunk, self.step, numerics.seed, sampling.gap_width, layer, drift)
            field, pair = self._field, self._pair
            status = bcd.advance_rods(
                self.positions, self.ring, stepping, field.force_field, field.energy, pair.force, counts, self.rejected
            )
            if status == bcd.PASSED:
                raise SimulationError(f"rods overlapped near step {self.step + chunk}: a bug or a non-finite force")
            if status == bcd.ALL_IN_CONTACT:
                raise SimulationError("all rods are in contact (close packing): BCD cannot split the ring")
            if status == LONG_STEP:
                raise SimulationError(f"a bond's detach probability per step exceeded 1 near step {self.step + chunk}: reduce dt")
            self.step += chunk

    @property
    def rejection(self) -> float:
        """The fraction of the steps so far (all replicas) that the Metropolis test rejected (drift_scheme
        "metropolis", fricgen.rods.adjusted; 0 for the other schemes)."""
        return float(self.rejected.sum()) / max(1, self.step * self.rejected.size)

    def run(self, steps: int) -> RodProfiles:
        """Sample the profiles; the replicas are the independent samples of the errors.

        Within one ring the occupation of the wells changes only by hopping over the barriers (about 20
        time units per rod at U0 = 6), longer than a typical run, so time blocks of one ring are not
        independent; replicas started from independent equilibrium configurations are.

        Parameters
        ----------
        steps : int
            The number of steps of ``config.numerics.dt``.

        Returns
        -------
        RodProfiles
            The density and contact density with their errors.
        """
        m, c = self.config.model, self.config.sampling
        if m.open_line:
            raise ConfigError("model.length", "profiles need a ring of finite length", "on an open line use advance() and positions")
        self.config.require_sampling()
        if steps < 1:
            raise ConfigError("steps", f"need at least one step, got {steps}", "sample longer")
        width = m.wavelength / c.bins
        scale = steps * width * m.length / m.wavelength  # sampled length per bin
        rods, gaps = np.zeros((c.replicas, c.bins)), np.zeros((c.replicas, c.bins, c.gap_bins))
        self.advance(steps, (rods, gaps))
        rho = rods / scale
        contact, covariance = self._contact(gaps / (scale * c.gap_width))
        return RodProfiles(
            (np.arange(c.bins) + 0.5) * width,
            rho.mean(0),
            rho.std(0, ddof=1) / math.sqrt(c.replicas),
            contact,
            np.sqrt(np.diagonal(covariance)),
            steps,
            covariance,
        )

    def _contact(self, pair_density: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """rho_2 at contact per bin from the gap histograms of the replicas (replicas, bins, gap bins), and
        the covariance of these estimates between bins (bins x bins).

        bridge: the local time in gap bin 0, covariance from the scatter between replicas. merge and
        reflect: beyond the BCD layer, g >= g0, the mean pair densities A and B over two windows
        [g0, g0 + d) and [g0 + d, g0 + 2d) fix rho_2(g) = rho_2(0) exp(-k g): k = ln(A / B) / d,
        rho_2(0) = A exp(k g0) (k d) / (1 - exp(-k d)); covariance by jackknife over the replicas. The
        bins of one ring are correlated (its long-wavelength density fluctuations and the occupation of
        its wells change all of them), so a sum over bins needs the covariance, not the errors alone."""
        c = self.config.sampling
        if self.config.model.sticky_boundary:  # gap bin 0 holds the bonded pairs: gamma rho_2(x, x + sigma+)
            bonded = pair_density[:, :, 0] * c.gap_width / self.config.model.gamma
            return bonded.mean(0), np.atleast_2d(np.cov(bonded, rowvar=False)) / bonded.shape[0]
        if self.config.numerics.contact_layer == "bridge" and not self.config.numerics.tested:  # gap bin 0: local time
            local = pair_density[:, :, 0]
            return local.mean(0), np.atleast_2d(np.cov(local, rowvar=False)) / local.shape[0]
        half = c.fit_bins // 2
        first = self.config.contact_fit_bins() - 2 * half  # RodConfig checked that gap_bins suffice
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
        deviation = leave_one_out - leave_one_out.mean(0)  # bins without pairs in a window stay NaN
        return extrapolate(*np.moveaxis(total / samples, -1, 0)), (samples - 1) / samples * deviation.T @ deviation


def extrapolate_to_zero_dt(coarse: RodProfiles, fine: RodProfiles, ratio: float, order: float = 0.5) -> RodProfiles:
    """Remove a bias of O(dt^order) from runs at dt and dt / ratio (Richardson).

    X(0) = (r X_fine - X_coarse) / (r - 1) with r = ratio^order; the errors and covariances of the
    independent runs are added.

    Parameters
    ----------
    coarse : RodProfiles
        The run at dt.
    fine : RodProfiles
        The run at dt / ratio.
    ratio : float
        The ratio of the time steps [1].
    order : float
        The bias order, ``RodNumerics.error_order``: 1/2 for BCD's merge layer, 1 for bridge and reflect.

    Returns
    -------
    RodProfiles
        The extrapolated profiles.
    """
    r = ratio**order

    def combine(a, b):
        return (r * b - a) / (r - 1)

    def error(a, b):
        return np.hypot(r * b, a) / (r - 1)

    known = coarse.contact_cov is not None and fine.contact_cov is not None
    return RodProfiles(
        fine.x,
        combine(coarse.rho, fine.rho),
        error(coarse.rho_err, fine.rho_err),
        combine(coarse.contact, fine.contact),
        error(coarse.contact_err, fine.contact_err),
        coarse.steps + fine.steps,
        (r**2 * fine.contact_cov + coarse.contact_cov) / (r - 1) ** 2 if known else None,
    )
