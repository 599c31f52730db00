"""The step of a batch of pairs (one colour: no shared atom) of the fix ``fricgen/exact/<law>`` by the mode its law
acts on, as C++ templates for fix_code: sliding (fricgen/langevin/contact_step.py update_pair: velocities and spins), rolling and spinning
(update_rolling with rolling_mode's mode vector: spins only), each mode's noise stream, and the refusal
of 2-D by a spinning law's fix."""

from textwrap import indent

#: What both pair steps start from: the pair's distance r, normal n (from lo to hi, on their neighbour-list copies),
#: radii, the law's weight w and the inverse moments of inertia, on the canonical copies i and k.
PAIR_GEOMETRY = """\
  double **x = atom->x, **omega = atom->omega;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int i = p.i, k = p.c;
  const double dx = x[p.xj][0] - x[p.xi][0], dy = x[p.xj][1] - x[p.xi][1], dz = x[p.xj][2] - x[p.xi][2];
  const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
  const double n[3] = {dx / r, dy / r, dz / r};
  const double ri = radius[i], rk = radius[k], sigma = ri + rk;
  const double w = ${weight_call};
  const double inv_ii = 1.0 / (inertia * rmass[i] * (ri * ri)), inv_ik = 1.0 / (inertia * rmass[k] * (rk * rk));
"""


def batch_step(comment: str, contact: str, before: str, prepare: str, impulse: str) -> str:
    """The member step_batch of a mode: the ``comment``, the per-pair ``Contact`` with the ``contact`` fields after
    i, k, n, e1, e2, the lines ``before`` the pairs' loop, the mode's ``prepare`` (after the geometry; it sets cs[q]
    and xm, mu, comps), the batch's move (move_batch) and the mode's ``impulse`` of each pair that moved (from c,
    xm, y, n, e1, e2 and mu). The text keeps fix_code's placeholders (${fix_cls}, ${weight_call})."""
    return (
        comment
        + r"""void ${fix_cls}::step_batch(const Pair *ps, int count, uint64_t key)
{
  struct Contact {
    int i, k;
    double n[3], e1[3], e2[3], """
        + contact
        + r""";
  };
  Contact cs[BATCH];
  Move ms[BATCH];
  Cx ys[BATCH];
"""
        + before
        + r"""  for (int q = 0; q < count; q++) {
    const Pair &p = ps[q];
"""
        + indent(PAIR_GEOMETRY, "  ")
        + prepare
        + r"""    Move &m = ms[q];    // field by field: held is written by hold, not zeroed first
    m.x = xm;
    m.w = w;
    m.r = r;
    m.mu = mu;
    m.comps = comps;
    m.key = pair_key(key, static_cast<uint64_t>(p.lo) - 1, static_cast<uint64_t>(p.hi) - 1);
    hold(calculus, m.held, w, r, mu, kT, params);
  }
  move_batch(ms, count, kT, update->dt, params, calculus, noise_on, ys);
  double **omega = atom->omega;
  for (int q = 0; q < count; q++) {
    const Cx xm = ms[q].x, y = ys[q];
    if (same(y, xm)) continue;
    const Contact &c = cs[q];
    const double *n = c.n, *e1 = c.e1, *e2 = c.e2, mu = ms[q].mu;
"""
        + impulse
        + r"""    if (c.k >= atom->nlocal) touched[c.k] = 1;
  }
}
"""
    )


SLIDING_PAIR = (
    batch_step(
        r"""// The engine's pairwise step (contact_step.update_pair) of count <= BATCH pairs of one colour (no shared atom)
// on their canonical copies i and c: each pair's mode, their moves together (move_batch), each pair's impulse.
""",
        "arms[2], inv_m[2], inv_i[2]",
        r"""  double **v = atom->v;
  const bool three = domain->dimension == 3;
  const int comps = three ? 2 : 1;
""",
        r"""    const double inv_mi = 1.0 / rmass[i], inv_mk = 1.0 / rmass[k];
    const double mu = inv_mi + inv_mk + ri * ri * inv_ii + rk * rk * inv_ik;
    // u_perp = P (v_k - v_i) - (R_i w_i + R_k w_k) x n (F-4) as x = u_perp . (e1 + i e2): contact_step.contact_mode
    const double wx = ri * omega[i][0] + rk * omega[k][0], wy = ri * omega[i][1] + rk * omega[k][1];
    const double wz = ri * omega[i][2] + rk * omega[k][2];
    const double cx = wy * n[2] - wz * n[1], cy = wz * n[0] - wx * n[2], cz = wx * n[1] - wy * n[0];
    const double ux = v[k][0] - v[i][0] - cx, uy = v[k][1] - v[i][1] - cy, uz = v[k][2] - v[i][2] - cz;
    Contact &c = cs[q];
    c = {i, k, {n[0], n[1], n[2]}, {}, {}, {ri, rk}, {inv_mi, inv_mk}, {inv_ii, inv_ik}};
    tangents(n, three, c.e1, c.e2);
    const double *e1 = c.e1, *e2 = c.e2;
    const Cx xm = {ux * e1[0] + uy * e1[1] + uz * e1[2], ux * e2[0] + uy * e2[1] + uz * e2[2]};
""",
        r"""    const double jp = (xm.re - y.re) / mu, jq = (xm.im - y.im) / mu;    // impulse on i: u_perp -> u_perp - mu J
    const double jx = jp * e1[0] + jq * e2[0], jy = jp * e1[1] + jq * e2[1], jz = jp * e1[2] + jq * e2[2];
    const double tx = n[1] * jz - n[2] * jy, ty = n[2] * jx - n[0] * jz, tz = n[0] * jy - n[1] * jx;
    const int particles[2] = {c.i, c.k};
    const double signs[2] = {1.0, -1.0};
    for (int s = 0; s < 2; s++) {
      const int a = particles[s];
      const double scale = signs[s] * c.inv_m[s], turn = c.arms[s] * c.inv_i[s];
      v[a][0] += scale * jx;
      v[a][1] += scale * jy;
      v[a][2] += scale * jz;
      omega[a][0] += turn * tx;
      omega[a][1] += turn * ty;
      omega[a][2] += turn * tz;
    }
""",
    )
    + "\n"
)

#: The step of a batch of pairs by the law's mode: sliding (contact_step.update_pair), rolling and spinning
#: (contact_step.update_rolling, with rolling_mode's mode vector).
PAIR_STEP = {"sliding": SLIDING_PAIR}


def mode_pair(mode: str, mode_vector: str, mode_vector_code: str, impulse_code: str) -> str:
    """step_batch of the rolling or spinning mode: its mode vector (described by ``mode_vector``, computed by
    ``mode_vector_code``) and the couple's direction (``impulse_code``, after J in the lab frame)."""
    return batch_step(
        f"""// The engine's step of the {mode} mode (contact_step.update_rolling) of count <= BATCH pairs of one colour (no
// shared atom) on their canonical copies i and c: x = {mode_vector}, mu_m = R_eff^2 (1/I_i + 1/I_k),
// J = (y - x) / mu_m; only the spins change.
""",
        "turns[2]",
        "",
        r"""    const double reff = ri * rk / sigma;
    const double mu = reff * reff * (inv_ii + inv_ik);
    const double ox = omega[i][0] - omega[k][0], oy = omega[i][1] - omega[k][1], oz = omega[i][2] - omega[k][2];
"""
        + indent(mode_vector_code, "  ")
        + r"""    cs[q] = {i, k, {n[0], n[1], n[2]}, {e1[0], e1[1], e1[2]}, {e2[0], e2[1], e2[2]}, {reff * inv_ii, -reff * inv_ik}};
""",
        r"""    const double jp = (y.re - xm.re) / mu, jq = (y.im - xm.im) / mu;
    double jx = jp * e1[0] + jq * e2[0], jy = jp * e1[1] + jq * e2[1], jz = jp * e1[2] + jq * e2[2];
"""
        + indent(impulse_code, "  ")
        + r"""    const int particles[2] = {c.i, c.k};
    for (int s = 0; s < 2; s++) {
      const int a = particles[s];
      omega[a][0] += c.turns[s] * jx;
      omega[a][1] += c.turns[s] * jy;
      omega[a][2] += c.turns[s] * jz;
    }
""",
    )


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
PAIR_STEP["rolling"] = mode_pair("rolling", "v_roll . (e1 + i e2) (3-D) or R_eff (w_iz - w_kz) (2-D)", ROLLING_VECTOR, ROLLING_IMPULSE)
PAIR_STEP["spinning"] = mode_pair("spinning", "v_spin = R_eff (w_i - w_k) . n", SPINNING_VECTOR, "")

#: The noise stream of each mode's key (fricgen.rng: CONTACT for sliding, ROLLING, SPINNING; support and mode_code
#: define the constants).
STREAM = {"sliding": "CONTACT_STREAM", "rolling": "MODE_STREAM", "spinning": "MODE_STREAM"}

#: The refusal of 2-D by a spinning law's fix (the spins are along z, normal to every contact normal).
SPINNING_2D = (
    "  if (domain->dimension == 2)\n"
    '    error->all(FLERR, "fix fricgen/exact/${law} acts on spinning, which does not exist in 2-D: '
    'the spins are along z, normal to every contact normal");\n'
)
