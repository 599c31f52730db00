"""The hand-written numerics of a plugin in C++ (integer powers, the special functions with the tables of
fricgen.generated.special, normals), shared by every law's pair style and fix."""

from string import Template

from ..special_functions import special_namespace

SUPPORT = Template("""// x^n for n >= 1 by repeated squaring (integer powers of the printed formulas).
inline double fricgen_powi(double x, int n)
{
  double result = 1.0;
  while (true) {
    if (n & 1) result *= x;
    n >>= 1;
    if (!n) return result;
    x *= x;
  }
}

// Scaled complementary error function exp(x^2) erfc(x) (derive/backends/special_functions/special.py, step for step):
// on 0 <= x < 4 the degree-12 piece of width 1/4 that holds x (derive/backends/special_functions/pieces.py) by Estrin's
// scheme, Laplace's continued fraction beyond as its 20-term convergent, erfcx(-x) = 2 exp(x^2) - erfcx(x).
const double ERFCX_PIECES[${pieces}][${terms}] = {
${table}
};
const double ERFCX_NUMERATOR[] = {${numerator}};
const double ERFCX_DENOMINATOR[] = {${denominator}};

inline double fricgen_erfcx_right(double x)
{
  if (x < 4.0) {
    const int j = static_cast<int>(4.0 * x);
    const double *c = ERFCX_PIECES[j];
    const double t = x - 0.25 * j - 0.125, t2 = t * t, t4 = t2 * t2;
    const double low = (c[0] + c[1] * t) + (c[2] + c[3] * t) * t2 + ((c[4] + c[5] * t) + (c[6] + c[7] * t) * t2) * t4;
    return low + ((c[8] + c[9] * t) + (c[10] + c[11] * t) * t2 + c[12] * t4) * (t4 * t4);
  }
  if (x > 1e8) return 1.0 / (1.7724538509055160273 * x);
  const int top = ${top};
  const double y = x * x;
  double numerator = ERFCX_NUMERATOR[top], denominator = ERFCX_DENOMINATOR[top];
  for (int j = top - 1; j >= 0; --j) {
    numerator = numerator * y + ERFCX_NUMERATOR[j];
    denominator = denominator * y + ERFCX_DENOMINATOR[j];
  }
  return numerator / (1.7724538509055160273 * x * denominator);
}

inline double fricgen_erfcx(double x)
{
  if (x < 0.0) return 2.0 * std::exp(x * x) - fricgen_erfcx_right(-x);
  return fricgen_erfcx_right(x);
}

// Counter-based normals of fricgen/rng.py: chained SplitMix64 finalisers (Steele, Lea, Flood 2014)
// and the Box-Muller transform of two 53-bit uniforms, bit for bit.
const uint64_t GOLDEN = 0x9E3779B97F4A7C15ULL;
const int CONTACT_STREAM = 2;  // fricgen.rng.CONTACT

inline uint64_t mix(uint64_t z)
{
  z += GOLDEN;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

inline uint64_t stream_key(uint64_t seed, uint64_t step, uint64_t stream)
{
  return mix(mix(mix(seed) ^ step) ^ stream);
}

// The key of pair (i, k) in a stream key: fricgen.rng.pair_key.
inline uint64_t pair_key(uint64_t base, uint64_t i, uint64_t k)
{
  return mix(mix(base ^ i) ^ k);
}

const double TWO_53 = 1.0 / 9007199254740992.0;

// Two independent standard normals for (stream key, i, k) and a small counter: fricgen.rng.normal_pair_at.
inline void normal_pair_at(uint64_t base, uint64_t i, uint64_t k, uint64_t counter, double &z0, double &z1)
{
  const uint64_t a = mix(pair_key(base, i, k) ^ counter);
  const uint64_t b = mix(a);
  const double u1 = (static_cast<double>(a >> 11) + 0.5) * TWO_53;
  const double u2 = static_cast<double>(b >> 11) * TWO_53;
  const double radius = std::sqrt(-2.0 * std::log(u1));
  z0 = radius * std::cos(2.0 * 3.141592653589793 * u2);
  z1 = radius * std::sin(2.0 * 3.141592653589793 * u2);
}
""")


def support() -> str:
    """The hand-written numerics in C++, with the tables of fricgen.generated.special."""
    special = special_namespace()
    pieces = special["_PIECES"]
    return SUPPORT.substitute(
        pieces=str(pieces.shape[0]),
        terms=str(pieces.shape[1]),
        table=",\n".join("  {" + ", ".join(repr(float(c)) for c in row) + "}" for row in pieces),
        numerator=", ".join(repr(c) for c in special["_NUMERATOR"]),
        denominator=", ".join(repr(c) for c in special["_DENOMINATOR"]),
        top=str(len(special["_NUMERATOR"]) - 1),
    )
