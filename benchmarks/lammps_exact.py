"""Benchmark of the fix fricgen/exact/coulomb_newton (the pairwise contact step) against the explicit pair
style fricgen/coulomb_newton, in LAMMPS, on the same cores, measured alternately in one run.

System: generated/lammps/coulomb_newton/in.coulomb_newton_2d_exact (2-D, N = 10 000 discs at area
fraction 0.6; with --dimension 3 in.coulomb_newton_3d_exact, N = 22^3 - 648 = 10 000 spheres; dt = 5e-3, kT = 1, no
solvent: the contacts are the thermostat): WCA from lj/cut and the
fix, against the same input with the pair style fricgen/coulomb_newton (WCA + the explicit kick) in
place of both. Rates are particle-steps per second of the timed run (after a 200-step warm-up, from
LAMMPS's "Loop time"), medians over the repeats, under `mpirun -np 1` and `-np 2`.

Printed: the cost per particle-step of each, the fix over the explicit pair style (1 and 2 ranks), and
the 2-rank throughput of each over twice its 1-rank throughput (strong scaling on 2 cores).

Run: python benchmarks/lammps_exact.py [--repeats 3] [--steps 1000] [--dimension 2] [--cells 100 (2-D), 22 (3-D)]
     python benchmarks/lammps_exact.py --figure docs/lammps-exact-phases.png   (the phases' figure of the guide)
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
from pathlib import Path

from lammps_plugin import LOOP, built_plugin, lammps_output, loop_rate

FIX = "fix             contact all fricgen/exact/coulomb_newton ${kT} ${seed} gamma_f 6.0 kappa_f 5.0 solvent ${gamma} ${gamma_r}\n"


def inputs(folder: Path, work: Path, warmup: str = "200", dimension: int = 2) -> dict[str, str]:
    """The exact template in ``dimension`` (a warm-up of ``warmup`` steps first, a number or a variable) and its
    explicit twin."""
    name = f"in.coulomb_newton_{dimension}d_exact"
    template = (folder / name).read_text()
    template = template.replace("run             ${nrun}", f"run             {warmup}\nrun             ${{nrun}}")
    if FIX not in template:
        raise RuntimeError(f"{name} has no fix line as expected: regenerate it (fricgen lammps coulomb_newton)")
    explicit = template.replace(FIX, "").replace("pair_modify     shift yes\n", "")
    explicit = explicit.replace(
        "pair_style      lj/cut 1.122462048309373\npair_coeff      * * 1.0 1.0\n",
        "pair_style      fricgen/coulomb_newton ${kT} ${seed}\npair_coeff      * * 1.0 1.0 gamma_f 6.0 kappa_f 5.0\n",
    )
    scripts = {"fix": template, "explicit": explicit}
    for name, text in scripts.items():
        (work / f"in.{name}").write_text(text)
    return {name: str(work / f"in.{name}") for name in scripts}


def phase_figure(path: str) -> None:
    """The fix's phases on 2 x 2 ranks: each sub-domain in halves along x and y, phase = (x half) + 2 (y half);
    the same phase of two ranks lies half a sub-domain (> two contact reaches + skin) apart."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    colours = ["#4c72b0", "#dd8452", "#55a868", "#c44e52"]
    figure, axes = plt.subplots(figsize=(5.2, 5.2))
    for rank_x in range(2):
        for rank_y in range(2):
            for half_x in range(2):
                for half_y in range(2):
                    phase = half_x + 2 * half_y
                    x0, y0 = 2 * rank_x + half_x, 2 * rank_y + half_y
                    axes.add_patch(plt.Rectangle((x0, y0), 1, 1, color=colours[phase], alpha=0.35, lw=0))
                    axes.text(x0 + 0.5, y0 + 0.5, f"phase {phase}", ha="center", va="center", fontsize=9)
            axes.add_patch(plt.Rectangle((2 * rank_x, 2 * rank_y), 2, 2, fill=False, lw=2.5, color="black"))
            axes.text(2 * rank_x + 0.06, 2 * rank_y + 1.9, f"rank {rank_x + 2 * rank_y}", fontsize=8, va="top")
    axes.annotate("", xy=(2.0, 0.35), xytext=(1.0, 0.35), arrowprops={"arrowstyle": "<->"})
    axes.text(1.5, 0.2, "> 2 reaches + skin", ha="center", fontsize=8)
    axes.set_xlim(0, 4)
    axes.set_ylim(0, 4)
    axes.set_aspect("equal")
    axes.set_xticks([])
    axes.set_yticks([])
    axes.set_title("fix fricgen/exact: phases run one after another;\na pair runs in the phase of its lower-ID atom", fontsize=10)
    figure.tight_layout()
    figure.savefig(path, dpi=110)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--figure", metavar="PATH", help="draw the phases' figure into PATH instead of benchmarking")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--steps", type=int, default=1000, help="timed steps per measurement")
    parser.add_argument("--dimension", type=int, choices=(2, 3), default=2)
    parser.add_argument("--cells", type=int, help="lattice cells per side (N = cells^dimension; default 100 in 2-D, 22 in 3-D)")
    options = parser.parse_args()
    if options.figure:
        phase_figure(options.figure)
        return
    lammps, folder, plugin = built_plugin()
    work = Path(tempfile.mkdtemp(prefix="fricgen-bench-"))
    scripts = inputs(folder, work, dimension=options.dimension)
    cells = options.cells or (100 if options.dimension == 2 else 22)
    extra = ["-var", "plugin", str(plugin), "-var", "solvent", "0", "-var", "cells", str(cells)]
    rates: dict[tuple[str, int], list[float]] = {}
    for _ in range(options.repeats):
        for ranks in (1, 2):
            for name, script in scripts.items():
                output = lammps_output(lammps, script, ranks, options.steps, extra, work)
                rates.setdefault((name, ranks), []).append(loop_rate(output))
                n = int(LOOP.findall(output)[-1][3])  # the atoms LAMMPS ran (the 3-D template deletes some of the lattice's)
    median = {key: statistics.median(values) for key, values in rates.items()}
    runs = f"{options.steps} timed steps, medians of {options.repeats} alternating repeats"
    print(f"{options.dimension}-D, N = {n}, dt = 5e-3, no solvent, {runs}:")
    for (name, ranks), values in sorted(rates.items()):
        spread = ", ".join(f"{v / 1e6:.2f}" for v in values)
        print(f"  {name:8s} {ranks} rank(s)  {1e6 / median[name, ranks]:.3f} us per particle-step  ({spread} M particle-steps/s)")
    for ranks in (1, 2):
        print(f"cost per particle-step, fix / explicit, {ranks} rank(s): {median['explicit', ranks] / median['fix', ranks]:.2f}")
    for name in scripts:
        print(f"2 ranks / (2 x 1 rank), {name}: {median[name, 2] / (2 * median[name, 1]):.2f}")


if __name__ == "__main__":
    main()
