"""Trajectories (GSD, HOOMD schema: freud, OVITO, AMEP read them) and bit-exact checkpoints.

GSD frames hold positions (in the HOOMD convention [-L/2, L/2)), velocities, orientations (unit
quaternions), types ("A" mobile, "W" wall), diameters, masses and moments of inertia, the box
(Lz = 0 and dimensions = 2 in 2-D), and the angular velocities as the per-particle log quantity
``log/particles/angular_velocity`` (lab frame). Frames are flushed as they are written, so a run
that stops keeps a valid file with every frame written so far.
"""

from __future__ import annotations

import json
import os
from collections.abc import Sequence
from pathlib import Path

import gsd.fl
import gsd.hoomd
import numpy as np

from ..errors import ConfigError
from ..kernels import LawKernels
from ..schema import structure
from .config import LangevinConfig
from .contact_law import ContactLaw
from .simulation import Simulation
from .system import Particles, State


class GSDWriter:
    """An observer for :meth:`Simulation.run` that appends a GSD (HOOMD) frame each time it is called.

    Parameters
    ----------
    path : str or pathlib.Path
        The ``.gsd`` file.
    particles : Particles
        The particles (radii, masses; walls get type "W").
    mode : str
        The file mode of gsd.hoomd.open: "w" writes a new file, "a" appends.
    """

    def __init__(self, path: str | Path, particles: Particles, mode: str = "w"):
        self.path = Path(path)
        self.particles = particles
        self.file = gsd.hoomd.open(str(self.path), mode)

    def frame(self, state: State) -> gsd.hoomd.Frame:
        """The GSD frame of a state: positions centred on the box [sigma], velocities [sigma/t0],
        orientations, diameters, masses and moments of inertia, types "A" (mobile) and "W" (wall).

        Parameters
        ----------
        state : State
            The state.

        Returns
        -------
        gsd.hoomd.Frame
            The frame.
        """
        p = self.particles
        frame = gsd.hoomd.Frame()
        frame.configuration.step = state.step
        frame.configuration.dimensions = state.dim
        frame.configuration.box = [*state.box.tolist(), 0.0, 0.0, 0.0]
        frame.particles.N = p.radius.size
        frame.particles.types = ["A", "W"]
        frame.particles.typeid = np.where(p.mobile, 0, 1).astype(np.uint32)
        half = np.where(state.box > 0, state.box / 2, 0.0)
        frame.particles.position = (state.position - half).astype(np.float32)
        frame.particles.velocity = state.velocity.astype(np.float32)
        frame.particles.orientation = state.orientation.astype(np.float32)
        frame.particles.diameter = (2 * p.radius).astype(np.float32)
        frame.particles.mass = p.mass.astype(np.float32)
        frame.particles.moment_inertia = np.repeat(p.inertia[:, None], 3, axis=1).astype(np.float32)
        frame.log["particles/angular_velocity"] = state.omega.astype(np.float32)
        return frame

    def __call__(self, simulation: Simulation) -> None:
        self.file.append(self.frame(simulation.state))
        self.file.flush()

    def close(self) -> None:
        """Close the file."""
        self.file.close()

    def __enter__(self) -> GSDWriter:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def truncate_trajectory(path: str | Path, step: int) -> None:
    """Drop the frames after ``step`` (to resume from an earlier checkpoint), rewriting the file
    atomically only if there are any."""
    path = Path(path)
    name = "configuration/step"  # omitted where it equals frame 0's (or, in frame 0, the default 0)
    with gsd.fl.open(str(path), "r") as handle:
        stored = [int(handle.read_chunk(i, name)[0]) if handle.chunk_exists(i, name) else None for i in range(handle.nframes)]
    steps = [s if s is not None else (stored[0] or 0) for s in stored]
    keep = sum(s <= step for s in steps)
    if keep < len(steps):
        temporary = path.with_name(path.name + ".tmp")
        with gsd.hoomd.open(str(path), "r") as old, gsd.hoomd.open(str(temporary), "w") as new:
            for frame in old[:keep]:
                new.append(frame)
        os.replace(temporary, path)


def save_checkpoint(path: str | Path, simulation: Simulation) -> Path:
    """Everything needed to continue bit-identically (state, particles, configuration, the law file
    and its hash), written atomically (a temporary file, then a rename).

    Parameters
    ----------
    path : str | Path
        The ``.npz`` file to write.
    simulation : Simulation
        The simulation to save.

    Returns
    -------
    Path
        The path written.
    """
    path = Path(path)
    s, p = simulation.state, simulation.particles
    temporary = path.with_name(path.name + ".tmp")
    with open(temporary, "wb") as handle:
        np.savez(
            handle,
            position=s.position,
            velocity=s.velocity,
            omega=s.omega,
            orientation=s.orientation,
            box=s.box,
            dim=s.dim,
            step=s.step,
            radius=p.radius,
            mass=p.mass,
            inertia=p.inertia,
            mobile=p.mobile,
            config=json.dumps(simulation.config.as_dict()),
            law_file=str(simulation.kernels.path or ""),
            law_hash=simulation.kernels.source_hash,
            **({"mode_laws": json.dumps([law.record() for law in simulation.law.laws[1:]])} if len(simulation.law.laws) > 1 else {}),
        )
    os.replace(temporary, path)
    return path


def checkpoint_config(path: str | Path) -> LangevinConfig:
    """The configuration a checkpoint was run with.

    What an edge resolves the law of before :func:`load_checkpoint` (``config.law`` names the laws).

    Parameters
    ----------
    path : str or pathlib.Path
        A file written by :func:`save_checkpoint`.

    Returns
    -------
    LangevinConfig
        The stored configuration.
    """
    with np.load(Path(path)) as data:
        return _stored_config(data)


def _stored_config(data) -> LangevinConfig:
    stored = json.loads(str(data["config"]))
    stored["law"].setdefault("contact_scheme", "explicit")  # written before the pairwise step existed
    return structure(LangevinConfig, stored, "checkpoint")


def load_checkpoint(path: str | Path, law: ContactLaw | LawKernels | Sequence[LawKernels]) -> Simulation:
    """A Simulation that continues exactly where :func:`save_checkpoint` left it.

    A checkpoint records the law files it ran (path and hash; those of the rolling and spinning laws
    too): resuming with kernels of another version of a law is refused.

    Parameters
    ----------
    path : str | Path
        A file written by :func:`save_checkpoint`.
    law : ContactLaw | LawKernels | Sequence[LawKernels]
        The resolved contact law of the stored configuration, as :class:`Simulation` takes it
        (a ContactLaw, or the kernels of each law of ``[law]``: name, rolling, spinning).

    Returns
    -------
    Simulation
        The simulation at the saved step.
    """
    with np.load(Path(path)) as data:
        config = _stored_config(data)
        particles = Particles(data["radius"], data["mass"], data["inertia"], data["mobile"])
        state = State(
            data["position"].copy(),
            data["velocity"].copy(),
            data["omega"].copy(),
            data["orientation"].copy(),
            data["box"].copy(),
            int(data["dim"]),
            int(data["step"]),
        )
        recorded = (str(data["law_file"]), str(data["law_hash"])) if "law_hash" in data.files else None
        modes = json.loads(str(data["mode_laws"])) if "mode_laws" in data.files else []
    simulation = Simulation(config, particles, state, law)
    laws = [mode_law.kernels for mode_law in simulation.law.laws]
    ran = [*([[config.law.name, *recorded]] if recorded is not None else []), *modes]
    for (name, file, digest), kernels in zip(ran, laws if recorded is not None else laws[1:]):
        if digest != kernels.source_hash:
            given = f"{kernels.path or kernels.name} (hash {kernels.source_hash[:12]})"
            raise ConfigError(
                "law",
                f"the checkpoint ran {file or f'law {name}'} (hash {digest[:12]}), not {given}",
                "resume with the law file the run started with, or start a new run",
            )
    return simulation
