"""The C++ text of the LAMMPS fix ``fricgen/exact/<law>``: fricgen's pairwise contact step
(fricgen/langevin/contact_step.py, docs/physics.md#the-pairwise-contact-step), formula for formula,
under MPI domain decomposition.

Per step, at end_of_step (after fix nve/sphere's velocity Verlet, B A B; under run_style respa once per
outer step, after the inner steps), the solvent's exact Ornstein–Uhlenbeck step O if asked for, then every pair of
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
(contact_step.colour_classes), up to BATCH pairs of one colour together, stage by stage (move_batch: they share
no atom, so this changes no result and lets the processor overlap their chains); an atom's ghost copies share
one canonical copy (atom->map). After a phase, the touched ghost copies' velocities and spins go to their owners (reverse communication, a
copy that was not touched carries none) and the owners' to every ghost (forward communication).
On one rank the fix therefore reproduces the engine's step to round-off (a pair across the periodic
boundary takes its vector from a ghost image); on several, the engine's step with the touching pairs split
by phase. The candidate pairs are collected and ID-sorted once per neighbour-list build from the pair style's
half list (shared, built once; with newton on a pair listed only on the rank of its higher-ID atom is sent to
the lower's owner by reverse communication); a step filters the contacts from them and sorts phases and
colours by counting.
"""

from __future__ import annotations

from string import Template

from ...law.names import camel
from .fix_modes import PAIR_STEP, SPINNING_2D, STREAM
from .fix_source import FIX_SOURCE

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
// The pair's parts of the law free of u are in held (hold).
inline ModeStep mode_step(Cx x, double w, double r, double mu, double kT, double dt, const double *params, int comps, int calculus,
                          const double *held)
{
  const double THETA = THETAS[calculus];
  const double inv_mu = 1.0 / mu, inv_spread = 1.0 / ((1.0 - THETA) * mu * kT);    // divisions off the chain from u
  const double u = comps == 1 ? std::fabs(x.re) : std::sqrt(x.re * x.re + x.im * x.im);
  const double ratio = friction_over_u(u, w, r, params, held);
  const double amplitude = noise_amplitude(calculus, u, w, r, mu, kT, params, held);
  double slope_over_u;
  if (THETA == 1.0)    // D'/u with D = f/u
    slope_over_u = u > 0.0 ? (friction_slope(u, w, r, params, held + SLOPE_AT) - ratio) / (u * u) : 0.0;
  else
    slope_over_u = (amplitude - ratio) * inv_spread;
  const double rate = mu * amplitude, inv_amplitude = 1.0 / amplitude;
  const double decay = std::expm1(-rate * dt);
  const double span = rate > 0.0 ? -decay * inv_amplitude * inv_mu : dt;
  const double s2 = -mu * kT * decay * (2.0 + decay);
  const Cx g = real(amplitude > 0.0 ? 0.5 * slope_over_u * inv_amplitude : 0.0) * Cx{x.re, -x.im};
  Cx m = real(-mu * ratio + THETA * mu * mu * kT * slope_over_u) * x * real(span);
  if (comps == 1) m = m - real(0.5) * g * real(s2);
  return {ratio, m, s2, g};
}

inline double log_proposal(double xi2, Cx g_w, int comps)
{
  return -0.5 * xi2 - comps * g_w.re;
}

// A pair's mode as its move reads it: x, the law's w and r, the mode's mobility mu, its components, noise key and
// the law's parts free of u (hold).
struct Move {
  Cx x;
  double w, r, mu;
  int comps;
  uint64_t key;
  double held[HELD];
};

// Pairs of one colour share no atom: the fix moves up to BATCH of them together, one stage after the other,
// so that the processor overlaps their independent chains of divisions and library calls (the arithmetic of
// each pair is unchanged).
const int BATCH = 8;

// The moves y of count <= BATCH modes from x: the Metropolis-Hastings move with the noise (contact_step._propose,
// step for step), else the friction's decay x e^(-mu (f/u) dt) (contact_step.update_pair and update_rolling).
inline void move_batch(const Move *ms, int count, double kT, double dt, const double *params, int calculus, bool noise, Cx *y)
{
  ModeStep a[BATCH], b[BATCH];
  Cx xi[BATCH], g_w[BATCH];
  bool open[BATCH];    // a proposal y awaits its acceptance
  for (int q = 0; q < count; q++) a[q] = mode_step(ms[q].x, ms[q].w, ms[q].r, ms[q].mu, kT, dt, params, ms[q].comps, calculus, ms[q].held);
  for (int q = 0; q < count; q++) {
    const Move &m = ms[q];
    y[q] = m.x;
    open[q] = false;
    if (!noise) {
      y[q] = m.x * real(std::exp(-m.mu * a[q].ratio * dt));
      continue;
    }
    if (!(a[q].s2 > 0.0)) continue;
    xi[q] = {ziggurat_normal(m.key, 0), m.comps == 2 ? ziggurat_normal(m.key, 1) : 0.0};
    const Cx move = a[q].m + real(std::sqrt(a[q].s2)) * xi[q];
    g_w[q] = a[q].g * move;
    if (std::fabs(g_w[q].im) >= 3.141592653589793) continue;
    y[q] = m.x + (nonzero(a[q].g) ? expm1_c(g_w[q], m.comps) * inverse(a[q].g) : move);
    open[q] = true;
  }
  for (int q = 0; q < count; q++)
    if (open[q]) b[q] = mode_step(y[q], ms[q].w, ms[q].r, ms[q].mu, kT, dt, params, ms[q].comps, calculus, ms[q].held);
  for (int q = 0; q < count; q++) {
    if (!open[q]) continue;
    const Cx x = ms[q].x, yq = y[q];
    const int comps = ms[q].comps;
    y[q] = x;    // until accepted
    const Cx z = b[q].g * (x - yq);
    if (!(b[q].s2 > 0.0 && (comps == 2 || 1.0 + z.re > 0.0))) continue;
    const Cx back = nonzero(b[q].g) ? log1p_c(z, comps) * inverse(b[q].g) : x - yq;
    double log_alpha = (x.re * x.re + x.im * x.im - yq.re * yq.re - yq.im * yq.im) / (2.0 * ms[q].mu * kT);
    const Cx shift = back - b[q].m;
    const double xi2_back = (shift.re * shift.re + shift.im * shift.im) / b[q].s2;
    log_alpha += log_proposal(xi2_back, b[q].g * back, comps) - log_proposal(xi[q].re * xi[q].re + xi[q].im * xi[q].im, g_w[q], comps);
    log_alpha += 0.5 * comps * std::log(a[q].s2 / b[q].s2);
    // accepted if U < e^(log alpha); e^a >= 1 + a, so U < 1 + a decides most without the exp
    if (log_alpha >= 0.0) {
      y[q] = yq;
      continue;
    }
    const double chance = uniform(ms[q].key, 2);
    if (chance < 1.0 + log_alpha || chance < std::exp(log_alpha)) y[q] = yq;
  }
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

FIX_HEADER = Template("""#ifndef LMP_FIX_FRICGEN_${LAW_UPPER}_H
#define LMP_FIX_FRICGEN_${LAW_UPPER}_H

#include "fix.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace LAMMPS_NS {

// fix ID group fricgen/exact/${law} kT seed [noise yes|no] [calculus ${calculi_list}] [inertia sphere|disc|c]
//     [solvent gamma gamma_R] [name value ...]
// (law parameters: ${parameter_list}; sigma is 1: distances are scaled by R_i + R_k, as in fricgen's engine)
class ${fix_cls} : public Fix {
 public:
  ${fix_cls}(class LAMMPS *, int, char **);
  ~${fix_cls}() override;
  int setmask() override;
  void init() override;
  void init_list(int, class NeighList *) override;
  void setup(int) override;
  void end_of_step() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;

  struct Pair {
    tagint lo, hi;    // atom IDs, lo < hi
    int i, c;         // the canonical copies of lo (owned) and hi
    int xi, xj;       // the neighbour-list copies of lo and hi: the pair's vector is x[xj] - x[xi]
    int phase, colour;
  };

 protected:
  double kT, inertia, reach, gamma, gamma_rot;    // gamma, gamma_rot: the solvent's frictions (0: none)
  bigint seed;
  int noise_on, calculus;
  double params[${nparams}];
  class NeighList *list;
  bigint built;                          // neighbor->ncalls when the candidates were collected
  std::vector<Pair> candidates, pairs;    // the listed pairs in ID order; this step's contacts (its first contacts)
  size_t contacts;
  std::vector<Pair> scratch;
  std::vector<std::pair<tagint, int>> order;    // (ID, index) of the owned atoms, by ID
  std::vector<int> place, degree, counts;       // place: an owned atom's position in order
  std::vector<uint64_t> used;
  std::vector<char> touched;
  // collect_candidates on several ranks: pairs (ghost copy of the lower-ID atom, higher ID) to send to the lower's
  // owner, the next of each ghost's to pack, and the pairs received (owned lower-ID atom, higher ID)
  std::vector<std::pair<int, tagint>> sent, received;
  std::vector<int> next_sent, end_sent;
  bool sending;    // the reverse communication carries pairs, not velocities
  void check_domain();
  void solvent_step();
  void collect_candidates();
  void send_pairs();
  template <typename Key> void sort_by(size_t, size_t, int, Key);
  void step_batch(const Pair *, int, uint64_t);
};

}    // namespace LAMMPS_NS

#endif
""")


def fix_files(
    fields: dict[str, str], kernels: tuple[str, str], support: str, ziggurat: str, weighted: bool, calculi: list[str], mode: str
) -> dict[str, str]:
    """The fix's header and source (by file name) of a law on ``mode``, from the pair style's ``fields``, the
    law's C++ ``kernels`` and its functions hold and noise_amplitude over its ``calculi`` (held_code.fix_kernels),
    the shared ``support`` code, the ``ziggurat`` (with the mode's stream constant) and whether f has a weight."""
    values = {
        **fields,
        "fix_cls": fix_class(fields["law"]),
        "calculi_list": calculi_list(calculi),
        "has_calculus": ", ".join("true" if c in calculi else "false" for c in THETA),
        "support": support,
        "ziggurat": ziggurat,
        "kernels": kernels[0],
        "dispatch": kernels[1],
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
