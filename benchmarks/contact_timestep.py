"""T_trans and T_rot against dt for the explicit and the pairwise contact step, per catalogue law.

The passive check (2-D, area fraction 0.6, the paper's solvent and WCA, Itô) at dt = 1e-4, 1e-3 and
5e-3, with the explicit kick and with the pairwise Metropolis-adjusted step, and the pairwise step's
rejection rate (its mean rejection probability). Prints one line per law, scheme and dt.
Run: python benchmarks/contact_timestep.py [--n 256] [--time 10] [--dim 2] [--seed 1] [--schemes explicit,pairwise]
"""

from __future__ import annotations

import argparse

from fricgen.app import thermostat_check
from fricgen.errors import SimulationError

#: (law, parameter overrides): the catalogue at its defaults, and stiffer linear friction.
LAWS = [
    ("linear", {}),
    ("linear", {"gamma_f": 3.0}),
    ("linear", {"gamma_f": 10.0}),
    ("coulomb", {}),
    ("smooth_coulomb", {}),
    ("coulomb_newton", {}),
    ("viscous_cubic", {}),
]
STEPS = (1e-4, 1e-3, 5e-3)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=256)
    parser.add_argument("--time", type=float, default=10.0, help="simulated time per run (t0)")
    parser.add_argument("--dim", type=int, default=2, choices=(2, 3))
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--schemes", default="explicit,pairwise", help="the contact schemes to run, comma-separated")
    args = parser.parse_args()
    print(f"{args.dim}-D, N = {args.n}, {args.time} t0 per run, seed {args.seed}; T +- block error; rejection rate of the pairwise step")
    for law, parameters in LAWS:
        name = law + "".join(f" {key}={value:g}" for key, value in parameters.items())
        for scheme in args.schemes.split(","):
            for dt in STEPS:
                options = dict(dim=args.dim, n=args.n, dt=dt, total_time=args.time, seed=args.seed, parameters=parameters)
                try:
                    r = thermostat_check(law, contact_scheme=scheme, **options)
                except SimulationError:
                    print(f"{name:28s} {scheme:9s} dt = {dt:.0e}: blew up", flush=True)
                    continue
                rate = "" if r.rejection_rate is None else f"   rejection {r.rejection_rate:.2e}"
                print(
                    f"{name:28s} {scheme:9s} dt = {dt:.0e}: T_trans = {r.T_trans:.4f} +- {r.T_trans_err:.4f}   "
                    f"T_rot = {r.T_rot:.4f} +- {r.T_rot_err:.4f}{rate}   ({r.seconds:.0f} s)",
                    flush=True,
                )


if __name__ == "__main__":
    main()
