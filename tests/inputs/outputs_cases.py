"""The corpus of outputs, resume, deadlines and edge numbers (issue 31, part B) as data.

Rows are ``args | key | piece`` as in :mod:`tests.inputs.cases`; ``{in}`` is the folder that
:func:`build` fills: run files, damaged checkpoints (each beside the one valid checkpoint it was
made from), folders that hold what the user had (a CMakeLists.txt of their own, a previous BCD
result, another run's checkpoint in a sweep's point folder), a law folder whose ``generated`` is a
symbolic link out of it, and sweep files. Each row must exit with status 2, print one line naming
``key`` and holding ``piece``, and change no file (tests/inputs/test_outputs_inputs.py).
"""

from __future__ import annotations

import json
import shlex
from pathlib import Path

import numpy as np

#: A small 2-D run and a small slit; the slit's variants differ in one field of [walls].
SMALL = "[system]\nn = 16\npacking_fraction = 0.3\n[run]\nsteps = 2000\nchunk = 1000\n[output]\nperiod = 1000\ntrajectory_period = 1000\n"
SLIT = (
    '[system]\ndimension = 3\nn = 20\nbox = [8.0, 12.0, 8.0]\n[walls]\nhalf_width = 5.0\nroughness = {roughness}\n[law]\nname = "linear"\n'
)
SLIT_RUN = "[run]\nsteps = 2000\nchunk = 1000\n[output]\nperiod = 1000\ntrajectory_period = 1000\n"

#: Damaged copies of the small run's checkpoint: folder -> what is done to its arrays.
DAMAGES = {
    "ck_nan_position": lambda a: a["position"].__setitem__((0, 0), np.nan),
    "ck_inf_velocity": lambda a: a["velocity"].__setitem__((1, 1), np.inf),
    "ck_nan_orientation": lambda a: a["orientation"].__setitem__((2, 0), np.nan),
    "ck_negative_step": lambda a: a.__setitem__("step", np.int64(-1000)),
    "ck_truncated": lambda a: a.__setitem__("position", a["position"][:-1]),
    "ck_reshaped": lambda a: a.__setitem__("velocity", a["velocity"][:, :2]),
    "ck_no_omega": lambda a: a.pop("omega"),
    "ck_config_list": lambda a: a.__setitem__("config", np.array(json.dumps([1, 2]))),
    "ck_config_garbled": lambda a: a.__setitem__("config", np.array("{not json")),
    "ck_dimension": lambda a: a.__setitem__("dim", np.int64(5)),
    "ck_zero_mass": lambda a: a["mass"].__setitem__(3, 0.0),
    "ck_string_radius": lambda a: a.__setitem__("radius", a["radius"].astype(str)),
}

ROWS = """
thermostat-check linear --time 2 | --time | under the 40 that 20 error blocks need
thermostat-check linear --time 0.5 --dt 0.01 | --time | under the 40
thermostat-check linear --kT 1e-310 | --kT | the scales fricgen is checked on
thermostat-check linear --kT 5e-324 | --kT | must be within
thermostat-check linear --kT 1e7 | --kT | must be within
run passive --set system.radius=1e-300 | system.radius | the scales fricgen is checked on
run passive --set system.radius=1e150 | system.radius | must be within
run passive --set system.mass=1e-300 | system.mass | must be within
run active --set active.force=1e200 | active.force | at most 1e+06 in magnitude
run passive --set 'bulk.force=[1e200, 0.0]' | bulk.force | at most 1e+06 in magnitude
run passive --set thermostat.kT=1e-310 | thermostat.kT | must be within
run passive --set thermostat.kT=1e9 | thermostat.kT | must be within
run passive --set output.profile_bins=100000000 | output.profile_bins | at most 10000
noise smooth_coulomb --u 1 --r 1.05 --kT 5e-324 | --kT | must be within
noise smooth_coulomb --u 1 --r 1.05 --mu 5e-324 | --mu | must be within
noise linear --u 1 --r 1.05 --kT 1e-310 | --kT | must be within
noise linear --u 1 --r 1.05 --mu 1e7 | --mu | must be within
noise linear --u 1 --r 1 --param gamma_f=1e-320 | --param gamma_f | neither 0 nor at least 1e-150
noise coulomb --u 1 --w 1 --param kappa_f=1e-200 | --param kappa_f | neither 0 nor at least
noise linear --u 1 --w 1e-320 | D | underflows at u = 1
bcd --n 20 --out {in}/bcd_result | --out | already holds a result (profile.csv, profile.png)
sweep {in}/grid_huge.toml | grid | more than a sweep runs
sweep {in}/small_sweep.toml --out {in}/sweep_foreign | --out | without its config.json
sweep {in}/small_sweep.toml --out {in}/sweep_other | point | holds an unfinished run with
run {in}/slit.toml --resume {in}/ck_slit_wide/checkpoint.npz | walls | another half_width, roughness or spacing
run {in}/slit.toml --resume {in}/ck_slit_rough/checkpoint.npz | walls | stand elsewhere
run {in}/small.toml --resume {in}/ck_damaged_trajectory/checkpoint.npz | --resume | trajectory.gsd is damaged
run {in}/small.toml --resume {in}/ck_damaged_table/checkpoint.npz | --resume | temperatures.csv is damaged
run {in}/small.toml --resume {in}/ck_not_zip/checkpoint.npz | --resume | not an .npz archive
run {in}/small.toml --resume {in}/ck_empty/checkpoint.npz | --resume | cannot read the checkpoint
"""

#: Rows of the damaged checkpoints: folder -> piece of the message.
CHECKPOINT_ROWS = {
    "ck_nan_position": "holds position that is not finite",
    "ck_inf_velocity": "holds velocity that is not finite",
    "ck_nan_orientation": "holds orientation that is not finite",
    "ck_negative_step": "is at a negative step, -1000",
    "ck_truncated": "holds position of float64 (15, 3)",
    "ck_reshaped": "holds velocity of float64 (16, 2)",
    "ck_no_omega": "lacks omega",
    "ck_config_list": "not a table with a law table",
    "ck_config_garbled": "not JSON",
    "ck_dimension": "has dimension 5",
    "ck_zero_mass": "is not positive",
    "ck_string_radius": "holds radius of <U",
}


#: Rows of the writers of generated code (fricgen.derive.driver.check_not_foreign).
WRITER_ROWS = [
    ("lammps linear --out {in}/cmake_mine", "CMakeLists.txt", "exists and was not written by fricgen"),
    ("generate --laws {in}/linked_laws", "generated", "is a symbolic link: fricgen writes only into folders of its own"),
]


def rows() -> list[tuple[str, str, str]]:
    """Every row as (args, key, piece)."""
    from fricgen.derive import driver

    found = [tuple(part.strip() for part in line.split(" | ")) for line in ROWS.strip().splitlines()]
    found += WRITER_ROWS if hasattr(driver, "check_not_foreign") else []  # lands with the manifests of issue 31, part A
    for folder, piece in CHECKPOINT_ROWS.items():
        found.append((f"run {{in}}/small.toml --resume {{in}}/{folder}/checkpoint.npz", "--resume", piece))
    return found


def _checkpoint(config: Path, folder: Path) -> dict:
    """A valid checkpoint of the run file ``config`` at step 0 in ``folder`` (no step is taken);
    its arrays."""
    from fricgen.app.run.runner import plan
    from fricgen.langevin.trajectory import save_checkpoint

    folder.mkdir(parents=True)
    simulation = plan(str(config), [], None, str(folder / "unused"), None).simulation
    save_checkpoint(folder / "checkpoint.npz", simulation)
    with np.load(folder / "checkpoint.npz") as data:
        return {name: data[name] for name in data.files}


def build(root: Path) -> None:
    """Fill ``root`` with the files the rows name."""
    (root / "small.toml").write_text(SMALL)
    (root / "slit.toml").write_text(SLIT.format(roughness=0.1) + SLIT_RUN)
    (root / "slit_wide.toml").write_text(SLIT.format(roughness=0.1).replace("half_width = 5.0", "half_width = 5.5") + SLIT_RUN)
    (root / "slit_rough.toml").write_text(SLIT.format(roughness=0.2) + SLIT_RUN)
    arrays = _checkpoint(root / "small.toml", root / "ck_valid")
    for folder, damage in DAMAGES.items():
        copy = {name: np.array(value, copy=True) for name, value in arrays.items()}
        damage(copy)
        (root / folder).mkdir()
        np.savez(root / folder / "checkpoint.npz", **copy)
    _checkpoint(root / "slit_wide.toml", root / "ck_slit_wide")
    _checkpoint(root / "slit_rough.toml", root / "ck_slit_rough")
    for name, files in {
        "ck_damaged_trajectory": {"trajectory.gsd": b"GSD but not quite" * 10, "summary.json": b'{"steps": 2000}\n'},
        "ck_damaged_table": {"temperatures.csv": b"step,T_trans,T_rot\n0,1.0\nx,y,z\n"},
    }.items():
        (root / name).mkdir()
        np.savez(root / name / "checkpoint.npz", **arrays)
        for file, data in files.items():
            (root / name / file).write_bytes(data)
    for name, data in {"ck_not_zip": b"PK\x03\x04 not a zip archive", "ck_empty": b""}.items():
        (root / name).mkdir()
        (root / name / "checkpoint.npz").write_bytes(data)
    (root / "bcd_result").mkdir()
    (root / "bcd_result" / "profile.csv").write_text("x,rho\n0.5,1.0\n")
    (root / "bcd_result" / "profile.png").write_bytes(b"\x89PNG a figure of an earlier study")
    (root / "linked_laws").mkdir()
    (root / "linked_laws" / "mylin.toml").write_text(
        'name = "mylin"\nfriction = "w*gamma_f*u"\nweight = "wca"\n\n[parameters.gamma_f]\ndefault = 1.0\n'
    )
    (root / "elsewhere").mkdir()
    (root / "elsewhere" / "keep.txt").write_text("the user's file, out of the law folder\n")
    (root / "linked_laws" / "generated").symlink_to(root / "elsewhere")
    (root / "cmake_mine").mkdir()
    (root / "cmake_mine" / "CMakeLists.txt").write_text("cmake_minimum_required(VERSION 3.16)\nproject(mine)\n")
    values = ", ".join(str(0.1 + i * 1e-4) for i in range(1000))
    (root / "grid_huge.toml").write_text(
        f'base = "passive"\n[grid]\n"thermostat.dt" = [{values}]\n"run.seed" = [{", ".join(map(str, range(1, 1001)))}]\n'
    )
    sweep = '[set]\n"run.steps" = 2000\n"run.equilibrate" = 0\n[grid]\n"system.packing_fraction" = [0.3]\n'
    (root / "small_sweep.toml").write_text(f"base = {json.dumps(str(root / 'small.toml'))}\n{sweep}")
    point = "packing_fraction=0.3"
    (root / "sweep_foreign" / point).mkdir(parents=True)
    np.savez(root / "sweep_foreign" / point / "checkpoint.npz", **arrays)
    (root / "sweep_other" / point).mkdir(parents=True)
    np.savez(root / "sweep_other" / point / "checkpoint.npz", **arrays)
    (root / "sweep_other" / point / "config.json").write_text(json.dumps({"system": {"n": 99}, "run": {"steps": 7}}))


def argv(args: str, inputs: str) -> list[str]:
    """The command line of a row, with ``{in}`` the folder of :func:`build`."""
    return [word.replace("{in}", inputs) for word in shlex.split(args)]
