"""The pair style of a rolling or spinning law (docs/physics-modes.md): the couples of the engine's
explicit kick (fricgen/langevin/modes.py), formula for formula, and its ziggurat normals.

Per pair within 2^(1/6) sigma, oriented from the atom of lower ID (a) to the higher (b), as the
engine's pair (i, k) = (ID_a - 1, ID_b - 1), with n from a to b, R_eff = R_a R_b / (R_a + R_b),
mu_m = R_eff^2 (1/I_a + 1/I_b), I = c m R^2:

- the mode's velocity x = v_m . (e1 + i e2) in the engine's basis (fricgen.langevin.contact_step.
  rolling_mode): rolling R_eff (w_a - w_b) x n on the tangents of _tangents (3-D), R_eff (w_az - w_bz)
  along z (2-D); spinning R_eff (w_a - w_b) . n along n;
- the generalized force J = -(f/u) x + sqrt(D) sqrt(2 kT / dt) xi in the mode's space, xi standard
  normal per component, ziggurat_normal(pair_key(stream key, ID_a - 1, ID_b - 1), j) of the engine's
  ROLLING or SPINNING stream: the same normals as the engine for the same seed;
- the torque tau_a = R_eff n x J (3-D rolling), R_eff J (2-D rolling along z, spinning along n),
  tau_b = -tau_a: a couple, no force, no energy, no virial.

The pair style applies no conservative force: it is meant to be overlaid on a sliding law's pair style
(whose WCA and sliding friction it adds to) or on WCA from ``lj/cut`` by ``pair_style hybrid/overlay``.
The ziggurat's tables are fricgen.rng's, handed to :func:`ziggurat_support` by the caller (derive never
imports the runtime), so the C++ draws the engine's normals bit for bit.
"""

from __future__ import annotations

from string import Template

import numpy as np

from .templates import PAIR_LOOP

#: The engine's noise streams of the modes (fricgen.rng.ROLLING, SPINNING), whose keys the tests check.
STREAMS = {"rolling": 6, "spinning": 7}

_ZIGGURAT = Template("""
// Ziggurat normals of fricgen/rng.py (Marsaglia & Tsang 2000, 256 layers), bit for bit: one SplitMix64 output
// z = word(key, j) gives the layer (bits 0-7), the sign (bit 8) and u (bits 11-63); x = u W[layer] when
// u < K[layer], else the tail or the wedge test (ziggurat_slow), continuing the SplitMix64 sequence from z.
${stream_line}const double ZIG_R = ${r};
const double ZIG_W[256] = {${w}};
const uint64_t ZIG_K[256] = {${k}};
const double ZIG_F[257] = {${f}};

inline uint64_t next_word(uint64_t &state)
{
  state += GOLDEN;
  return mix(state);
}

inline double ziggurat_slow(uint64_t z)
{
  uint64_t state = z;
  while (true) {
    const uint64_t layer = z & 255ULL, u = z >> 11;
    double x = static_cast<double>(u) * ZIG_W[layer];
    if (layer == 0) {
      if (u >= ZIG_K[0]) {    // the tail beyond r (Marsaglia 1964)
        while (true) {
          const uint64_t a = next_word(state);
          const uint64_t b = next_word(state);
          x = -std::log((static_cast<double>(a >> 11) + 1.0) * TWO_53) / ZIG_R;
          if (-2.0 * std::log((static_cast<double>(b >> 11) + 1.0) * TWO_53) > x * x) break;
        }
        x += ZIG_R;
      }
    } else if (u >= ZIG_K[layer]) {    // the wedge
      const uint64_t a = next_word(state);
      if (ZIG_F[layer] + static_cast<double>(a >> 11) * TWO_53 * (ZIG_F[layer + 1] - ZIG_F[layer]) >= std::exp(-0.5 * x * x)) {
        z = next_word(state);
        continue;
      }
    }
    return (z & 256ULL) ? -x : x;
  }
}

// A standard normal for (key, j): fricgen.rng.ziggurat_normal.
inline double ziggurat_normal(uint64_t key, uint64_t j)
{
  const uint64_t z = mix(key + j * GOLDEN);
  const uint64_t layer = z & 255ULL, u = z >> 11;
  if (u < ZIG_K[layer]) {
    const double x = static_cast<double>(u) * ZIG_W[layer];
    return (z & 256ULL) ? -x : x;
  }
  return ziggurat_slow(z);
}
""")


def ziggurat_support(mode: str, tables: tuple[np.ndarray, np.ndarray, np.ndarray], r: float) -> str:
    """The ziggurat of fricgen.rng in C++ with its ``tables`` (W, K, F) and tail start ``r``, and the mode's stream."""
    return ziggurat_code(tables, r, f"const int MODE_STREAM = {STREAMS[mode]};    // fricgen.rng.{mode.upper()}\n")


def ziggurat_code(tables: tuple[np.ndarray, np.ndarray, np.ndarray], r: float, stream_line: str = "") -> str:
    """The ziggurat of fricgen.rng in C++ with its ``tables`` (W, K, F) and tail start ``r``, after ``stream_line``."""
    w, k, f = tables
    if (len(w), len(k), len(f)) != (256, 256, 257):
        raise ValueError(f"ziggurat tables of 256, 256 and 257 entries expected, got {len(w)}, {len(k)}, {len(f)}")
    return _ZIGGURAT.substitute(
        stream_line=stream_line,
        r=repr(float(r)),
        w=", ".join(repr(float(x)) for x in w),
        k=", ".join(f"{int(x)}ULL" for x in k),
        f=", ".join(repr(float(x)) for x in f),
    )


#: The mode's value x = (xr, xi) and basis e1, e2 of the pair a -> b (fricgen.langevin.contact_step.rolling_mode).
MODE_VALUE = {
    "rolling": """      double xr, xi = 0.0, e1[3] = {0.0, 0.0, 1.0}, e2[3] = {0.0, 0.0, 0.0};
      if (three) {    // v_roll = R_eff (w_a - w_b) x n on the tangents (e1, e2) of contact_step._tangents
        const double sx = std::fabs(nx) < 0.9 ? 1.0 : 0.0, sy = 1.0 - sx;
        const double along = sx * nx + sy * ny;
        const double px = sx - along * nx, py = sy - along * ny, pz = -along * nz;
        const double norm = std::sqrt(px * px + py * py + pz * pz);
        e1[0] = px / norm;
        e1[1] = py / norm;
        e1[2] = pz / norm;
        e2[0] = ny * e1[2] - nz * e1[1];
        e2[1] = nz * e1[0] - nx * e1[2];
        e2[2] = nx * e1[1] - ny * e1[0];
        const double cx = dwy * nz - dwz * ny, cy = dwz * nx - dwx * nz, cz = dwx * ny - dwy * nx;
        xr = reff * (cx * e1[0] + cy * e1[1] + cz * e1[2]);
        xi = reff * (cx * e2[0] + cy * e2[1] + cz * e2[2]);
      } else {    // 2-D: R_eff (w_az - w_bz) along z
        xr = reff * dwz;
      }
""",
    "spinning": """      (void) three;    // 3-D only (init_style)
      // v_spin = R_eff (w_a - w_b) . n along e1 = n
      const double xr = reff * (dwx * nx + dwy * ny + dwz * nz), xi = 0.0;
      const double e1[3] = {nx, ny, nz}, e2[3] = {0.0, 0.0, 0.0};
""",
}
#: Whether the mode's space has two components (3-D rolling) in the pair style's terms.
COMPONENTS = {"rolling": "three", "spinning": "false"}
#: J in the lab frame made a torque on a (modes._torque): n x J for 3-D rolling, J otherwise.
TORQUE = {
    "rolling": "three ? ny * jz - nz * jy : jx, three ? nz * jx - nx * jz : jy, three ? nx * jy - ny * jx : jz",
    "spinning": "jx, jy, jz",
}

MODE_COMPUTE = Template(r"""void ${cls}::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);    // a couple: no force, no energy, no virial
  double **x = atom->x, **omega = atom->omega, **torque = atom->torque;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int *type = atom->type;
  const tagint *tag = atom->tag;
  const int nlocal = atom->nlocal, newton_pair = force->newton_pair, three = domain->dimension == 3;
  const uint64_t key = stream_key(static_cast<uint64_t>(seed), static_cast<uint64_t>(update->ntimestep), MODE_STREAM);
  const double noise_scale = std::sqrt(2.0 * kT / update->dt);    // sqrt(2 kT dt) / dt: the impulse as a force
  const int inum = list->inum;
  const int *ilist = list->ilist, *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  if (!friction_on) return;

  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii], itype = type[i];
    const int *jlist = firstneigh[i];
${pair_loop}      const bool lower = tag[i] < tag[j];    // the pair as the engine's (i, k): from the lower ID a to the higher b
      const int a = lower ? i : j, b = lower ? j : i;
      const double sign = lower ? 1.0 : -1.0;
      const double nx = sign * dx / r, ny = sign * dy / r, nz = sign * dz / r;
      const double *params = law[itype][jtype];
      const double ra = radius[a], rb = radius[b];
      const double reff = ra * rb / (ra + rb);
      const double w = ${weight_call};
      const double dwx = omega[a][0] - omega[b][0], dwy = omega[a][1] - omega[b][1], dwz = omega[a][2] - omega[b][2];
${mode_value}      const bool two = ${components};
      const double u = std::sqrt(xr * xr + xi * xi);
      const double ratio = friction_over_u(u, w, r, params);
      double jp = -ratio * xr, jq = -ratio * xi;    // the friction -(f/u) v_m in the mode's space
      if (noise_on) {
        const double inertia_a = inertia * rmass[a] * ra * ra, inertia_b = inertia * rmass[b] * rb * rb;
        const double mu = reff * reff * (1.0 / inertia_a + 1.0 / inertia_b);
        const double amplitude = std::sqrt(noise_amplitude_${calculus}(u, w, r, mu, kT, params)) * noise_scale;
        const uint64_t draws = pair_key(key, static_cast<uint64_t>(tag[a]) - 1, static_cast<uint64_t>(tag[b]) - 1);
        jp += amplitude * ziggurat_normal(draws, 0);
        if (two) jq += amplitude * ziggurat_normal(draws, 1);
      }
      const double jx = jp * e1[0] + jq * e2[0], jy = jp * e1[1] + jq * e2[1], jz = jp * e1[2] + jq * e2[2];
      const double q[3] = {${torque}};
      const double ti = lower ? reff : -reff;    // tau_a = R_eff q, tau_b = -tau_a
      torque[i][0] += ti * q[0];
      torque[i][1] += ti * q[1];
      torque[i][2] += ti * q[2];
      if (newton_pair || j < nlocal) {
        torque[j][0] -= ti * q[0];
        torque[j][1] -= ti * q[1];
        torque[j][2] -= ti * q[2];
      }
    }
  }
}
""")


def mode_compute(mode: str, cls: str, calculus: str, weight_call: str) -> str:
    """compute() of the pair style of a law on ``mode`` (rolling or spinning)."""
    return MODE_COMPUTE.substitute(
        pair_loop=PAIR_LOOP,
        cls=cls,
        calculus=calculus,
        weight_call=weight_call,
        mode_value=MODE_VALUE[mode],
        components=COMPONENTS[mode],
        torque=TORQUE[mode],
    )


def mode_fields(mode: str, law: str) -> dict[str, str]:
    """What the pair style of a law on ``mode`` puts in the shared template: its plugin's info, the note in
    place of the pair potential, and (spinning) the refusal of 2-D."""
    check = ""
    if mode == "spinning":
        check = (
            "  if (domain->dimension == 2)\n"
            f'    error->all(FLERR, "pair_style fricgen/{law} acts on spinning, which does not exist in 2-D: '
            'the spins are along z, normal to every contact normal");\n'
        )
    note = (
        f"// None: fricgen/{law} acts on the {mode} mode and exerts couples only; the WCA force comes from the sliding\n"
        "// law's pair style or lj/cut under pair_style hybrid/overlay.\n"
    )
    info = f"fricgen: {mode} friction law {law} with its noise (couples only; overlay it on WCA)"
    return {"dimension_check": check, "potential": note, "info": info}
