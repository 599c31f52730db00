"""Does LAMMPS with fix fricgen/exact/<law> keep kT at dt = 5e-3 t0? (docs/guide/lammps.md#the-exact-contact-step)

Each law's template in.<law>_<dim>d_exact (generated/lammps), smaller, with the contacts in free flight
(pair_style zero: velocity Verlet is then exact, so the contact step and the solvent are the only
dynamics of the velocities and any deviation from kT is theirs), 2-D (1600 discs) and 3-D (1728 spheres),
with and without the solvent (fix langevin), for coulomb, linear (gamma_f = 10), coulomb_newton,
rolling_coulomb_newton together with coulomb_newton (two fixes), and a law of a folder of one's own that
no test was tuned against. T_trans and T_rot: means over the samples (every 10 steps) after 2000 steps,
errors from 20 blocks. Verdict per run: |T - 1| < 0.5 % and < 4 errors.

With WCA (lj/cut) as the templates ship: the fix with and without its solvent, and as the negative control
the explicit plugin (pair style fricgen/<law>, the first-order kick) at the same dt = 5e-3, 2-D and 3-D,
no solvent. And 1, 2 and 4 ranks (free flight, 2-D, coulomb_newton, --rank-steps sampled steps each; 4 ranks
as 2 x 2 sub-domains, oversubscribed on a 2-core machine, which changes the time and not the result).

Run: python docs/studies/lammps_exact_kT.py [--steps 20000] [--rank-steps 20000] [--rows free,ranks,wca]
     [--rank-counts 1,2,4]
(writes docs/studies/results/lammps_exact_kT.json; the runs of a call replace those of the same kind)
"""

from __future__ import annotations

import argparse
import json
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from fricgen.app.cli.lammps import build_plugin, emit_plugin, locate_lammps, plugin_folder
from fricgen.derive.law.catalogues import BUILT_IN
from fricgen.langevin.analysis import block_estimate

RESULTS = Path(__file__).parent / "results" / "lammps_exact_kT.json"
EQUILIBRATION = 2000
USER_LAW = """name = "saturating_viscous"
description = "Viscous friction that saturates at high sliding speed: f = gamma_f u / sqrt(1 + (u/u0)^2) (no weight)."
friction = "gamma_f*u/sqrt(1 + (u/u0)**2)"
calculi = ["ito"]

[parameters.gamma_f]
default = 8.0

[parameters.u0]
default = 0.7
"""
#: The laws (fix parameters) of the free-flight runs; "rolling_coulomb_newton" runs beside coulomb_newton's fix.
LAWS = {
    "coulomb": "",
    "linear": " gamma_f 10.0",
    "coulomb_newton": "",
    "rolling_coulomb_newton": "",
    "saturating_viscous": "",
}
NO_FORCE = "pair_style      zero 1.2\npair_coeff      * *\n"
WCA = "pair_style      lj/cut 1.122462048309373\npair_coeff      * * 1.0 1.0\npair_modify     shift yes\n"


def plugins(lammps, work: Path) -> dict[str, tuple[Path, Path]]:
    """(the built plugin, its sources' folder) of each law: the catalogue's from generated/lammps, the user's law
    emitted into ``work``."""
    built = {}
    for law in ("coulomb", "linear", "coulomb_newton", "rolling_coulomb_newton"):
        law_file = BUILT_IN.find(law)
        built[law] = (build_plugin(plugin_folder(law_file), lammps, law_file), plugin_folder(law_file))
    (work / "laws").mkdir(exist_ok=True)
    law_file = work / "laws" / "saturating_viscous.toml"
    law_file.write_text(USER_LAW)
    sources, _ = emit_plugin(law_file, out=work / "sources")
    built["saturating_viscous"] = (build_plugin(sources, lammps, law_file, work / "build"), sources)
    return built


def script(law: str, dim: int, built: dict, solvent: int, steps: int, pair: str, explicit: bool = False) -> str:
    """The law's exact template: free flight (``pair``) or WCA, smaller (no deletions in 3-D), sampled every 10 steps."""
    template = built[law][1] / f"in.{law}_{dim}d_exact"
    text = template.read_text().replace("delete_atoms    random count 648 yes all NULL ${seed}\n", "")
    replacements = [
        (f"cells index {'100' if dim == 2 else '22'}", f"cells index {'40' if dim == 2 else '12'}"),
        ("thermo index 1000", "thermo index 10"),
        (f"plugin index fricgen_{law}.so", f"plugin index {built[law][0]}"),
        ("run             ${nrun}", f"run {EQUILIBRATION}\nrun {steps}"),
    ]
    if pair != WCA:
        replacements.append((WCA, pair))
    fix = next(line for line in text.splitlines() if line.startswith("fix             contact"))
    if law == "rolling_coulomb_newton":  # the sliding law's fix beside it
        sliding = f"plugin          load {built['coulomb_newton'][0]}\n"
        sliding += "fix             slide all fricgen/exact/coulomb_newton ${kT} ${seed}\n"
        replacements.append((fix + "\n", fix + "\n" + sliding))
    elif LAWS[law]:
        replacements.append((fix + "\n", fix + LAWS[law] + "\n"))
    if explicit:  # the pair style's first-order kick in place of lj/cut and the fix
        replacements += [(fix + "\n", ""), (WCA, f"pair_style      fricgen/{law} ${{kT}} ${{seed}}\npair_coeff      * * 1.0 1.0\n")]
    for old, new in replacements:
        if old not in text:
            raise RuntimeError(f"{template.name}: no {old!r}")
        text = text.replace(old, new)
    return text.replace("solvent index 1", f"solvent index {solvent}")


def temperatures(lammps, work: Path, text: str, ranks: int = 1) -> dict[str, list[float]]:
    """T_trans and T_rot (mean, error from 20 blocks) after the equilibration; nan if the run failed."""
    (work / "in.run").write_text(text)
    done = subprocess.run(
        [*lammps.command(ranks), "-in", "in.run", "-log", "none", "-nocite"],
        cwd=work,
        env=lammps.environment(),
        capture_output=True,
        text=True,
    )
    rows, reading = [], False
    for line in done.stdout.splitlines():  # the thermo tables' rows (Step Temp c_trot ...)
        words = line.split()
        if words[:3] == ["Step", "Temp", "c_trot"]:
            reading = True
        elif reading:
            try:
                rows.append([float(x) for x in words[:3]])
            except ValueError:
                reading = False
    table = np.array([r for r in rows if r[0] > EQUILIBRATION])
    if done.returncode != 0 or len(table) < 40 or not np.isfinite(table).all():
        return {"T_trans": [float("nan")] * 2, "T_rot": [float("nan")] * 2, "failed": (done.stdout + done.stderr)[-300:]}
    estimates = {name: block_estimate(table[:, column]) for name, column in (("T_trans", 1), ("T_rot", 2))}
    return {name: [e.mean, e.error] for name, e in estimates.items()}


def verdict(result: dict) -> bool:
    return all(abs(m - 1.0) < 0.005 and abs(m - 1.0) < 4.0 * e for m, e in (result["T_trans"], result["T_rot"]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=20000, help="sampled steps per run (after 2000)")
    parser.add_argument("--rank-steps", type=int, default=20000, help="sampled steps of the rank-count runs")
    parser.add_argument("--rank-counts", default="1,2,4", help="the rank counts of the ranks rows")
    parser.add_argument("--rows", default="free,ranks,wca", help="which runs: free (every law in free flight), ranks, wca")
    options = parser.parse_args()
    lammps = locate_lammps()
    work = Path(tempfile.mkdtemp(prefix="fricgen-kT-"))
    built = plugins(lammps, work)
    rows = []

    def record(kind, law, dim, solvent, ranks, text, steps=options.steps):
        result = temperatures(lammps, work, text, ranks)
        row = {
            "kind": kind,
            "law": law,
            "dim": dim,
            "solvent": solvent,
            "ranks": ranks,
            "steps": steps,
            **result,
            "within": verdict(result),
        }
        rows.append(row)
        (t, dt_), (r, dr) = result["T_trans"], result["T_rot"]
        print(
            f"{kind:22s} {law:24s} {dim}-D solvent {solvent} ranks {ranks}: T_trans {t:.4f} +- {dt_:.4f}  T_rot {r:.4f} +- {dr:.4f}"
            f"  {'within' if row['within'] else 'OFF'}",
            flush=True,
        )

    chosen = options.rows.split(",")
    if "free" in chosen:
        for law in LAWS:
            for dim in (2, 3):
                for solvent in (0, 1):
                    record("fix, free flight", law, dim, solvent, 1, script(law, dim, built, solvent, options.steps, NO_FORCE))
    if "ranks" in chosen:
        for ranks in (int(count) for count in options.rank_counts.split(",")):
            text = script("coulomb_newton", 2, built, 0, options.rank_steps, NO_FORCE)
            record("fix, free flight", "coulomb_newton", 2, 0, ranks, text, options.rank_steps)
    if "wca" in chosen:
        for dim in (2, 3):
            for solvent in (0, 1):
                record("fix, WCA", "coulomb_newton", dim, solvent, 1, script("coulomb_newton", dim, built, solvent, options.steps, WCA))
            text = script("coulomb_newton", dim, built, 0, options.steps, WCA, explicit=True)
            record("explicit, WCA", "coulomb_newton", dim, 0, 1, text)
    # the runs of this call replace those of the same kind, law, dimension, solvent and ranks
    keys = {(r["kind"], r["law"], r["dim"], r["solvent"], r["ranks"]) for r in rows}
    kept = json.loads(RESULTS.read_text())["runs"] if RESULTS.exists() else []
    kept = [r for r in kept if (r["kind"], r["law"], r["dim"], r["solvent"], r["ranks"]) not in keys]
    RESULTS.write_text(json.dumps({"dt": 5e-3, "runs": kept + rows}, indent=1) + "\n")
    print(f"written {RESULTS}")


if __name__ == "__main__":
    main()
