"""The bulk shear viscosity of issue 28 (eta at gamma_f = 6, kappa_f = 5 to +-3 %), resumable.

The transverse-current method of :mod:`fricgen.app.studies.viscosity` (docs/poiseuille.md), run as
``--segments`` independent runs (seeds 1, 2, ...), each ``--equilibrate`` t0 from a lattice and then
``--duration`` t0 sampled every 0.05 t0. Each finished segment is saved as ``segment_<seed>.npz``
(the currents, k, interval, mass density, wall seconds); the same command skips the saved segments,
so a stopped run continues with the segment it was in. The segments are joined into one series of
``--segments x --blocks`` blocks, each block inside one segment (a segment's frames are cut to a
multiple of ``--blocks``), and :func:`~fricgen.app.studies.viscosity.transverse_viscosity` gives
eta(k) per k, the extrapolation eta(k -> 0) and their jackknife errors over the blocks, written
to ``bulk_viscosity.json`` (also with only the segments finished so far).

Cost: about 0.56 ms per step for 1500 spheres on one core (single-threaded), 0.56 s per t0:
10 segments of 20 + 400 t0 are about 39 min of one core. The error falls as 1/sqrt(time): 300 t0
gave eta(k -> 0) to +-0.023 (docs/poiseuille.md), so +-3 % (+-0.007) needs about 3000-4000 t0. Units: sigma = 1, kT = 1, m = 1, t0;
eta in kT t0 / sigma^3.

Usage::

    NUMBA_NUM_THREADS=1 python docs/studies/bulk_viscosity.py --out out/bulk_g6k5
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from fricgen.app.run.config import RunLaw
from fricgen.app.studies.viscosity import bulk_config, measure_bulk_viscosity, transverse_viscosity


def run_segment(path: Path, seed: int, args: argparse.Namespace) -> None:
    """One independent run of ``args.duration`` t0 after ``args.equilibrate`` t0, saved to ``path``."""
    law = RunLaw(parameters={"gamma_f": args.gamma_f, "kappa_f": args.kappa_f})
    config = bulk_config(law, n=args.n, packing_fraction=args.packing_fraction, seed=seed)
    start = time.perf_counter()
    result, currents, k = measure_bulk_viscosity(config, args.equilibrate, args.duration, interval=args.interval, blocks=args.blocks)
    seconds = time.perf_counter() - start
    temporary = path.with_name(path.name + ".tmp.npz")
    np.savez(temporary, currents=currents, k=k, interval=args.interval, mass_density=result.mass_density, seconds=seconds, seed=seed)
    temporary.replace(path)
    print(f"segment {seed}: eta = {result.eta:.4f} +- {result.eta_err:.4f} ({seconds:.0f} s)", flush=True)


def combine(paths: list[Path], blocks: int) -> dict:
    """eta(k) and eta(k -> 0) of the saved segments joined, ``blocks`` jackknife blocks per segment."""
    segments = [np.load(path) for path in paths]
    length = min(s["currents"].shape[0] for s in segments) // blocks * blocks
    currents = np.concatenate([s["currents"][:length] for s in segments])
    first = segments[0]
    result = transverse_viscosity(currents, first["k"], float(first["interval"]), float(first["mass_density"]), blocks * len(segments))
    return result.as_dict() | {
        "segments": [int(s["seed"]) for s in segments],
        "sampled": len(segments) * length * float(first["interval"]),
        "seconds": [round(float(s["seconds"]), 1) for s in segments],
    }


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("--segments", type=int, default=10)
    parser.add_argument("--duration", type=float, default=400.0, help="sampled t0 per segment")
    parser.add_argument("--equilibrate", type=float, default=20.0, help="t0 per segment before sampling")
    parser.add_argument("--blocks", type=int, default=4, help="jackknife blocks per segment")
    parser.add_argument("--interval", type=float, default=0.05)
    parser.add_argument("--n", type=int, default=1500)
    parser.add_argument("--packing-fraction", type=float, default=0.15)
    parser.add_argument("--gamma-f", type=float, default=6.0)
    parser.add_argument("--kappa-f", type=float, default=5.0)
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "arguments.json").write_text(json.dumps({k: str(v) if isinstance(v, Path) else v for k, v in vars(args).items()}) + "\n")
    paths = []
    for seed in range(1, args.segments + 1):
        path = args.out / f"segment_{seed}.npz"
        if not path.exists():
            run_segment(path, seed, args)
        paths.append(path)
        record = combine(paths, args.blocks)
        (args.out / "bulk_viscosity.json").write_text(json.dumps(record, indent=1) + "\n")
        print(f"{len(paths)} segments, {record['sampled']:g} t0: eta = {record['eta']:.4f} +- {record['eta_err']:.4f}", flush=True)


if __name__ == "__main__":
    main()
