"""The bad-input corpus as data: command lines, the flag or key the one-line error must name, and a
piece of its message; and the files (configurations, folders in the way) that the lines refer to.

``{in}`` in a command line is the folder that holds :data:`FILES`; every other relative path is
inside the case's empty working folder. Rows are ``args | key | piece``; args are split as a shell
would (quotes keep spaces).
"""

import shlex

#: A valid [system] table that the configuration files below break one key at a time.
SYSTEM = "[system]\nn = 64\npacking_fraction = 0.6\n"
SLIT = '[system]\ndimension = 3\nn = 100\nbox = [12.0, 18.0, 6.0]\n[law]\nname = "linear"\n'

#: Files in the ``{in}`` folder: configuration files by name, and things in the way of an output folder.
FILES = {
    "broken.toml": b"[system\nn = 4\n",
    "binary.toml": bytes(range(256)) * 4,
    "latin1.toml": "# Gr\u00f6\u00dfe des Systems\n[system]\nn = 64\npacking_fraction = 0.6\n".encode("latin-1"),
    "utf16.toml": SYSTEM.encode("utf-16"),
    "nul.toml": b"[system]\nn = 64\x00\npacking_fraction = 0.6\n",
    "empty.toml": b"",
    "unknown_section.toml": b"[sytem]\nn = 64\n",
    "unknown_key.toml": (SYSTEM + "radious = 0.5\n").encode(),
    "unknown_nested.toml": (SYSTEM + "[law.extra]\na = 1\n").encode(),
    "system_number.toml": b"system = 3\n",
    "system_array.toml": b"[[system]]\nn = 64\npacking_fraction = 0.6\n",
    "dt_nan.toml": (SYSTEM + "[thermostat]\ndt = nan\n").encode(),
    "dt_inf.toml": (SYSTEM + "[thermostat]\ndt = inf\n").encode(),
    "kT_minus_inf.toml": (SYSTEM + "[thermostat]\nkT = -inf\n").encode(),
    "gamma_negative.toml": (SYSTEM + "[thermostat]\ngamma = -1.0\n").encode(),
    "n_string.toml": b'[system]\nn = "64"\npacking_fraction = 0.6\n',
    "n_float.toml": b"[system]\nn = 64.0\npacking_fraction = 0.6\n",
    "n_huge.toml": b"[system]\nn = 100000000000000000000\npacking_fraction = 0.6\n",
    "dimension_bool.toml": (SYSTEM + "dimension = true\n").encode(),
    "radius_nan.toml": (SYSTEM + "radius = nan\n").encode(),
    "mass_zero.toml": (SYSTEM + "mass = 0.0\n").encode(),
    "epsilon_inf.toml": (SYSTEM + "epsilon = inf\n").encode(),
    "start_unknown.toml": (SYSTEM + 'start = "hexagonal"\n').encode(),
    "fraction_close.toml": b"[system]\nn = 64\npacking_fraction = 0.95\n",
    "fraction_lattice.toml": b"[system]\nn = 64\npacking_fraction = 0.85\n",
    "fraction_random.toml": (SYSTEM + 'start = "random"\n').encode(),
    "fraction_zero.toml": b"[system]\nn = 64\npacking_fraction = 0.0\n",
    "fraction_nan.toml": b"[system]\nn = 64\npacking_fraction = nan\n",
    "fraction_3d.toml": b"[system]\ndimension = 3\nn = 64\npacking_fraction = 0.8\n",
    "box_negative.toml": b"[system]\nn = 20\nbox = [-10.0, 10.0]\n",
    "box_inf.toml": b"[system]\nn = 20\nbox = [inf, 10.0]\n",
    "box_short.toml": b"[system]\ndimension = 3\nn = 20\nbox = [10.0, 10.0]\n",
    "box_and_both.toml": b"[system]\nn = 20\npacking_fraction = 0.3\nbox = [10.0, 10.0]\n",
    "box_small.toml": b"[system]\nn = 2\nbox = [2.0, 2.0]\n",
    "box_cells.toml": b"[system]\nn = 10\nbox = [1e12, 1e12]\n",
    "no_n.toml": b"[system]\npacking_fraction = 0.6\n",
    "law_unknown.toml": (SYSTEM + '[law]\nname = "stick_slip"\n').encode(),
    "law_calculus.toml": (SYSTEM + '[law]\nname = "coulomb"\ncalculus = "hk"\n').encode(),
    "calculus_number.toml": (SYSTEM + "[law]\ncalculus = 1\n").encode(),
    "scheme_mismatch.toml": (SYSTEM + '[law]\nscheme = "hk"\n').encode(),
    "parameters_number.toml": (SYSTEM + "[law]\nparameters = 1\n").encode(),
    "parameter_inf.toml": (SYSTEM + "[law.parameters]\ngamma_f = inf\n").encode(),
    "parameter_owned.toml": (SYSTEM + "[law.parameters]\nepsilon = 2.0\n").encode(),
    "active_nan.toml": (SYSTEM + "[active]\nforce = nan\n").encode(),
    "bulk_3d_in_2d.toml": (SYSTEM + "[bulk]\nforce = [1.0, 0.0, 0.0]\n").encode(),
    "bulk_inf.toml": (SYSTEM + "[bulk]\nforce = [inf, 0.0]\n").encode(),
    "walls_no_box.toml": (SYSTEM + "[walls]\nhalf_width = 5.0\n").encode(),
    "walls_no_half_width.toml": (SLIT + "[walls]\nroughness = 0.1\n").encode(),
    "walls_wide.toml": (SLIT + "[walls]\nhalf_width = 9.5\n").encode(),
    "walls_thin.toml": (SLIT + "[walls]\nhalf_width = 1.0\nroughness = 0.5\n").encode(),
    "walls_spacing_inf.toml": (SLIT + "[walls]\nhalf_width = 8.0\nspacing = inf\n").encode(),
    "walls_roughness_nan.toml": (SLIT + "[walls]\nhalf_width = 8.0\nroughness = nan\n").encode(),
    "walls_huge.toml": b"[system]\ndimension = 3\nn = 100\nbox = [1e9, 18.0, 1e9]\n[walls]\nhalf_width = 8.0\n",
    "steps_huge.toml": (SYSTEM + "[run]\nsteps = 9223372036854775807\n").encode(),
    "seed_negative.toml": (SYSTEM + "[run]\nseed = -1\n").encode(),
    "chunk_zero.toml": (SYSTEM + "[run]\nchunk = 0\n").encode(),
    "observables_numbers.toml": (SYSTEM + "[output]\nobservables = [1, 2]\n").encode(),
    "observables_string.toml": (SYSTEM + '[output]\nobservables = "temperatures"\n').encode(),
    "period_odd.toml": (SYSTEM + "[run]\nchunk = 100\n[output]\nperiod = 150\n").encode(),
    "afile": b"not a folder\n",
    "oldrun/checkpoint.npz": b"a run was here\n",
    "foreign/summary.json": b'{"steps": 600, "T_trans": {"mean": 1.0}}\n',
    "garbled/summary.json": b"\xff\xfe not json",
}

#: The command lines: args | the flag or key the error names | a piece of the message.
ROWS = """
noise linear --u 1 --r -1 | --r | must be positive
noise linear --u 1 --r 0 | --r | must be positive
noise linear --u 1 --r nan | --r | got nan
noise linear --u 1 --r inf | --r | got inf
noise linear --u 1 --r -inf | --r | got -inf
noise linear --u 1 --r 1e-30 | --r | is inf, not a finite value
noise linear --u 1 --w -1 | --w | must be >= 0
noise linear --u 1 --w inf | --w | got inf
noise linear --u 1 --w nan | --w | got nan
noise linear --u 1 --r 1 --kT inf | --kT | got inf
noise linear --u 1 --r 1 --kT 0 | --kT | must be positive
noise linear --u 1 --r 1 --kT -1 | --kT | must be positive
noise linear --u 1 --r 1 --kT nan | --kT | got nan
noise linear --u 1 --r 1 --mu inf | --mu | got inf
noise linear --u 1 --r 1 --mu 0 | --mu | must be positive
noise linear --u 1 --r 1 --mu -7 | --mu | must be positive
noise linear --u 1 --r 1 --mu nan | --mu | got nan
noise linear --u -1 --r 1 | --u | got -1.0
noise linear --u 1,-2 --r 1 | --u | got -2.0
noise linear --u nan --r 1 | --u | got nan
noise linear --u 0,inf --r 1 | --u | got inf
noise linear --u , --r 1 | --u | at least one speed
noise linear --u 1 --r 1 --param gamma_f=1e308 --json | D | overflows double precision
noise linear --u 1 --r 1 --param gamma_f=1e308 | D | is inf at u = 1
noise linear --u 1e308 --w 24 | f | is inf at u = 1e+308
noise linear --u 1 --r 1 --param gamma_f=inf | --param gamma_f | got inf
noise linear --u 1 --r 1 --param gamma_f=nan | --param gamma_f | got nan
noise linear --u 1 --r 1 --param gamma_f=0 | --param gamma_f | must be positive
noise linear --u 1 --r 1 --param gamma_f=-1 | --param gamma_f | must be positive
noise linear --u 1 --r 1 --param beta_f=1 | --param beta_f | has no parameter 'beta_f'
noise linear --u 1 | --r | give --r R
noise coulomb --calculus hk --u 1 --w 1 | --calculus | no kernels for the 'hk' calculus
noise stick_slip --u 1 --w 1 | LAW | unknown law 'stick_slip'
noise linear --u a,b --w 1 | --u | expected comma-separated numbers
noise linear --u 1 --w 1 --param gamma_f | --param | expected NAME=VALUE
noise linear --u 1 --r 1 --w 1 | --w | not allowed with argument --r
noise linear --u 1 --w 1 --calculus euler | --calculus | invalid choice: 'euler'
noise linear --w 1 | --u | the following arguments are required
thermostat-check linear --n 0 | --n | at least 2 spheres, got 0
thermostat-check linear --n 1 | --n | at least 2 spheres, got 1
thermostat-check linear --n -5 | --n | at least 2 spheres, got -5
thermostat-check linear --n 4 | --n | give n >= 7
thermostat-check linear --dim 3 --n 8 | --n | under twice the interaction range
thermostat-check linear --n 100000000000 | --n | of memory, more than this machine has
thermostat-check linear --n 1.5 | --n | invalid int value
thermostat-check linear --phi 0 | --phi | must be in (0, 1)
thermostat-check linear --phi -0.1 | --phi | must be in (0, 1)
thermostat-check linear --phi nan | --phi | got nan
thermostat-check linear --phi inf | --phi | got inf
thermostat-check linear --phi 0.95 | --phi | close packing is 0.9069
thermostat-check linear --phi 0.8 | --phi | lattice start of 256 spheres
thermostat-check linear --n 250 --phi 0.77 | --phi | at most 0.7670
thermostat-check linear --dim 3 --phi 0.6 | --phi | at most 0.5236 in 3-D
thermostat-check linear --dim 4 | --dim | invalid choice: 4
thermostat-check linear --dt 0 | --dt | must be positive
thermostat-check linear --dt -1e-3 | --dt | got -0.001
thermostat-check linear --dt inf | --dt | got inf
thermostat-check linear --dt nan | --dt | got nan
thermostat-check linear --dt 10 | --time | under 20 steps
thermostat-check linear --time 0 | --time | must be positive
thermostat-check linear --time -1 | --time | must be positive
thermostat-check linear --time inf | --time | got inf
thermostat-check linear --time nan | --time | got nan
thermostat-check linear --time 1e300 | --time | more than a run can count
thermostat-check linear --kT 0 | --kT | must be positive
thermostat-check linear --kT -1 | --kT | got -1.0
thermostat-check linear --kT inf | --kT | got inf
thermostat-check linear --kT nan | --kT | got nan
thermostat-check linear --seed -1 | --seed | got -1
thermostat-check linear --seed 9223372036854775808 | --seed | [0, 2^63)
thermostat-check linear --param gamma_f=-1 | --param gamma_f | must be positive
thermostat-check linear --param gamma_f=inf | --param gamma_f | got inf
thermostat-check linear --param beta_f=1 | --param beta_f | has no parameter
thermostat-check linear --param sigma=1.2 | --param sigma | set by the radii
thermostat-check coulomb --calculus hk | --calculus | no kernels for the 'hk' calculus
thermostat-check stick_slip | LAW | unknown law 'stick_slip'
thermostat-check rolling_coulomb_newton --no-rolling-noise | --no-rolling-noise | is itself a rolling law
thermostat-check linear --no-spinning-noise | --no-spinning-noise | give the spinning law with --spinning NAME
run passive --set thermostat.dt=inf | thermostat.dt | got inf
run passive --set thermostat.dt=nan | thermostat.dt | got nan
run passive --set thermostat.dt=0 | thermostat.dt | must be positive
run passive --set thermostat.dt=-1e-3 | thermostat.dt | must be positive
run passive --set thermostat.kT=inf | thermostat.kT | got inf
run passive --set thermostat.kT=0 | thermostat.kT | must be positive
run passive --set thermostat.gamma=inf | thermostat.gamma | got inf
run passive --set thermostat.gamma_rot=-1.0 | thermostat.gamma_rot | must be >= 0
run passive --set system.mass=inf | system.mass | got inf
run passive --set system.mass=0 | system.mass | must be positive
run passive --set system.radius=-0.5 | system.radius | must be positive
run passive --set system.epsilon=-1.0 | system.epsilon | must be >= 0
run passive --set system.n=100000000000 | system.n | of memory, more than this machine has
run passive --set system.n=1 | system.n | at least 2 particles
run passive --set system.n=3 | system.n | too small for the interaction range
run passive --set system.n=1e4 | system.n | must be an integer
run passive --set system.dimension=4 | system.dimension | must be 2 or 3
run passive --set system.start=hexagonal | system.start | 'lattice' or 'random'
run passive --set system.packing_fraction=0 | system.packing_fraction | impossible
run passive --set system.packing_fraction=nan | system.packing_fraction | impossible
run passive --set system.packing_fraction=inf | system.packing_fraction | impossible
run passive --set system.packing_fraction=1.2 | system.packing_fraction | close packing is 0.9069
run passive --set system.packing_fraction=0.85 | system.packing_fraction | too high for a lattice start
run passive --set 'system.box=[10.0]' | system.box | needs 2 lengths
run passive --set system.box=big | system.box | must be a list of numbers
run passive --set law.name=stick_slip | law.name | no law 'stick_slip'
run passive --set law.calculus=euler | law.calculus | must be one of
run passive --set law.scheme=hk | law.scheme | not a consistent thermostat
run passive --set law.friction=yes | law.friction | true or false
run passive --set law.parameters.gamma_f=inf | law.parameters.gamma_f | got inf
run passive --set law.parameters.gamma_f=nan | law.parameters.gamma_f | got nan
run passive --set law.parameters.kappa_f=0 | law.parameters.kappa_f | must be positive
run passive --set law.parameters.epsilon=2.0 | law.parameters.epsilon | system.epsilon
run passive --set active.force=inf | active.force | must be finite
run passive --set active.force=nan | active.force | must be finite
run passive --set 'bulk.force=[1.0]' | bulk.force | needs 2 or 3 components
run passive --set 'bulk.force=[inf, 0.0]' | bulk.force | must be finite
run passive --set 'bulk.force=[1.0, 0.0, 0.0]' | bulk.force | needs 2 components
run passive --set walls.half_width=inf | walls.half_width | got inf
run passive --set run.steps=0 | run.steps | must be >= 1
run passive --set run.seed=-1 | run.seed | got -1
run passive --set run.seed=9223372036854775807 --set run.chunk=0 | run.chunk | must be >= 1
run passive --set output.period=0 | output.period | a positive multiple of run.chunk
run passive --set output.trajectory_period=-100 | output.trajectory_period | multiple of run.chunk
run passive --set output.profile_bins=0 | output.profile_bins | must be >= 1
run passive --set output.observables=temperatures | output.observables | must be a list of strings
run passive --set output.extra=1 | output.extra | unknown key
run passive --set system.n.x=1 | system.n.x | n is not a table
run passive --set nodot=1 | --set nodot=1 | expected SECTION.KEY=VALUE
run passive --set system.n | --set system.n | expected SECTION.KEY=VALUE
run passive --set .n=5 | --set .n=5 | expected SECTION.KEY=VALUE
run passive --steps 0 | run.steps | must be >= 1
run passive --steps -1 | run.steps | must be >= 1
run passive --steps 100000000000000000000 | run.steps | more than a run can count
run passive --steps 1e3 | --steps | invalid int value
run passive --out {in}/afile | --out | is a file, not a folder
run passive --out {in}/afile/sub | --out | is a file, not a folder
lammps stick_slip | LAW | unknown law 'stick_slip'
lammps coulomb_newton --calculus hk | --calculus | consistent with the Itô amplitude only
lammps coulomb --calculus stratonovich | --calculus | consistent with the Itô amplitude only
lammps linear --out {in}/afile | --out | is a file, not a folder
lammps linear --build --build-dir {in}/afile | --build-dir | is a file, not a folder
lammps linear --build --lammps nowhere | --lammps | holds no liblammps.so
run passive --out /sys/fricgen-bad-input | --out | cannot write
run passive --out {in}/oldrun | --out | already holds a run
run passive --set system.n=64 --resume {in}/missing.npz | --resume | no checkpoint file
run passive --set system.n=64 --resume {in}/afile | --resume | cannot read the checkpoint
run no_such_example | CONFIG | no bundled example
run {in}/missing.toml | CONFIG | no file
run {in} | CONFIG | no file
run {in}/broken.toml | broken.toml | not valid TOML
run {in}/binary.toml | binary.toml | not UTF-8
run {in}/latin1.toml | latin1.toml | not UTF-8
run {in}/utf16.toml | utf16.toml | not UTF-8
run {in}/nul.toml | nul.toml | not valid TOML
run {in}/empty.toml | system.n | needs n and packing_fraction, or a box
run {in}/no_n.toml | system.n | needs n and packing_fraction
run {in}/unknown_section.toml | [sytem] | did you mean 'system'
run {in}/unknown_key.toml | system.radious | did you mean 'radius'
run {in}/unknown_nested.toml | law.extra | unknown key
run {in}/system_number.toml | system | must be a table
run {in}/system_array.toml | system | must be a table
run {in}/dt_nan.toml | thermostat.dt | got nan
run {in}/dt_inf.toml | thermostat.dt | got inf
run {in}/kT_minus_inf.toml | thermostat.kT | got -inf
run {in}/gamma_negative.toml | thermostat.gamma | must be >= 0
run {in}/n_string.toml | system.n | must be an integer
run {in}/n_float.toml | system.n | must be an integer
run {in}/n_huge.toml | system.n | of memory, more than this machine has
run {in}/dimension_bool.toml | system.dimension | must be an integer
run {in}/radius_nan.toml | system.radius | got nan
run {in}/mass_zero.toml | system.mass | must be positive
run {in}/epsilon_inf.toml | system.epsilon | got inf
run {in}/start_unknown.toml | system.start | 'hexagonal'
run {in}/fraction_close.toml | system.packing_fraction | close packing is 0.9069
run {in}/fraction_lattice.toml | system.packing_fraction | too high for a lattice start
run {in}/fraction_random.toml | system.packing_fraction | too dense for a random start
run {in}/fraction_zero.toml | system.packing_fraction | impossible
run {in}/fraction_nan.toml | system.packing_fraction | impossible
run {in}/fraction_3d.toml | system.packing_fraction | close packing is 0.7405 in 3-D
run {in}/box_negative.toml | system.box | finite and positive
run {in}/box_inf.toml | system.box | finite and positive
run {in}/box_short.toml | system.box | needs 3 lengths
run {in}/box_and_both.toml | system.n | give one of n and packing_fraction
run {in}/box_small.toml | system.box | too small for the interaction range
run {in}/box_cells.toml | system.box | of memory, more than this machine has
run {in}/law_unknown.toml | law.name | no law 'stick_slip'
run {in}/law_calculus.toml | law.calculus | has no 'hk' noise
run {in}/calculus_number.toml | law.calculus | must be a string
run {in}/scheme_mismatch.toml | law.scheme | not a consistent thermostat
run {in}/parameters_number.toml | law.parameters | must be a table of numbers
run {in}/parameter_inf.toml | law.parameters.gamma_f | got inf
run {in}/parameter_owned.toml | law.parameters.epsilon | set by system.epsilon
run {in}/active_nan.toml | active.force | must be finite
run {in}/bulk_3d_in_2d.toml | bulk.force | needs 2 components
run {in}/bulk_inf.toml | bulk.force | must be finite
run {in}/walls_no_box.toml | system.box | slab walls need an explicit box
run {in}/walls_no_half_width.toml | walls.half_width | missing
run {in}/walls_wide.toml | walls.half_width | leaves no room
run {in}/walls_thin.toml | walls.half_width | leaves no room
run {in}/walls_spacing_inf.toml | walls.spacing | got inf
run {in}/walls_roughness_nan.toml | walls.roughness | got nan
run {in}/walls_huge.toml | system.box | wall spheres
run {in}/steps_huge.toml | run.steps | more than a run can count
run {in}/seed_negative.toml | run.seed | got -1
run {in}/chunk_zero.toml | run.chunk | must be >= 1
run {in}/observables_numbers.toml | output.observables[0] | must be a string
run {in}/observables_string.toml | output.observables | must be a list of strings
run {in}/period_odd.toml | output.period | multiple of run.chunk = 100
demo --out {in}/afile | --out | is a file, not a folder
demo --out {in}/afile/sub | --out | is a file, not a folder
demo --out /sys/fricgen-bad-input | --out | cannot write
demo --out {in}/foreign | --out | summary.json that the demo did not write
demo --out {in}/garbled | --out | summary.json that the demo did not write
demo --out | --out | expected one argument
bcd --dt inf | --dt | got inf
bcd --dt nan | --dt | got nan
bcd --dt 0 | --dt | must be positive
bcd --dt -1e-3 | --dt | got -0.001
bcd --dt -inf | --dt | got -inf
bcd --U0 nan | --U0 | must be finite
bcd --U0 inf | --U0 | must be finite
bcd --U0 -inf | --U0 | must be finite
bcd --seed -1 | --seed | got -1
bcd --seed 9223372036854775808 | --seed | [0, 2^63)
bcd --n 1 | --n | at least 2 rods
bcd --n 0 | --n | at least 2 rods
bcd --n 300 | --n | close packing
bcd --n 100000000000 --length 1e12 | --n | of memory, more than this machine has
bcd --n 2.5 | --n | invalid int value
bcd --length 0 | --length | must be positive
bcd --length -100 | --length | must be positive
bcd --length nan | --length | got nan
bcd --length 100.5 | --length | whole number of wavelengths
bcd --length inf | --start-sweeps | open line
bcd --length inf --start-sweeps 0 | --length | finite length
bcd --sigma 0 | --sigma | must be positive
bcd --sigma inf | --sigma | got inf
bcd --sigma nan | --sigma | got nan
bcd --sigma 0.123456789 | --sigma | not a fraction k / m
bcd --wavelength 0 | --wavelength | must be positive
bcd --kT 0 | --kT | must be positive
bcd --kT inf | --kT | got inf
bcd --mu -1 | --mu | must be positive
bcd --drive inf | --drive | must be finite
bcd --gamma -1 | --gamma | must be >= 0
bcd --gamma nan | --gamma | must be finite
bcd --gamma 1 --p 1 | --p | need p > 1
bcd --gamma 1 --p inf | --p | must be finite
bcd --eps 0 | --eps | needs gamma > 0
bcd --gamma 1 --eps -0.01 | --eps | must be >= 0
bcd --gamma 1 --eps 0 --contact-layer merge | --contact-layer | bridge layer only
bcd --gamma 0.01 --eps 0 | --dt | sqrt(4 D dt) / gamma
bcd --gamma 1 --eps 0.6 | --eps | below sigma
bcd --pair-range 0.1 | --pair-range | need a pair potential
bcd --pair wca --pair-range 0.01 | --pair-range | not zero beyond
bcd --pair wca --pair-range 0.7 | --pair-range | 0 < pair_range < sigma
bcd --pair wca --gamma 1 --pair-range 0.12 | --pair-range | gamma = 0
bcd --pair wca --pair-range 0.12 --pair-param sigma=inf | --pair-param | must be finite
bcd --pair cosine --pair-range 0.12 | --pair | an external field, not a pair potential
bcd --field wca | --field | a pair potential, not an external field
bcd --field sawtooth | sawtooth | no generated potential 'sawtooth'
bcd --field-param b=1 | --field-param | no parameter(s) ['b']
bcd --field-param U0=1 | --field-param | not field_params
bcd --field ratchet --field-param a=nan | --field-param | must be finite
bcd --field-param a | --field-param | expected NAME=VALUE
bcd --replicas 0 | --replicas | must be >= 1
bcd --replicas 1 | --replicas | must be >= 2
bcd --replicas 100000000000 | --replicas | of memory, more than this machine has
bcd --gap-bins 100000000000 | --gap-bins | histogram bins each
bcd --bins 0 | --bins | must be >= 1
bcd --bins 1000000000 | --bins | of memory, more than this machine has
bcd --gap-width 0 | --gap-width | must be positive
bcd --gap-width nan | --gap-width | got nan
bcd --gap-bins 0 | --gap-bins | must be >= 1
bcd --contact-layer merge --gap-bins 5 | --gap-bins | the contact fit needs 21
bcd --fit-bins 1 | --fit-bins | must be >= 2
bcd --start-sweeps -1 | --start-sweeps | must be >= 0
bcd --time 0 | --time | must be positive
bcd --time -1 | --time | must be positive
bcd --time inf | --time | got inf
bcd --time nan | --time | got nan
bcd --time 1e300 | --time | more than a run can count
bcd --equilibrate -1 | --equilibrate | must be >= 0
bcd --equilibrate nan | --equilibrate | got nan
bcd --equilibrate inf | --equilibrate | got inf
bcd --U0 abc | --U0 | invalid float value
bcd --out {in}/afile | --out | is a file, not a folder
bcd --out /sys/fricgen-bad-input | --out | cannot write
bcd --dtt 1e-5 | --dtt | unrecognized arguments
verify stick_slip | LAW | unknown law 'stick_slip'
verify linear stick_slip | LAW | unknown law 'stick_slip'
verify --calculus euler | --calculus | invalid choice: 'euler'
generate stick_slip | LAW | unknown law 'stick_slip'
generate linear --output {in}/afile | --output | is a file, not a folder
generate linear --output /sys/fricgen-bad-input | --output | cannot write
generate --laws nowhere | --laws | the law folder nowhere does not exist
generate --laws {in}/afile linear | --laws | is a file, not a folder
noise linear --u 1 --w 1 --laws nowhere | --laws | does not exist
thermostat-check linear --laws nowhere | --laws | does not exist
verify --laws nowhere | --laws | does not exist
run passive --laws nowhere | --laws | does not exist
run passive --set law.folder=nowhere | law.folder | does not exist
run passive --set law.folder=1 | law.folder | must be a string
frobnicate | COMMAND | invalid choice: 'frobnicate'
 | COMMAND | the following arguments are required
"""


def cases() -> list[tuple[str, str, str]]:
    """The rows of :data:`ROWS` as (args, key, piece)."""
    rows = []
    for line in ROWS.strip("\n").splitlines():
        args, key, piece = (part.strip() for part in line.split(" | "))
        rows.append((args, key, piece))
    return rows


def argv(args: str, inputs: str) -> list[str]:
    """The command line of a row, with ``{in}`` the folder of :data:`FILES`."""
    return [word.replace("{in}", inputs) for word in shlex.split(args)]
