"""What the command line says about itself: the top-level description, each command's examples and
the help texts of ``fricgen bcd``'s flags, with their units (spheres: sigma = 1, m = 1, kT = 1, time
in t0; rods: wavelength = 1, D = 1, kT = 1, time in wavelength^2 / D). tests/cli/test_help.py checks
that every argument has a help text with its default and unit."""

#: What ``fricgen --help`` says first (plain text: argparse prints it as written).
DESCRIPTION = """\
fricgen: thermodynamically consistent frictional contacts for any friction law.
One program, one subcommand per job; `fricgen CMD --help` for each.

Units (spheres): diameter sigma = 1, mass m = 1, kT = 1, so time is in t0 = sqrt(m sigma^2 / kT).
Units (rods, fricgen bcd): wavelength = 1, diffusion coefficient D = 1, kT = 1; time in wavelength^2 / D.

Exit status: 0 done, 1 a physical failure (a failed check, a run that blew up), 2 bad input (one
line on stderr naming the flag or key, the problem and the fix), 130 interrupted. A negative number
after a flag is its value (--dt -1e-3 reads as --dt=-1e-3)."""

#: Examples shown under each command's help (fricgen CMD --help) and in the command-line reference
#: (fricgen lammps keeps its own in cli/lammps.py).
EXAMPLES = {
    "": """\
fricgen demo                                   # the 2-D check with and without the contact noise
fricgen verify coulomb_newton                  # derive D and prove zero probability current
fricgen thermostat-check coulomb_newton --time 20
fricgen generate my_law --laws ./laws          # your own law file ./laws/my_law.toml""",
    "verify": """\
fricgen verify                                 # every law of your folders, else of the catalogue
fricgen verify coulomb_newton --calculus ito
fricgen verify my_law --laws ./laws --json""",
    "generate": """\
fricgen generate my_law --laws ./laws          # kernels into ./laws/generated/
fricgen generate linear --output /tmp/kernels  # inspect the emitted code""",
    "noise": """\
fricgen noise coulomb_newton --u 0,0.5,1,2 --r 1.0
fricgen noise coulomb --calculus stratonovich --u 0,1 --w 2 --json
fricgen noise my_law --laws ./laws --u 0,1 --w 1 --param kappa=3""",
    "thermostat-check": """\
fricgen thermostat-check coulomb_newton                        # 256 discs in 2-D for 40 t0
fricgen thermostat-check coulomb_newton --no-contact-noise     # the inconsistent model fails
fricgen thermostat-check linear --dim 3 --time 20 --seed 2
fricgen thermostat-check coulomb_newton --rolling rolling_coulomb_newton --no-rolling-noise""",
    "demo": """\
fricgen demo
fricgen demo --out /tmp/demo --json""",
    "run": """\
fricgen run passive --steps 2000
fricgen run my_run.toml --set thermostat.dt=5e-4 --out results
fricgen run my_run.toml --resume results/checkpoint.npz""",
    "sweep": """\
fricgen sweep mips --workers 2
fricgen sweep my_sweep.toml --scheduler tcp://host:8786 --out sweep-results""",
    "bcd": """\
fricgen bcd                                    # hard rods in the cosine field, U0 = 6
fricgen bcd --gamma 0.5 --out sticky           # sticky rods
fricgen bcd --dt 1e-3 --extrapolate --json""",
}

#: The time unit of the spheres, in help texts.
T0 = "t0 = sqrt(m sigma^2 / kT)"


#: What each flag of ``fricgen bcd`` sets, in the rods' units (wavelength = 1, D = 1, kT = 1; time in
#: wavelength^2 / D); the defaults come from fricgen.rods.config.
ROD_HELP = {
    "n": "rods per ring",
    "length": "ring length L, in wavelengths",
    "sigma": "rod length, in wavelengths",
    "U0": "amplitude of the field, in kT: U = (U0/2) cos(2 pi x) by default",
    "wavelength": "period of the field, in wavelengths (the length unit)",
    "field": "a generated external potential (cosine or ratchet)",
    "field_params": "other parameters of the field, repeatable (default: none)",
    "kT": "thermal energy, in kT",
    "mu": "mobility, in D/kT",
    "drive": "constant force on every rod, in kT per wavelength",
    "gamma": "Baxter stickiness, dimensionless (0: hard rods)",
    "p": "exponent of the delta_eps representation (B-31), dimensionless",
    "eps": "range of the delta_eps representation (B-31), in wavelengths (0: Baxter's limit, a sticky boundary)",
    "pair": "a generated pair potential V(r) between neighbours instead of the sticky contact (e.g. wca)",
    "pair_params": "parameters of the pair potential, repeatable (default: none)",
    "pair_range": "gap beyond sigma where the pair potential ends, in wavelengths (< sigma)",
    "dt": "time step, in wavelength^2/D (bias O(dt) with the bridge layer, O(sqrt(dt)) with merge)",
    "seed": "noise seed, an integer",
    "start_sweeps": "Monte Carlo sweeps of the equilibrium start (none: 2000, or 20000 for the sticky boundary eps = 0)",
    "contact_layer": "how a step ends collisions: bridge (Brownian-bridge push, O(dt)), reflect (elastic) or merge (BCD's, O(sqrt(dt)))",
    "drift_scheme": "where a step evaluates the forces: euler (its start), lm (Leimkuhler-Matthews: noise midpoint) or "
    "metropolis (its start, then a Metropolis test of the step: the exact equilibrium); lm, metropolis: bridge, hard rods",
    "replicas": "independent rings run in parallel, the samples of the errors",
    "bins": "bins over one wavelength",
    "gap_width": "bin width of the gap histogram (contact density), in wavelengths",
    "gap_bins": "bins of the gap histogram",
    "fit_bins": "gap bins fitted beyond the BCD layer",
}
