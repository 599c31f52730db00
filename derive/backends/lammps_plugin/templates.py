"""The C++ text of the LAMMPS pair style ``fricgen/<law>``: its class declaration and its methods
(compute() of a rolling or spinning law's style: fricgen.derive.backends.lammps_plugin.mode_code).

The physics is fricgen's engine, formula for formula (fricgen/langevin/pairs.py,
docs/physics.md#one-tangential-random-force and #the-two-dimensional-reduction): per pair i, j
within 2^(1/6) sigma, with r_hat from i to j,

- WCA (F-34) with epsilon, sigma of pair_coeff, cut and shifted at 2^(1/6) sigma;
- u_perp = P (v_j - v_i) - (R_i omega_i + R_j omega_j) x r_hat (F-4), F_f = (f/u) u_perp on i, -F_f on j;
- the noise force sqrt(D) sqrt(2 kT / dt) P z on the atom of lower ID (minus on the other), z a
  standard normal 3-vector keyed on (seed, step, ID_lo - 1, ID_hi - 1) exactly as fricgen.rng keys the
  engine's pair (i, k) = (ID_lo - 1, ID_hi - 1), so the same seed gives the same normals as the engine;
  in 2-D one normal along t = z x r_hat (r_hat from the lower ID to the higher);
- torques R_i r_hat x F and R_j r_hat x F (F: the tangential force on i), the same sign for both;
- mu = 1/m_i + 1/m_j + R_i^2/I_i + R_j^2/I_j with I = c m R^2, c = 2/5 (solid sphere, the paper's
  and LAMMPS's fix langevin and compute temp/sphere) unless pair_style says ``inertia disc`` (1/2,
  as fix nve/sphere disc) or a number.

The time scheme is LAMMPS's velocity Verlet: the pair force is computed once per step, at the
velocities after the first half kick, and acts for dt in total (half at the end of the step, half at
the start of the next). In the half-step velocities this is Euler–Maruyama with D taken at the start
of the step: the Itô calculus. Stratonovich (Heun) and Hänggi–Klimontovich (end point) would need a
second force evaluation with the predicted velocities and the same z, which a pair style cannot do
within one force computation; fricgen.derive.backends.lammps_plugin.module refuses them.
"""

from __future__ import annotations

from string import Template

HEADER = Template("""#ifndef LMP_PAIR_FRICGEN_${LAW_UPPER}_H
#define LMP_PAIR_FRICGEN_${LAW_UPPER}_H

#include "pair.h"

namespace LAMMPS_NS {

// pair_style fricgen/${law} kT seed [noise yes|no] [friction yes|no] [inertia sphere|disc|c]
// pair_coeff I J epsilon sigma [name value ...]   (law parameters: ${parameter_list})
class ${cls} : public Pair {
 public:
  ${cls}(class LAMMPS *);
  ~${cls}() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  static const char *built_for();    // "<law> <source hash>": checked when the plugin is loaded

 protected:
  double kT, inertia;
  bigint seed;
  int noise_on, friction_on;
  double **epsilon, **sigma, **cut;
  double ***law;    // law[i][j][k]: parameter k of the law for types i, j (PARAMETERS order)
  void allocate();
};

}    // namespace LAMMPS_NS

#endif
""")

#: The law's parameters as C++ constants (the pair style's and the fix's).
LAW_CONSTANTS = """const int NPARAMS = ${nparams};
const char *const PARAMETERS[NPARAMS] = {${parameter_names}};
const double DEFAULTS[NPARAMS] = {${defaults}};
// Admissible values: lower, upper, lower end closed, upper end closed (the law file's ranges).
const double RANGES[NPARAMS][4] = {${ranges}};
"""

SOURCE = Template(
    r"""#include "pair_fricgen_${law}.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"
#include "utils.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;

namespace {

"""
    + LAW_CONSTANTS
    + r"""const int EPSILON_INDEX = ${epsilon_index};    // set by pair_coeff's epsilon (-1: not a law parameter)
const int SIGMA_INDEX = ${sigma_index};        // set by pair_coeff's sigma
const bool HAS_WEIGHT = ${has_weight};
const double WCA_RANGE = 1.122462048309373;    // 2^(1/6)

${support}
// --- the pair potential (derive/law/potentials.py) --------------------------------------------------

${potential}
// --- the law's kernels (derive, verified: ${verified}) -------------------------------------------

${kernels}
}    // namespace

const char *${cls}::built_for()
{
  return "${built_for}";
}

${cls}::${cls}(LAMMPS *lmp) : Pair(lmp)
{
  single_enable = 0;
  restartinfo = 0;
  writedata = 0;
  kT = 1.0;
  inertia = 0.4;
  seed = 0;
  noise_on = friction_on = 1;
  epsilon = sigma = cut = nullptr;
  law = nullptr;
}

${cls}::~${cls}()
{
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(epsilon);
    memory->destroy(sigma);
    memory->destroy(cut);
    memory->destroy(law);
  }
}

void ${cls}::allocate()
{
  allocated = 1;
  const int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) setflag[i][j] = 0;
  memory->create(cutsq, n, n, "pair:cutsq");
  memory->create(epsilon, n, n, "pair:epsilon");
  memory->create(sigma, n, n, "pair:sigma");
  memory->create(cut, n, n, "pair:cut");
  memory->create(law, n, n, NPARAMS, "pair:law");
}

void ${cls}::settings(int narg, char **arg)
{
  if (narg < 2) error->all(FLERR, "Illegal pair_style fricgen/${law} command: give kT and seed");
  kT = utils::numeric(FLERR, arg[0], false, lmp);
  seed = utils::bnumeric(FLERR, arg[1], false, lmp);
  if (!(kT > 0.0)) error->all(FLERR, "pair_style fricgen/${law}: kT must be > 0, got {}", kT);
  if (seed < 0) error->all(FLERR, "pair_style fricgen/${law}: seed must be >= 0, got {}", seed);
  for (int k = 2; k < narg; k += 2) {
    if (k + 1 >= narg) error->all(FLERR, "pair_style fricgen/${law}: keyword {} needs a value", arg[k]);
    const std::string key = arg[k];
    if (key == "noise") noise_on = utils::logical(FLERR, arg[k + 1], false, lmp);
    else if (key == "friction") friction_on = utils::logical(FLERR, arg[k + 1], false, lmp);
    else if (key == "inertia") {
      const std::string value = arg[k + 1];
      inertia = value == "sphere" ? 0.4 : value == "disc" ? 0.5 : utils::numeric(FLERR, value, false, lmp);
      if (!(inertia > 0.0)) error->all(FLERR, "pair_style fricgen/${law}: inertia must be sphere, disc or a factor > 0");
    } else if (key == "calculus") {
      if (std::string(arg[k + 1]) != "ito")
        error->all(FLERR, "pair_style fricgen/${law}: calculus {} not available: velocity Verlet computes the pair "
                   "force once per step, at the start-of-step velocities, which is the Ito (Euler-Maruyama) scheme", arg[k + 1]);
    } else error->all(FLERR, "pair_style fricgen/${law}: unknown keyword {} (noise, friction, inertia, calculus)", key);
  }
}

void ${cls}::coeff(int narg, char **arg)
{
  if (narg < 4 || narg % 2)
    error->all(FLERR, "Incorrect args for pair coefficients: pair_coeff I J epsilon sigma [name value ...]");
  if (!allocated) allocate();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  const double epsilon_one = utils::numeric(FLERR, arg[2], false, lmp);
  const double sigma_one = utils::numeric(FLERR, arg[3], false, lmp);
  if (!(epsilon_one >= 0.0) || !(sigma_one > 0.0))
    error->all(FLERR, "pair_coeff fricgen/${law}: epsilon must be >= 0 and sigma > 0");
  double values[NPARAMS];
  for (int k = 0; k < NPARAMS; k++) values[k] = DEFAULTS[k];
  if (EPSILON_INDEX >= 0) values[EPSILON_INDEX] = epsilon_one;
  if (SIGMA_INDEX >= 0) values[SIGMA_INDEX] = sigma_one;
  for (int a = 4; a < narg; a += 2) {
    int k = 0;
    while (k < NPARAMS && std::strcmp(arg[a], PARAMETERS[k]) != 0) k++;
    if (k == NPARAMS || k == EPSILON_INDEX || k == SIGMA_INDEX)
      error->all(FLERR, "pair_coeff fricgen/${law}: {} is not a parameter set by name; the law has ${parameter_list} "
                 "(epsilon and sigma are the first two numbers)", arg[a]);
    const double value = utils::numeric(FLERR, arg[a + 1], false, lmp);
    const double *range = RANGES[k];
    const bool above = value > range[0] || (range[2] != 0.0 && value == range[0]);
    const bool below = value < range[1] || (range[3] != 0.0 && value == range[1]);
    if (!(above && below))
      error->all(FLERR, "pair_coeff fricgen/${law}: {} = {} is outside its range {}{}, {}{}", arg[a], value,
                 range[2] != 0.0 ? "[" : "(", range[0], range[1], range[3] != 0.0 ? "]" : ")");
    values[k] = value;
  }
  int count = 0;
  for (int i = ilo; i <= ihi; i++) {
    for (int j = MAX(jlo, i); j <= jhi; j++) {
      epsilon[i][j] = epsilon_one;
      sigma[i][j] = sigma_one;
      for (int k = 0; k < NPARAMS; k++) law[i][j][k] = values[k];
      setflag[i][j] = 1;
      count++;
    }
  }
  if (count == 0) error->all(FLERR, "Incorrect args for pair coefficients");
}

void ${cls}::init_style()
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "pair_style fricgen/${law} needs radius, per-atom mass, omega and torque: use atom_style sphere");
  if (!comm->ghost_velocity)
    error->all(FLERR, "pair_style fricgen/${law} needs the velocities of ghost atoms: use comm_modify vel yes");
  neighbor->add_request(this);
${dimension_check}}

double ${cls}::init_one(int i, int j)
{
  if (setflag[i][j] == 0) {
    for (int k = 0; k < NPARAMS; k++)
      if (k != EPSILON_INDEX && k != SIGMA_INDEX && law[i][i][k] != law[j][j][k])
        error->all(FLERR, "pair_coeff fricgen/${law}: {} differs between types {} and {}, which do not mix: give pair_coeff {} {}",
                   PARAMETERS[k], i, j, i, j);
    epsilon[i][j] = mix_energy(epsilon[i][i], epsilon[j][j], sigma[i][i], sigma[j][j]);
    sigma[i][j] = mix_distance(sigma[i][i], sigma[j][j]);
    for (int k = 0; k < NPARAMS; k++) law[i][j][k] = law[i][i][k];
    if (EPSILON_INDEX >= 0) law[i][j][EPSILON_INDEX] = epsilon[i][j];
    if (SIGMA_INDEX >= 0) law[i][j][SIGMA_INDEX] = sigma[i][j];
  }
  cut[i][j] = WCA_RANGE * sigma[i][j];
  epsilon[j][i] = epsilon[i][j];
  sigma[j][i] = sigma[i][j];
  cut[j][i] = cut[i][j];
  for (int k = 0; k < NPARAMS; k++) law[j][i][k] = law[i][j][k];
  return cut[i][j];
}

${compute}"""
)

#: The pairs of atom i's neighbour list within reach, r = |x_j - x_i| (both pair styles' compute()).
PAIR_LOOP = """    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK, jtype = type[j];
      const double dx = x[j][0] - x[i][0], dy = x[j][1] - x[i][1], dz = x[j][2] - x[i][2];
      const double rsq = dx * dx + dy * dy + dz * dz;
      if (rsq >= cutsq[itype][jtype]) continue;
      const double r = std::sqrt(rsq);
"""

#: compute() of the sliding pair style: WCA, the friction (f/u) u_perp with its torques, the noise (module docstring).
SLIDING_COMPUTE = Template(r"""void ${cls}::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  double **x = atom->x, **v = atom->v, **f = atom->f, **omega = atom->omega, **torque = atom->torque;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int *type = atom->type;
  const tagint *tag = atom->tag;
  const int nlocal = atom->nlocal, newton_pair = force->newton_pair, three = domain->dimension == 3;
  const uint64_t key = stream_key(static_cast<uint64_t>(seed), static_cast<uint64_t>(update->ntimestep), CONTACT_STREAM);
  const double noise_scale = std::sqrt(2.0 * kT / update->dt);    // sqrt(2 kT dt) / dt: the impulse as a force
  const int inum = list->inum;
  const int *ilist = list->ilist, *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;

  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii], itype = type[i];
    const double ri = radius[i];
    const int *jlist = firstneigh[i];
${pair_loop}      const double nx = dx / r, ny = dy / r, nz = dz / r;
      const double pot[2] = {epsilon[itype][jtype], sigma[itype][jtype]};
      const double magnitude = pair_force(r, pot);    // -dU/dr
      double fx = -magnitude * nx, fy = -magnitude * ny, fz = -magnitude * nz;    // on i
      double tx = 0.0, ty = 0.0, tz = 0.0;    // tangential force on i (friction and noise)
      const double rj = radius[j];
      if (friction_on) {
        const double *params = law[itype][jtype];
        // u_perp = P (v_j - v_i) - (R_i w_i + R_j w_j) x n   (F-4)
        const double wx = ri * omega[i][0] + rj * omega[j][0];
        const double wy = ri * omega[i][1] + rj * omega[j][1];
        const double wz = ri * omega[i][2] + rj * omega[j][2];
        const double rvx = v[j][0] - v[i][0], rvy = v[j][1] - v[i][1], rvz = v[j][2] - v[i][2];
        const double along = rvx * nx + rvy * ny + rvz * nz;
        const double cx = wy * nz - wz * ny, cy = wz * nx - wx * nz, cz = wx * ny - wy * nx;
        const double ux = rvx - along * nx - cx, uy = rvy - along * ny - cy, uz = rvz - along * nz - cz;
        const double u = std::sqrt(ux * ux + uy * uy + uz * uz);
        const double w = ${weight_call};
        const double ratio = friction_over_u(u, w, r, params);
        tx = ratio * ux;
        ty = ratio * uy;
        tz = ratio * uz;
        if (noise_on) {
          const double inv_i = 1.0 / rmass[i], inv_j = 1.0 / rmass[j];
          const double inertia_i = inertia * rmass[i] * ri * ri, inertia_j = inertia * rmass[j] * rj * rj;
          const double mu = inv_i + inv_j + ri * ri * (1.0 / inertia_i) + rj * rj * (1.0 / inertia_j);
          const double amplitude = std::sqrt(noise_amplitude_${calculus}(u, w, r, mu, kT, params)) * noise_scale;
          const bool lower = tag[i] < tag[j];    // the noise is keyed and oriented by atom IDs
          const uint64_t lo = static_cast<uint64_t>(lower ? tag[i] : tag[j]) - 1, hi = static_cast<uint64_t>(lower ? tag[j] : tag[i]) - 1;
          const double sign = lower ? 1.0 : -1.0;
          double z0, z1, z2, unused;
          normal_pair_at(key, lo, hi, 0, z0, z1);
          if (three) {    // P z: one random tangential force (P does not depend on the sign of n)
            normal_pair_at(key, lo, hi, 1, z2, unused);
            const double zn = z0 * nx + z1 * ny + z2 * nz;
            tx += sign * amplitude * (z0 - zn * nx);
            ty += sign * amplitude * (z1 - zn * ny);
            tz += sign * amplitude * (z2 - zn * nz);
          } else {    // along t = z x n_lo with n_lo = sign n: on i, amplitude z0 (z x n) for either order
            tx += -amplitude * z0 * ny;
            ty += amplitude * z0 * nx;
          }
        }
      }
      fx += tx;
      fy += ty;
      fz += tz;
      const double qx = ny * tz - nz * ty, qy = nz * tx - nx * tz, qz = nx * ty - ny * tx;    // n x F_t
      f[i][0] += fx;
      f[i][1] += fy;
      f[i][2] += fz;
      torque[i][0] += ri * qx;
      torque[i][1] += ri * qy;
      torque[i][2] += ri * qz;
      if (newton_pair || j < nlocal) {
        f[j][0] -= fx;
        f[j][1] -= fy;
        f[j][2] -= fz;
        torque[j][0] += rj * qx;
        torque[j][1] += rj * qy;
        torque[j][2] += rj * qz;
      }
      if (evflag) {
        const double energy = eflag ? pair_energy(r, pot) : 0.0;
        ev_tally_xyz(i, j, nlocal, newton_pair, energy, 0.0, fx, fy, fz, -dx, -dy, -dz);
      }
    }
  }
  if (vflag_fdotr) virial_fdotr_compute();
}
""")
