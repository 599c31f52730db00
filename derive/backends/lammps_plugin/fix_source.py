"""The C++ source of the LAMMPS fix ``fricgen/exact/<law>`` as a template that
fricgen.derive.backends.lammps_plugin.fix_code fills (the law's kernels, the ported contact step, the step of
a batch of pairs of the law's mode from fix_modes, the calculi): its keywords, checks, solvent step, pair collection,
phases, and fix_comm's communication; the design is in fix_code's docstring and docs/guide/lammps.md#the-exact-contact-step."""

from string import Template

from .fix_comm import COMMUNICATION
from .templates import LAW_CONSTANTS

FIX_SOURCE = Template(
    r"""#include "fix_fricgen_${law}.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"
#include "utils.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {

"""
    + LAW_CONSTANTS
    + r"""const int SIGMA_INDEX = ${sigma_index};    // 1: distances scaled by sigma_ik = R_i + R_k (the engine's convention)
const double WCA_RANGE = 1.122462048309373;    // 2^(1/6)
// The calculi in fricgen.derive.calculus.Calculus's order, theta of each (contact_step.THETA), which of them the law has.
const char *const CALCULI[3] = {"ito", "stratonovich", "hk"};
const double THETAS[3] = {0.0, 0.5, 1.0};
const bool HAS_CALCULUS[3] = {${has_calculus}};

${support}${ziggurat}
// --- the law's kernels (derive, verified: ${verified}) -------------------------------------------

${kernels}${dispatch}${step_code}}    // namespace

${fix_cls}::${fix_cls}(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg), list(nullptr)
{
  if (narg < 5) error->all(FLERR, "Illegal fix fricgen/exact/${law} command: give kT and seed");
  kT = utils::numeric(FLERR, arg[3], false, lmp);
  seed = utils::bnumeric(FLERR, arg[4], false, lmp);
  if (!(kT > 0.0)) error->all(FLERR, "fix fricgen/exact/${law}: kT must be > 0, got {}", kT);
  if (seed < 0) error->all(FLERR, "fix fricgen/exact/${law}: seed must be >= 0, got {}", seed);
  noise_on = 1;
  gamma = gamma_rot = 0.0;
  calculus = 0;
  inertia = 0.4;
  for (int k = 0; k < NPARAMS; k++) params[k] = DEFAULTS[k];
  if (SIGMA_INDEX >= 0) params[SIGMA_INDEX] = 1.0;
  for (int a = 5; a < narg; a += 2) {
    if (a + 1 >= narg) error->all(FLERR, "fix fricgen/exact/${law}: keyword {} needs a value", arg[a]);
    const std::string key = arg[a];
    if (key == "solvent") {
      if (a + 2 >= narg) error->all(FLERR, "fix fricgen/exact/${law}: solvent needs two values, gamma and gamma_R");
      gamma = utils::numeric(FLERR, arg[a + 1], false, lmp);
      gamma_rot = utils::numeric(FLERR, arg[a + 2], false, lmp);
      if (!(gamma >= 0.0 && gamma_rot >= 0.0))
        error->all(FLERR, "fix fricgen/exact/${law}: solvent gamma and gamma_R must be >= 0, got {} and {}", gamma, gamma_rot);
      a++;
      continue;
    }
    if (key == "noise") {
      noise_on = utils::logical(FLERR, arg[a + 1], false, lmp);
      continue;
    }
    if (key == "calculus") {
      calculus = 0;
      while (calculus < 3 && std::string(arg[a + 1]) != CALCULI[calculus]) calculus++;
      if (calculus == 3 || !HAS_CALCULUS[calculus])
        error->all(FLERR, "fix fricgen/exact/${law}: calculus {} not available; the law has ${calculi_list}", arg[a + 1]);
      continue;
    }
    if (key == "inertia") {
      const std::string value = arg[a + 1];
      inertia = value == "sphere" ? 0.4 : value == "disc" ? 0.5 : utils::numeric(FLERR, value, false, lmp);
      if (!(inertia > 0.0)) error->all(FLERR, "fix fricgen/exact/${law}: inertia must be sphere, disc or a factor > 0");
      continue;
    }
    int k = 0;
    while (k < NPARAMS && key != PARAMETERS[k]) k++;
    if (k == NPARAMS || k == SIGMA_INDEX)
      error->all(FLERR, "fix fricgen/exact/${law}: unknown keyword {} (noise, calculus, inertia, solvent or a law parameter: "
                 "${parameter_list})", key);
    const double value = utils::numeric(FLERR, arg[a + 1], false, lmp);
    const double *range = RANGES[k];
    const bool above = value > range[0] || (range[2] != 0.0 && value == range[0]);
    const bool below = value < range[1] || (range[3] != 0.0 && value == range[1]);
    if (!(above && below))
      error->all(FLERR, "fix fricgen/exact/${law}: {} = {} is outside its range {}{}, {}{}", key, value,
                 range[2] != 0.0 ? "[" : "(", range[0], range[1], range[3] != 0.0 ? "]" : ")");
    params[k] = value;
  }
  comm_forward = 6;
  comm_reverse = 7;    // a ghost copy's touched flag, velocity and spin; or a count and up to 6 IDs (send_pairs)
  sending = false;
  reach = 0.0;
  contacts = 0;
  built = -1;
}

${fix_cls}::~${fix_cls}() = default;

// The solvent and contact steps run at the end of each step, after fix nve/sphere's second half kick (velocity
// Verlet B A B, then O C); under run_style respa once per outer step, after the inner steps of the forces.
int ${fix_cls}::setmask()
{
  return END_OF_STEP;
}

void ${fix_cls}::init()
{
${fix_dimension_check}  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag)
    error->all(FLERR, "fix fricgen/exact/${law} needs radius, per-atom mass and omega: use atom_style sphere");
  if (domain->triclinic)
    error->all(FLERR, "fix fricgen/exact/${law}: triclinic boxes are not supported (the phases halve orthogonal sub-domains)");
  if (atom->map_style == Atom::MAP_NONE)
    error->all(FLERR, "fix fricgen/exact/${law} needs an atom map: put atom_modify map array before the box is created");
  if (!comm->ghost_velocity)
    error->all(FLERR, "fix fricgen/exact/${law} needs the velocities of ghost atoms: use comm_modify vel yes");
  if (modify->get_fix_by_style("^nve/sphere").empty())
    error->all(FLERR, "fix fricgen/exact/${law} needs fix nve/sphere: it integrates positions, forces and spins around the contact step");
  if (force->pair_match("fricgen/${law}", 1))
    error->all(FLERR, "fix fricgen/exact/${law} and pair_style fricgen/${law} would apply the friction of ${law} twice: "
               "take lj/cut for WCA with the fix, or the pair style alone");
  // the pair style's half list (the same request: LAMMPS shares it, no second build); a pair that only the rank of
  // its higher-ID atom lists is sent to the rank of the lower (collect_candidates)
  neighbor->add_request(this, NeighConst::REQ_DEFAULT);
}

void ${fix_cls}::init_list(int, NeighList *ptr)
{
  list = ptr;
}

void ${fix_cls}::setup(int)
{
  double largest = 0.0, all;
  for (int i = 0; i < atom->nlocal; i++) largest = std::max(largest, atom->radius[i]);
  MPI_Allreduce(&largest, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  reach = WCA_RANGE * 2.0 * all;
  if (reach > neighbor->cutneighmax - neighbor->skin)
    error->all(FLERR, "fix fricgen/exact/${law}: the contacts reach {} (2^(1/6) times the largest diameter), beyond the pair "
               "cutoff {}: give the pair style a cutoff of at least {}", reach, neighbor->cutneighmax - neighbor->skin, reach);
  built = -1;    // collect the candidates afresh: setup may have sorted the atoms
}

// Each half of a split sub-domain must be wider than two contact reaches and the skin: atoms touched in one
// phase by two ranks would otherwise meet.
void ${fix_cls}::check_domain()
{
  for (int d = 0; d < domain->dimension; d++) {
    if (comm->procgrid[d] == 1) continue;
    const double half = 0.5 * (domain->subhi[d] - domain->sublo[d]);
    double thinnest;
    MPI_Allreduce(&half, &thinnest, 1, MPI_DOUBLE, MPI_MIN, world);
    if (!(thinnest > 2.0 * reach + neighbor->skin))
      error->all(FLERR, "fix fricgen/exact/${law}: sub-domains too thin along {}: half a sub-domain is {}, the phases need more than "
                 "2 contact reaches + skin = {}: use fewer ranks along it (processors) or a larger system",
                 "xyz"[d], thinnest, 2.0 * reach + neighbor->skin);
  }
}

${pair_step}
// On each neighbour-list build (atoms are renumbered only then): every listed pair once, as (lower ID, higher ID),
// in the engine's pair order (IDs sorted), so that a step only filters the contacts from it; each pair on the rank
// owning its lower-ID atom. The half list gives a pair from either atom; a pair between an owned atom and a ghost
// with newton off from both sides (kept from the lower ID), with newton on from one: where that is the rank of the
// higher ID, the pair is sent to the lower's owner (send_pairs).
void ${fix_cls}::collect_candidates()
{
  const tagint *tag = atom->tag;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int *ilist = list->ilist, *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  const bool several = comm->nprocs > 1, twice = !force->newton_pair;
  // the owned atoms by ID: on one rank every ID through the atom map, on several a sort of the owned atoms
  order.clear();
  if (several) {
    for (int ii = 0; ii < list->inum; ii++) {
      const int i = ilist[ii];
      if (mask[i] & groupbit) order.push_back({tag[i], i});
    }
    std::sort(order.begin(), order.end());
  } else {
    for (tagint id = 1; id <= atom->map_tag_max; id++) {
      const int i = atom->map(id);
      if (i >= 0 && i < nlocal && (mask[i] & groupbit)) order.push_back({id, i});
    }
  }
  place.assign(nlocal, 0);
  for (size_t o = 0; o < order.size(); o++) place[order[o].second] = static_cast<int>(o);
  // the pairs, counted by the place of their lower-ID atom
  scratch.clear();
  sent.clear();
  received.clear();
  counts.assign(order.size() + 1, 0);
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = ilist[ii];
    if (!(mask[i] & groupbit)) continue;
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = firstneigh[i][jj] & NEIGHMASK;
      if (tag[j] == tag[i] || !(mask[j] & groupbit)) continue;
      const bool up = tag[j] > tag[i];
      if (!up && j >= nlocal && twice) continue;    // listed from the lower ID as well
      const int canonical = atom->map(tag[j]);
      if (!up && canonical >= nlocal) {    // the lower ID is owned by another rank: it gets the pair
        sent.push_back({j, tag[i]});
        continue;
      }
      const Pair p = up ? Pair{tag[i], tag[j], i, canonical, i, j, 0, 0} : Pair{tag[j], tag[i], canonical, i, j, i, 0, 0};
      scratch.push_back(p);
      counts[place[p.i] + 1]++;
    }
  }
  if (several) send_pairs();
  for (const std::pair<int, tagint> &got : received) {    // (owned lower-ID atom, the higher ID)
    const int i = got.first, c = atom->map(got.second);
    scratch.push_back(Pair{tag[i], got.second, i, c, i, domain->closest_image(i, c), 0, 0});
    counts[place[i] + 1]++;
  }
  // by lower ID (counting sort), then each atom's partners by higher ID (a handful: insertion sort)
  for (size_t o = 0; o < order.size(); o++) counts[o + 1] += counts[o];
  candidates.resize(scratch.size());
  pairs.resize(candidates.size());    // room for every candidate: a step writes its contacts first
  for (const Pair &p : scratch) candidates[counts[place[p.i]]++] = p;
  for (size_t o = 0, first = 0; o < order.size(); first = counts[o++])
    for (size_t q = first + 1; q < static_cast<size_t>(counts[o]); q++) {
      const Pair p = candidates[q];
      size_t slot = q;
      for (; slot > first && candidates[slot - 1].hi > p.hi; slot--) candidates[slot] = candidates[slot - 1];
      candidates[slot] = p;
    }
  const size_t nall = static_cast<size_t>(atom->nlocal + atom->nghost);
  degree.resize(nall, 0);    // degree, used and touched are all zero between steps
  touched.resize(nall, 0);
  if (used.size() < nall) used.resize(nall, 0);
  built = neighbor->ncalls;
  check_domain();    // sub-domains change on neighbour-list builds only
}

// Stable counting sort of pairs[first, last) by key(pair) < keys, through the scratch buffer.
template <typename Key> void ${fix_cls}::sort_by(size_t first, size_t last, int keys, Key key)
{
  counts.assign(keys + 1, 0);
  for (size_t q = first; q < last; q++) counts[key(pairs[q]) + 1]++;
  for (int c = 0; c < keys; c++) counts[c + 1] += counts[c];
  scratch.resize(last - first);
  for (size_t q = first; q < last; q++) scratch[counts[key(pairs[q])]++] = pairs[q];
  std::copy(scratch.begin(), scratch.end(), pairs.begin() + first);
}

// The engine's solvent step O (single_particle.kick_drift_solvent) on the owned atoms: the exact Ornstein-Uhlenbeck
// update v <- c v + s xi, c = exp(-gamma dt / m), s = sqrt(kT (1 - c^2) / m), and its rotational twin with gamma_R
// and I, the normals of the SOLVENT stream keyed on 6 (ID - 1) + component.
void ${fix_cls}::solvent_step()
{
  double **v = atom->v, **omega = atom->omega;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const tagint *tag = atom->tag;
  const int *mask = atom->mask;
  const double dt = update->dt;
  const uint64_t key = stream_key(static_cast<uint64_t>(seed), static_cast<uint64_t>(update->ntimestep - 1), SOLVENT_STREAM);
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double inv_m = 1.0 / rmass[i], inv_i = 1.0 / (inertia * rmass[i] * (radius[i] * radius[i]));
    const double c = std::exp(-gamma * inv_m * dt), cr = std::exp(-gamma_rot * inv_i * dt);
    const double s = std::sqrt(kT * inv_m * (1.0 - c * c)), sr = std::sqrt(kT * inv_i * (1.0 - cr * cr));
    const uint64_t first = 6 * static_cast<uint64_t>(tag[i] - 1);
    v[i][0] = c * v[i][0] + s * ziggurat_normal(key, first);
    v[i][1] = c * v[i][1] + s * ziggurat_normal(key, first + 1);
    omega[i][2] = cr * omega[i][2] + sr * ziggurat_normal(key, first + 2);
    if (domain->dimension == 3) {
      v[i][2] = c * v[i][2] + s * ziggurat_normal(key, first + 3);
      omega[i][0] = cr * omega[i][0] + sr * ziggurat_normal(key, first + 4);
      omega[i][1] = cr * omega[i][1] + sr * ziggurat_normal(key, first + 5);
    }
  }
}

void ${fix_cls}::end_of_step()
{
  if (neighbor->ncalls != built) collect_candidates();
  if (gamma > 0.0 || gamma_rot > 0.0) solvent_step();
  // the last half kick and the solvent changed the owned copies only: on several ranks the ghosts get them
  // (on one the pair steps read the owned copies)
  if (comm->nprocs > 1) comm->forward_comm(this);
  double **x = atom->x;
  const double *radius = atom->radius;
  const uint64_t key = stream_key(static_cast<uint64_t>(seed), static_cast<uint64_t>(update->ntimestep - 1), ${stream});
  int split[3] = {0, 0, 0}, phases = 1;
  for (int d = 0; d < domain->dimension; d++)
    if (comm->procgrid[d] > 1) {
      split[d] = phases;
      phases *= 2;
    }
  // the pairs in contact in ID order, each in the phase of the halves that hold its owned atom
  // (each candidate is written and the count moves on for a contact: no branch to mispredict)
  contacts = 0;
  for (const Pair &candidate : candidates) {
    const int i = candidate.xi, j = candidate.xj;
    const double dx = x[j][0] - x[i][0], dy = x[j][1] - x[i][1], dz = x[j][2] - x[i][2];
    const double range = WCA_RANGE * (radius[i] + radius[j]);
    pairs[contacts] = candidate;
    contacts += dx * dx + dy * dy + dz * dz < range * range;
  }
  int most = 0;
  for (size_t q = 0; q < contacts; q++) {
    Pair &p = pairs[q];
    for (int d = 0; d < 3; d++)
      if (split[d] && x[p.i][d] >= 0.5 * (domain->sublo[d] + domain->subhi[d])) p.phase += split[d];
    most = std::max(most, std::max(++degree[p.i], ++degree[p.c]));
  }
  for (size_t q = 0; q < contacts; q++) degree[pairs[q].i] = degree[pairs[q].c] = 0;
  if (phases > 1) sort_by(0, contacts, phases, [](const Pair &p) { return p.phase; });
  // greedy edge colouring in pair order within each phase (contact_step.colour_classes): a pair takes the
  // lowest colour free at both atoms; fewer than 2 most colours are needed
  const int words = (2 * most) / 64 + 1;
  if (used.size() < degree.size() * words) used.assign(degree.size() * words, 0);
  size_t first = 0;
  while (first < contacts) {
    size_t last = first;
    while (last < contacts && pairs[last].phase == pairs[first].phase) last++;
    for (size_t q = first; q < last; q++) {
      Pair &p = pairs[q];
      uint64_t *ui = &used[static_cast<size_t>(p.i) * words], *uc = &used[static_cast<size_t>(p.c) * words];
      int word = 0;
      while (~(ui[word] | uc[word]) == 0) word++;
      const int bit = __builtin_ctzll(~(ui[word] | uc[word]));
      ui[word] |= 1ULL << bit;
      uc[word] |= 1ULL << bit;
      p.colour = word * 64 + bit;
    }
    for (size_t q = first; q < last; q++) {
      std::fill_n(&used[static_cast<size_t>(pairs[q].i) * words], words, 0);
      std::fill_n(&used[static_cast<size_t>(pairs[q].c) * words], words, 0);
    }
    sort_by(first, last, 64 * words, [](const Pair &p) { return p.colour; });
    first = last;
  }
  // the phases one after another; the pairs of a phase in colour order, up to BATCH of one colour at a time
  size_t q = 0;
  for (int phase = 0; phase < phases; phase++) {
    while (q < contacts && pairs[q].phase == phase) {
      size_t end = q + 1;
      while (end < contacts && end - q < BATCH && pairs[end].phase == phase && pairs[end].colour == pairs[q].colour) end++;
      step_batch(&pairs[q], static_cast<int>(end - q), key);
      q = end;
    }
    if (phases == 1) break;
    comm->reverse_comm(this);    // touched ghost copies to their owners
    std::fill(touched.begin(), touched.end(), 0);
    if (phase + 1 < phases) comm->forward_comm(this);    // the owners' velocities and spins to every ghost
  }
}

"""
    + COMMUNICATION
)
