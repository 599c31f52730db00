"""The time step of active Langevin particles: one state, continued at several dt.

Loads a ``checkpoint.npz`` of a ``fricgen run active`` run (e.g. a phase-separated one from
benchmarks/mips_fig7.py), continues it for ``--time`` t_R at each dt, and prints per dt: the kinetic
temperatures T_trans = m <v_a^2> and T_rot = I <omega^2> (block errors), the closest approach of two
centres (in sigma; WCA with epsilon = 10 kT), and the MIPS verdict with its dilute and dense area
fractions (frames every 0.05 t_R pooled). A dt passes when it does not blow up and matches the
smallest dt within the errors; run it with and without the contact noise.
Run: NUMBA_NUM_THREADS=1 python benchmarks/mips_timestep.py CHECKPOINT [--time 1] [--dt 5e-5 1e-4 2e-4 4e-4 8e-4]
"""

from __future__ import annotations

import argparse
import dataclasses
import time

import freud
import numpy as np

from fricgen.app.studies.mips import Frame, detect
from fricgen.errors import SimulationError
from fricgen.kernels import load_law_kernels
from fricgen.langevin.analysis import block_estimate, temperatures
from fricgen.langevin.simulation import Simulation
from fricgen.langevin.trajectory import checkpoint_config, load_checkpoint


def closest_approach(frame: Frame) -> float:
    box = freud.box.Box(*frame.box, is2D=True)
    points = np.c_[frame.position, np.zeros(len(frame.position))]
    pairs = freud.locality.AABBQuery(box, points).query(points, {"r_max": 1.5, "exclude_ii": True}).toNeighborList()
    return float(pairs.distances.min())


def continue_at(path: str, dt: float, duration: float) -> str:
    stored = checkpoint_config(path)
    loaded = load_checkpoint(path, load_law_kernels(stored.law.name))
    config = dataclasses.replace(loaded.config, thermostat=dataclasses.replace(loaded.config.thermostat, dt=dt))
    simulation = Simulation(config, loaded.particles, loaded.state, loaded.law)
    simulation.threads = 1
    mobile, t, frames = loaded.particles.mobile, [], []

    def sample(sim: Simulation) -> None:
        t.append(temperatures(sim.state, sim.particles))
        frames.append(Frame(sim.state.position[mobile, :2].copy(), sim.particles.radius[mobile], tuple(sim.state.box[:2].tolist())))

    start = time.process_time()
    try:
        simulation.run(round(duration / dt), every=max(1, round(0.05 / dt)), observers=[sample])
    except SimulationError as error:
        return f"blew up: {error}"
    seconds = time.process_time() - start
    trans, rot = (block_estimate(np.array(series), blocks=5) for series in zip(*t))
    mips = detect(frames)
    verdict = f"separated, dilute {mips.phi_dilute:.3f} dense {mips.phi_dense:.3f}" if mips.phase_separated else "not separated"
    dip = "-" if mips.dip_ratio is None else f"{mips.dip_ratio:.2f}"
    return (
        f"T_trans = {trans.mean:.3f} +- {trans.error:.3f}  T_rot = {rot.mean:.3f} +- {rot.error:.3f}  "
        f"closest {min(closest_approach(f) for f in frames):.3f}  {verdict} (dip {dip})  {seconds:.0f} s CPU"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("checkpoint")
    parser.add_argument("--time", type=float, default=1.0, help="t_R per dt")
    parser.add_argument("--dt", type=float, nargs="+", default=[5e-5, 1e-4, 2e-4, 4e-4, 8e-4])
    args = parser.parse_args()
    law = checkpoint_config(args.checkpoint).law
    print(f"{args.checkpoint}: friction {law.friction}, contact noise {law.contact_noise}; {args.time:g} t_R per dt")
    for dt in args.dt:
        print(f"  dt = {dt:g}: {continue_at(args.checkpoint, dt, args.time)}", flush=True)


if __name__ == "__main__":
    main()
