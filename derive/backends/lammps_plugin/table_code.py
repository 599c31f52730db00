"""The noise tables of an integral-form D in C++ (fricgen.derive.backends.tables), for the pair style.

The table functions of fricgen.generated.special (table_points, table_zone, table_block, table_value),
step for step, with the same constants (printed from special.py's namespace: Chebyshev points, the
transform to Chebyshev coefficients, the powers of T_k), and a per-law ``noise_table(a, params)`` that
tabulates D_g = D / factor(w, r, params) from ``gaussian_tail`` as the Numba kernels' _noise_table does.
A pair style cannot build its tables before the run knows its particles, so ``noise_table_for(a,
params)`` builds them lazily: the first call with an (a, parameters) it has no table for builds one
(a few ms) and keeps it, up to TABLE_CACHE tables per process; beyond, the quadrature. A table is a
function of a and the parameters alone, so the order of first calls (or the rank) changes nothing.
"""

from __future__ import annotations

from string import Template

from .. import tables
from ..special_functions import special_namespace

#: Most tables one plugin process keeps (one per contact mobility and pair of types met).
TABLE_CACHE = 16

_SUPPORT = Template("""// --- noise tables (fricgen.derive.backends.tables; fricgen.generated.special's table functions, step for step) ---
// Piecewise polynomials of D_g(u) = D(u) / factor(w, r) in x = u/sqrt(a): zone 0 is [0, 2^-TABLE_LOW), zone k
// the octave [2^(k-1-TABLE_LOW), 2^(k-TABLE_LOW)); a table is: its length, a, 1/sqrt(a), the NPARAMS
// parameters it was built for, per zone (offset of its first row or -1, pieces), rows (centre, 1/half-width,
// ${terms} coefficients of powers of t = (x - centre)/half-width).
const int TABLE_TERMS = ${terms}, TABLE_ROW = ${terms} + 2, TABLE_LOW = ${low}, TABLE_HIGH = ${high};
const int TABLE_ZONES = 1 + TABLE_LOW + TABLE_HIGH, TABLE_NCHECKS = ${nchecks}, TABLE_POINTS = TABLE_TERMS + TABLE_NCHECKS;
const double TABLE_CHECKS[TABLE_NCHECKS] = {${checks}};
const double TABLE_NODES[TABLE_TERMS] = {${nodes}};
const double TABLE_TRANSFORM[TABLE_TERMS][TABLE_TERMS] = {
${transform}
};
const double TABLE_POWERS[TABLE_TERMS][TABLE_TERMS] = {
${powers}
};

inline double table_estrin(const double *c, double t)
{
  const double t2 = t * t, t4 = t2 * t2;
  const double low = (c[0] + c[1] * t) + (c[2] + c[3] * t) * t2;
  const double middle = (c[4] + c[5] * t) + (c[6] + c[7] * t) * t2;
  const double high = (c[8] + c[9] * t) + (c[10] + c[11] * t) * t2;
  return low + (middle + high * t4) * t4;
}

inline void table_zone_bounds(int k, double &lower, double &width)
{
  if (k == 0) {
    lower = 0.0;
    width = std::ldexp(1.0, -TABLE_LOW);
  } else {
    lower = width = std::ldexp(1.0, k - 1 - TABLE_LOW);
  }
}

// Where zone k cut into pieces needs D_g: per piece its nodes, then its checks (special.table_points).
inline std::vector<double> table_points(int k, int pieces)
{
  double lower, width;
  table_zone_bounds(k, lower, width);
  const double half = 0.5 * width / pieces;
  std::vector<double> xs(static_cast<size_t>(pieces) * TABLE_POINTS);
  for (int j = 0; j < pieces; ++j) {
    const double centre = lower + (2 * j + 1) * half;
    for (int i = 0; i < TABLE_TERMS; ++i) xs[j * TABLE_POINTS + i] = centre + half * TABLE_NODES[i];
    for (int i = 0; i < TABLE_NCHECKS; ++i) xs[j * TABLE_POINTS + TABLE_TERMS + i] = centre + half * TABLE_CHECKS[i];
  }
  return xs;
}

// The rows of zone k cut into pieces, or none unless every piece passes the checks (special.table_zone).
inline std::vector<double> table_zone(int k, int pieces, const std::vector<double> &values, double tolerance)
{
  double lower, width;
  table_zone_bounds(k, lower, width);
  const double half = 0.5 * width / pieces;
  std::vector<double> rows(static_cast<size_t>(pieces) * TABLE_ROW);
  double chebyshev[TABLE_TERMS];
  for (int j = 0; j < pieces; ++j) {
    const int base = j * TABLE_POINTS;
    for (int m = 0; m < TABLE_TERMS; ++m) {
      double total = 0.0;
      for (int i = 0; i < TABLE_TERMS; ++i) total += TABLE_TRANSFORM[m][i] * values[base + i];
      chebyshev[m] = total;
    }
    if (!(std::fabs(chebyshev[TABLE_TERMS - 2]) + std::fabs(chebyshev[TABLE_TERMS - 1]) <= tolerance * std::fabs(chebyshev[0])))
      return std::vector<double>();
    double *row = &rows[static_cast<size_t>(j) * TABLE_ROW];
    row[0] = lower + (2 * j + 1) * half;
    row[1] = 1.0 / half;
    for (int p = 0; p < TABLE_TERMS; ++p) {
      double total = 0.0;
      for (int m = 0; m < TABLE_TERMS; ++m) total += TABLE_POWERS[p][m] * chebyshev[m];
      row[2 + p] = total;
    }
    for (int i = 0; i < TABLE_NCHECKS; ++i) {
      const double exact = values[base + TABLE_TERMS + i];
      if (!(std::fabs(table_estrin(row + 2, TABLE_CHECKS[i]) - exact) <= tolerance * std::fabs(exact))) return std::vector<double>();
    }
  }
  return rows;
}

// D_g(u) from the table at t; -1 beyond its zones or in a zone it leaves to the quadrature (special._table_lookup).
inline double table_lookup(double u, const double *t)
{
  const double x = u * t[2];
  if (!(x >= 0.0 && x < std::ldexp(1.0, TABLE_HIGH))) return -1.0;
  int k;
  double s;
  if (x < std::ldexp(1.0, -TABLE_LOW)) {
    k = 0;
    s = x * std::ldexp(1.0, TABLE_LOW);
  } else {
    int e;
    const double m = std::frexp(x, &e);
    k = e + TABLE_LOW;
    s = 2.0 * m - 1.0;
  }
  const double *zone = t + 3 + NPARAMS + 2 * k;
  if (zone[0] < 0.0) return -1.0;
  const int pieces = static_cast<int>(zone[1]);
  const int at = static_cast<int>(s * pieces), j = at < pieces ? at : pieces - 1;
  const double *row = t + static_cast<int>(zone[0]) + TABLE_ROW * j;
  return table_estrin(row + 2, (x - row[0]) * row[1]);
}
""")

_LAW = Template("""// The noise table of D_g(u) = D(u) / factor(w, r, params) for a = kT nu: zone by zone, the fewest equal pieces
// (1, 2, 4, ... ${pieces}) whose polynomials pass the checks against gaussian_tail at relative ${tolerance}
// (the Numba kernels' _noise_table, step for step).
inline std::vector<double> noise_table(double a, const double *params)
{
  const double scale = factor(1.0, 1.0, params);
  const double root = std::sqrt(a);
  std::vector<std::vector<double>> zones(TABLE_ZONES);
  size_t count = 0;
  for (int k = 0; k < TABLE_ZONES; ++k) {
    for (int pieces = 1; scale > 0.0 && scale < INFINITY && pieces <= ${pieces}; pieces *= 2) {
      const std::vector<double> xs = table_points(k, pieces);
      std::vector<double> values(xs.size());
      for (size_t i = 0; i < xs.size(); ++i) values[i] = gaussian_tail(root * xs[i], a, 1.0, 1.0, params) / scale;
      zones[k] = table_zone(k, pieces, values, ${tolerance});
      if (!zones[k].empty()) break;
    }
    count += zones[k].size();
  }
  const size_t head = 3 + NPARAMS + 2 * TABLE_ZONES;
  std::vector<double> block(head + count);
  block[0] = static_cast<double>(block.size());
  block[1] = a;
  block[2] = 1.0 / root;
  for (int i = 0; i < NPARAMS; ++i) block[3 + i] = params[i];
  size_t offset = head;
  for (int k = 0; k < TABLE_ZONES; ++k) {
    block[3 + NPARAMS + 2 * k] = zones[k].empty() ? -1.0 : static_cast<double>(offset);
    block[4 + NPARAMS + 2 * k] = static_cast<double>(zones[k].size() / TABLE_ROW);
    for (double c : zones[k]) block[offset++] = c;
  }
  return block;
}

// The table for a and params, built on first use and kept (at most ${cache} per process; then nullptr: the quadrature).
inline const double *noise_table_for(double a, const double *params)
{
  static std::vector<std::vector<double>> tables;
  for (const std::vector<double> &table : tables) {
    bool same = table[1] == a;
    for (int i = 0; same && i < NPARAMS; ++i) same = table[3 + i] == params[i];
    if (same) return table.data();
  }
  if (tables.size() >= ${cache}) return nullptr;
  tables.push_back(noise_table(a, params));
  return tables.back().data();
}
""")

_AMPLITUDE = """{{
  const double a = {scale};
  const double *table = noise_table_for(a, params);
  if (table) {{
    const double tabled = table_lookup(u, table);
    if (tabled >= 0.0) return factor(w, r, params) * tabled;
  }}
  return gaussian_tail(u, a, w, r, params);
}}
"""


def _numbers(values) -> str:
    return ", ".join(repr(float(x)) for x in values)


def table_support() -> str:
    """The generic table functions in C++, with special.py's constants."""
    special = special_namespace()
    return _SUPPORT.substitute(
        terms=str(special["TABLE_TERMS"]),
        low=str(special["TABLE_LOW"]),
        high=str(special["TABLE_HIGH"]),
        nchecks=str(special["TABLE_CHECKS"].size),
        checks=_numbers(special["TABLE_CHECKS"]),
        nodes=_numbers(special["TABLE_NODES"]),
        transform=",\n".join("  {" + _numbers(row) + "}" for row in special["TABLE_TRANSFORM"]),
        powers=",\n".join("  {" + _numbers(row) + "}" for row in special["TABLE_POWERS"]),
    )


def table_builder() -> str:
    """The table functions, then noise_table and noise_table_for of a law (after its factor and gaussian_tail),
    with the pieces and the tolerance of fricgen.derive.backends.tables."""
    law = _LAW.substitute(pieces=str(tables.TABLE_PIECES), tolerance=repr(tables.TABLE_TOLERANCE), cache=str(TABLE_CACHE))
    return table_support() + "\n" + law


def tabled_amplitude(scale: str) -> str:
    """The body of noise_amplitude_<c>: the table for a = ``scale`` where it applies, the quadrature elsewhere."""
    return _AMPLITUDE.format(scale=scale)


__all__ = ["TABLE_CACHE", "table_builder", "table_support", "tabled_amplitude"]
