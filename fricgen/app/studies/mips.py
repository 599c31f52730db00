"""Motility-induced phase separation (MIPS): the local area fraction on a grid and the bimodality of
its histogram (the paper's test, sec. II B 3, done there with AMEP).

Local area fraction of discs of radii R_i at r_i (lengths in sigma), on a periodic grid of spacing
about ``spacing``:

    phi(r) = sum_i pi R_i^2 G_s(r - r_i),   G_s(x) = exp(-|x|^2 / 2 s^2) / (2 pi s^2),

a Gaussian kernel density of width s = ``kernel`` (freud's ``GaussianDensity``, the estimator of
AMEP's ``gkde``), cut at 4 s. It integrates to the disc area of each particle, so phi averages to
the global area fraction; the kernel covers about 4 pi s^2 = 28 sigma^2 for s = 1.5, enough
particles to tell a gas from a liquid, yet a few sigma, below the size of a MIPS domain.

The grid values of the last frames are pooled into one histogram p(phi) (bins of 0.01), smoothed
with a Gaussian of width 0.03. Criterion (:func:`bimodality`): the run is phase separated when p
has two maxima at least ``SEPARATION`` = 0.2 apart (the highest one and the highest one that far
from it) and the lowest p between them is at most ``DIP`` = 0.5 of the lower maximum, with at least
``MINORITY`` = 5 % of the grid on each side of that minimum. The maxima are the dilute and dense
area fractions (the modes of the coexisting phases). A ``fricgen run`` of active discs (the kind
``active``, 2-D) gets the verdict as the ``mips`` entry of its summary (:func:`summarize_run`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import freud
import gsd.hoomd
import numpy as np
from matplotlib.collections import EllipseCollection
from matplotlib.figure import Figure
from scipy.ndimage import gaussian_filter1d

from ..run.config import RunConfig
from ..run.outputs import TRAJECTORY

if TYPE_CHECKING:  # a name only: importing the study (as fricgen.app does) compiles no engine
    from ...langevin.simulation import Simulation

KERNEL, SPACING = 1.5, 1.0  # sigma
BIN, SMOOTHING, TOP = 0.01, 0.03, 1.2  # area fraction; values above TOP count in the last bin
SEPARATION, DIP, MINORITY = 0.2, 0.5, 0.05


@dataclass(frozen=True)
class Frame:
    """A 2-D configuration: centres (N, 2), disc radii (N,), periodic box (Lx, Ly)."""

    position: np.ndarray
    radius: np.ndarray
    box: tuple[float, float]


@dataclass(frozen=True)
class Mips:
    """The verdict and the numbers behind it (flat, JSON-simple: the ``mips`` entry of summary.json).
    ``phi_dilute``/``phi_dense``: the two maxima (None when not separated); ``dip_ratio``: p at the
    minimum between the two highest separated maxima over the lower one (None with one maximum);
    ``dense_share``: the fraction of the grid above that minimum; ``phi``/``probability``: the
    smoothed histogram."""

    phase_separated: bool
    criterion: str
    phi_dilute: float | None
    phi_dense: float | None
    dip_ratio: float | None
    dense_share: float | None
    phi_mean: float
    frames: int
    steps: list[int]
    kernel: float
    spacing: float
    phi: list[float]
    probability: list[float]

    def as_dict(self) -> dict:
        return asdict(self)


CRITERION = (
    f"two maxima of the smoothed local area fraction histogram at least {SEPARATION} apart, "
    f"the minimum between them at most {DIP} of the lower maximum, at least {MINORITY:.0%} of the grid on each side"
)


def too_small(box: tuple[float, float], kernel: float) -> str | None:
    """Why a box is too small for the kernel (not over 8 widths on a side: the cut kernel would see
    itself through the periodic boundary), or None."""
    if min(box) > 8 * kernel:
        return None
    return f"the box {list(box)} must exceed 8 kernel widths ({8 * kernel:g}) on each side"


def local_area_fraction(frame: Frame, kernel: float = KERNEL, spacing: float = SPACING) -> np.ndarray:
    """phi on a grid of round(L / spacing) cells per side (a ValueError for a bad frame or width)."""
    position, radius, box = np.asarray(frame.position, float), np.asarray(frame.radius, float), frame.box
    if position.ndim != 2 or position.shape[1] not in (2, 3) or radius.shape != (len(position),) or len(position) == 0:
        raise ValueError(f"need N >= 1 positions (N, 2) and N radii, got {position.shape} and {radius.shape}")
    if not (kernel > 0 and spacing > 0):
        raise ValueError(f"kernel and spacing must be positive, got {kernel} and {spacing}")
    if reason := too_small(box, kernel):
        raise ValueError(reason)
    points = np.zeros((len(position), 3))
    points[:, :2] = position[:, :2]
    cells = [max(8, round(length / spacing)) for length in box]
    density = freud.density.GaussianDensity(cells, 4 * kernel, kernel)
    density.compute((freud.box.Box(box[0], box[1], is2D=True), points), values=np.pi * radius**2)
    return np.asarray(density.density, dtype=float)


def local_maxima(probability: np.ndarray) -> np.ndarray:
    """The indices of the local maxima of a histogram p (bins i with p_(i-1) < p_i >= p_(i+1), p = 0
    beyond the range, so a maximum in the first or last bin counts). Their number is the paper's
    criterion (two maxima: a bimodal distribution); :func:`bimodality` adds the strict one."""
    padded = np.pad(np.asarray(probability, float), 1)
    return np.flatnonzero((padded[1:-1] > padded[:-2]) & (padded[1:-1] >= padded[2:]))


def bimodality(values: np.ndarray) -> tuple[np.ndarray, np.ndarray, dict]:
    """The smoothed histogram (centres, probability density) of the pooled grid values, and the
    criterion's numbers: ``phase_separated``, the two maxima, ``dip_ratio``, ``dense_share``."""
    edges = np.arange(0.0, TOP + BIN / 2, BIN)
    counts, _ = np.histogram(np.clip(values, 0.0, TOP - BIN / 2), edges)
    probability = gaussian_filter1d(counts / (counts.sum() * BIN), SMOOTHING / BIN, mode="constant")
    centres = 0.5 * (edges[1:] + edges[:-1])
    maxima = local_maxima(probability)
    verdict = {"phase_separated": False, "phi_dilute": None, "phi_dense": None, "dip_ratio": None, "dense_share": None}
    first = maxima[np.argmax(probability[maxima])]
    far = maxima[np.abs(centres[maxima] - centres[first]) >= SEPARATION]
    if far.size == 0:
        return centres, probability, verdict
    second = far[np.argmax(probability[far])]
    low, high = sorted((first, second))
    dip = low + np.argmin(probability[low : high + 1])
    ratio = probability[dip] / min(probability[low], probability[high])
    share = float(np.mean(values > centres[dip]))
    separated = ratio <= DIP and MINORITY <= share <= 1 - MINORITY
    verdict.update(dip_ratio=float(ratio), dense_share=share, phase_separated=bool(separated))
    if separated:
        verdict.update(phi_dilute=float(centres[low]), phi_dense=float(centres[high]))
    return centres, probability, verdict


def detect(frames: Sequence[Frame], steps: Sequence[int] = (), kernel: float = KERNEL, spacing: float = SPACING) -> Mips:
    """The MIPS verdict of one or more frames (their grid values pooled into one histogram)."""
    if not frames:
        raise ValueError("need at least one frame")
    values = np.concatenate([local_area_fraction(frame, kernel, spacing).ravel() for frame in frames])
    centres, probability, verdict = bimodality(values)
    return Mips(
        criterion=CRITERION,
        phi_mean=float(values.mean()),
        frames=len(frames),
        steps=[int(s) for s in steps],
        kernel=kernel,
        spacing=spacing,
        phi=np.round(centres, 4).tolist(),
        probability=np.round(probability, 5).tolist(),
        **verdict,
    )


def read_frames(path: str | Path, last: int = 10, first_step: int = 0) -> tuple[list[Frame], list[int]]:
    """The last ``last`` frames at steps >= ``first_step`` of a 2-D GSD trajectory (mobile particles,
    type 0, as fricgen writes them), and their steps."""
    with gsd.hoomd.open(str(path), "r") as trajectory:
        steps = [int(frame.configuration.step) for frame in trajectory]
        chosen = [i for i, step in enumerate(steps) if step >= first_step][-last:] if last > 0 else []
        frames = [_frame(trajectory[i], path) for i in chosen]
    return frames, [steps[i] for i in chosen]


def _frame(snapshot: gsd.hoomd.Frame, path) -> Frame:
    if snapshot.configuration.dimensions != 2:
        raise ValueError(f"{path}: MIPS detection needs a 2-D trajectory, frame has {snapshot.configuration.dimensions} dimensions")
    mobile = snapshot.particles.typeid == 0
    box = snapshot.configuration.box
    return Frame(snapshot.particles.position[mobile, :2], snapshot.particles.diameter[mobile] / 2, (float(box[0]), float(box[1])))


def detect_trajectory(path: str | Path, last: int = 10, first_step: int = 0, **grid) -> Mips:
    """The verdict of a GSD trajectory's last frames after ``first_step``, e.g.
    ``detect_trajectory("fricgen-active/trajectory.gsd", first_step=2_000_000).phase_separated``."""
    frames, steps = read_frames(path, last, first_step)
    if not frames:
        raise ValueError(f"{path}: no frame at step >= {first_step}")
    return detect(frames, steps, **grid)


def run_mips(folder: Path, trajectory: Path, final: Frame, step: int, first_step: int, last: int = 10) -> dict:
    """The ``mips`` entry of a run's summary.json and its figure ``local_density.png``: the GSD frames
    at steps >= ``first_step`` (the averaging window, at most the last ``last``) and the final state
    when it is not the last frame (or when there is no trajectory). A box under 8 kernel widths gets
    ``phase_separated`` None and the reason, and no figure."""
    if reason := too_small(final.box, KERNEL):
        return {"phase_separated": None, "criterion": CRITERION, "reason": reason}
    frames, steps = read_frames(trajectory, last, first_step) if trajectory.exists() else ([], [])
    if not steps or steps[-1] != step:
        frames, steps = [*frames, final][-last:], [*steps, step][-last:]
    mips = detect(frames, steps)
    local_density_figure(mips, frames[-1], folder / "local_density.png", f"step {steps[-1]}")
    return mips.as_dict()


def summarize_run(config: RunConfig, simulation: Simulation, folder: Path, summary: dict) -> dict | None:
    """The ``mips`` entry of an active run's summary (:func:`run_mips` of its trajectory after
    ``run.equilibrate`` and its final state); None in 3-D."""
    state, particles = simulation.state, simulation.particles
    if state.dim != 2:
        return None
    mobile = particles.mobile
    final = Frame(state.position[mobile, :2], particles.radius[mobile], tuple(state.box[:2].tolist()))
    return run_mips(folder, folder / TRAJECTORY, final, state.step, config.run.equilibrate)


def describe_run(mips: dict) -> list[str]:
    """The verdict's line in the report of ``fricgen run`` (none for a box too small to tell)."""
    if mips.get("phase_separated") is None:
        return []
    phases = "no"
    if mips["phase_separated"]:
        phases = f"phase separated: dilute phi = {mips['phi_dilute']:.3f}, dense phi = {mips['phi_dense']:.3f}"
    return [f"MIPS ({mips['frames']} frames): {phases}; local_density.png"]


def local_density_figure(mips: Mips, frame: Frame, path: Path, title: str = "") -> Path:
    """The pooled histogram p(phi) with its maxima (left) and the frame's discs coloured by phi (right)."""
    figure = Figure(figsize=(11, 4.8), layout="constrained")
    histogram, snapshot = figure.subplots(1, 2, width_ratios=(1, 1.1))
    draw_histogram(histogram, mips)
    mappable = draw_snapshot(snapshot, frame, mips.kernel, mips.spacing)
    figure.colorbar(mappable, ax=snapshot, label=r"local area fraction $\phi$")
    snapshot.set_title(title)
    figure.savefig(path, dpi=110)
    return path


def draw_histogram(axis, mips: Mips, label: str = "", colour: str = "tab:blue") -> None:
    verdict = "phase separated" if mips.phase_separated else "not separated"
    axis.plot(mips.phi, mips.probability, color=colour, label=f"{label}{verdict}")
    for value in (mips.phi_dilute, mips.phi_dense):
        if value is not None:
            axis.axvline(value, color=colour, ls="--", lw=0.8)
    axis.set_xlabel(r"local area fraction $\phi$")
    axis.set_ylabel(r"$p(\phi)$")
    axis.set_xlim(0, TOP)
    axis.set_title(f"{mips.frames} frame(s), kernel {mips.kernel:g}$\\sigma$; mean $\\phi$ = {mips.phi_mean:.3f}", fontsize=9)
    axis.legend(frameon=False, fontsize=8)


def draw_snapshot(axis, frame: Frame, kernel: float = KERNEL, spacing: float = SPACING):
    """The discs (true size) coloured by phi at their grid cell; returns the mappable."""
    field = local_area_fraction(frame, kernel, spacing)
    box = np.asarray(frame.box)
    wrapped = np.mod(np.asarray(frame.position)[:, :2] + box / 2, box)
    cell = np.minimum((wrapped / box * field.shape).astype(int), np.array(field.shape) - 1)
    discs = EllipseCollection(
        2 * frame.radius, 2 * frame.radius, 0, units="xy", offsets=wrapped, offset_transform=axis.transData, cmap="viridis"
    )
    discs.set_array(field[cell[:, 0], cell[:, 1]])
    discs.set_clim(0, 1)
    axis.add_collection(discs)
    axis.set_xlim(0, box[0])
    axis.set_ylim(0, box[1])
    axis.set_aspect("equal")
    axis.set_xticks([])
    axis.set_yticks([])
    return discs
