"""Special functions for generated kernels (Numba has no scipy.special inside nopython code)."""

import math

import numba
import numpy

_SQRT_PI = 1.7724538509055160273
#: erfcx on [0, 4) in 16 pieces of width 1/4: piece j is the degree-12 interpolant at the Chebyshev
#: points of [j/4, (j + 1)/4], in powers of t = x - (j + 1/2)/4, lowest first (derive/erfcx_pieces.py
#: computes them with mpmath; tests/codegen/test_special.py checks that they agree).
_PIECES = numpy.array((
    (0.8732218450821508, -0.9100737058249748, 0.759462631854029, -0.5434272512288376, 0.3457671127252221,
     -0.20008254484327542, 0.1069189315350891, -0.053347910747932686, 0.025062611709523383, -0.011158626701468466,
     0.004733447842483794, -0.0019356473822429144, 0.0007540948494775165),
    (0.6858572331012929, -0.6139862422695429, 0.45561239225021427, -0.2954210634504818, 0.1724147467281454,
     -0.09230621336750003, 0.045933305570143745, -0.021451778984211422, 0.00947222244753548, -0.003977628865180708,
     0.00159608813514055, -0.0006185420156587484, 0.00022905448458625585),
    (0.5568138808733625, -0.43236181600380946, 0.2865877458709816, -0.1688296498896327, 0.09053460734498192,
     -0.04489820811854473, 0.020824409089725073, -0.009109415215390305, 0.003782756258424993, -0.0014989067951486311,
     0.0005691765826741029, -0.00020912350071074624, 7.363214257331038e-05),
    (0.464311583202669, -0.3158338964908418, 0.1879569237731824, -0.10091439212620548, 0.04982841533137681,
     -0.022925811484156768, 0.009922776760704834, -0.0040695377378321225, 0.0015904828502581662, -0.0005950731226669547,
     0.00021395483349863278, -7.456866102720806e-05, 2.497428235728618e-05),
    (0.3956980795529959, -0.2380584881012718, 0.12788228043906513, -0.06279394840488257, 0.028619544241786313,
     -0.012238784453032324, 0.00495030391062935, -0.0019056264695248481, 0.0007016185480284176, -0.00024806517590081605,
     8.450760676854731e-05, -2.795719976635647e-05, 8.911018197121129e-06),
    (0.3432958898621254, -0.18431546997466777, 0.08986211864695719, -0.04050337122340118, 0.017084991607390358,
     -0.006804603105254051, 0.0025762207791909016, -0.0009320855902612192, 0.0003236507789235028,
     -0.00010823586083519329, 3.496474482374798e-05, -1.098807548497499e-05, 3.335187449560455e-06),
    (0.30226120936348594, -0.14603023666418335, 0.06496207478418799, -0.02697791009325194, 0.010561485441326825,
     -0.003926198500422747, 0.0013938042927005585, -0.0004746475819316404, 0.00015562549534526093,
     -4.9278779864759255e-05, 1.5109276732553369e-05, -4.514364028833331e-06, 1.3057676665450787e-06),
    (0.2694299851646704, -0.11801672272799837, 0.04814863004967349, -0.01849202758990707, 0.006738039159298881,
     -0.0023432816664825835, 0.0007814620115426119, -0.0002508686855750777, 7.777080749883476e-05,
     -2.3343951257309468e-05, 6.8000889612901964e-06, -1.9334345754266977e-06, 5.333442670538872e-07),
    (0.24267036461265454, -0.09703011749173075, 0.0364813649427267, -0.013004811325624345, 0.00442307043788749,
     -0.0014423146580429004, 0.0004527172631797362, -0.00013722585019556091, 4.027808330310593e-05,
     -1.1474369509694925e-05, 3.1789704768334423e-06, -8.60973143103244e-07, 2.2669477497353674e-07),
    (0.22050569220490668, -0.08097712912220592, 0.028185010539667613, -0.009358486060330228, 0.0029793030731916637,
     -0.0009130565045989669, 0.00027026462492196177, -7.74794346316363e-05, 2.1562742109066935e-05,
     -5.837291601586933e-06, 1.5398174251029425e-06, -3.9765523934743816e-07, 1.0002736415628084e-07),
    (0.201887554546017, -0.06846950572892327, 0.022155102007593415, -0.00687490863932704, 0.0020542334146799695,
     -0.0005930183703163913, 0.00016585339753264242, -4.504377204111378e-05, 1.1903374070072646e-05,
     -3.066081557659455e-06, 7.709739165843627e-07, -1.9005181976253436e-07, 4.5713797574382465e-08),
    (0.1860549346844711, -0.05856329265980373, 0.01768546828753539, -0.005145047555426323, 0.0014467282828423563,
     -0.0003942814969016125, 0.00010438965974982962, -2.690320722274112e-05, 6.760734788759569e-06,
     -1.6591273185977365e-06, 3.981448957189344e-07, -9.3786036968736e-08, 2.159192706377783e-08),
    (0.1724443521021736, -0.05060196645692752, 0.014313206924275092, -0.003915463212378573, 0.0010386921927960265,
     -0.00026782004395629953, 6.725151847740898e-05, -1.6474013939592873e-05, 3.942556250111947e-06,
     -9.230034409904174e-07, 2.1163220542314262e-07, -4.768899282448834e-08, 1.051893570881236e-08),
    (0.1606310681265444, -0.044119457241337846, 0.011727899937029176, -0.0030251966359095845, 0.0007589306454171639,
     -0.000185522283050616, 4.426431337371653e-05, -1.0322921557154124e-05, 2.356113290277071e-06,
     -5.268965119915123e-07, 1.1556655511384625e-07, -2.493926126417226e-08, 5.275506170316265e-09),
    (0.15028972247426936, -0.03877867915705971, 0.009717010529927907, -0.002369677324047367, 0.0005634651151281015,
     -0.0001308465126831764, 2.9715502217163306e-05, -6.607947761042391e-06, 1.4404229014202357e-06,
     -3.080916260858646e-07, 6.471765449034604e-08, -1.3389445030460211e-08, 2.71892536935332e-09),
    (0.1411674197630518, -0.034331663931861184, 0.0081322220270897, -0.001879535717925734, 0.00042451056006373997,
     -9.38229190714849e-05, 2.0315582887227988e-05, -4.314295826420686e-06, 8.99421642938506e-07,
     -1.8423016139041112e-07, 3.710568911889599e-08, -7.367786439380672e-09, 1.4376435628898673e-09),
))  # fmt: skip
#: Laplace's continued fraction t = x + (1/2)/(x + (2/2)/(x + ... (20/2)/x)) as A(x)/B(x), from the
#: recurrences P_k = x P_(k-1) + (k/2) P_(k-2): B is even and A odd, with positive coefficients, here
#: as polynomials in y = x^2, lowest power first: B(x) and A(x)/x. The values are exact dyadic
#: rationals (tests/codegen/test_special.py recomputes them with fractions).
_NUMERATOR = (3628800.0, 52979477.783203125, 122404170.41015625, 104750739.84375, 43369889.0625, 9816994.6875,
              1287706.875, 99577.5, 4437.0, 104.5, 1.0)  # fmt: skip
_DENOMINATOR = (13427061.108398438, 89513740.72265625, 161124733.30078125, 122761701.5625, 47740661.71875,
                10416144.375, 1335403.125, 101745.0, 4488.75, 105.0, 1.0)  # fmt: skip


@numba.njit(cache=True)
def erfcx(x):
    """Scaled complementary error function exp(x^2) erfc(x), relative error < 2e-15.

    On 0 <= x < 4 the piece of _PIECES that holds x, evaluated by Estrin's scheme (no exp or erfc);
    beyond, Laplace's continued fraction erfcx = 1/(sqrt(pi) t) with 20 terms, evaluated as its
    convergent B(x)/(sqrt(pi) A(x)): two Horner sums in x^2 with positive terms (no cancellation) and
    one division; erfcx(-x) = 2 exp(x^2) - erfcx(x). Above x = 1e8, erfcx = 1/(x sqrt(pi)) to
    1/(2 x^2) < 1e-16 (no overflow for large x).
    """
    if x < 0.0:
        return 2.0 * math.exp(x * x) - _erfcx_right(-x)
    return _erfcx_right(x)


@numba.njit(cache=True)
def _erfcx_right(x):
    """erfcx for x >= 0 (and NaN)."""
    if x < 4.0:
        j = int(4.0 * x)
        c, t = _PIECES[j], x - 0.25 * j - 0.125
        t2 = t * t
        t4 = t2 * t2  # Estrin's scheme: short dependency chains, within 2 ulp
        low = (c[0] + c[1] * t) + (c[2] + c[3] * t) * t2 + ((c[4] + c[5] * t) + (c[6] + c[7] * t) * t2) * t4
        return low + ((c[8] + c[9] * t) + (c[10] + c[11] * t) * t2 + c[12] * t4) * (t4 * t4)
    if x > 1e8:
        return 1.0 / (_SQRT_PI * x)
    y, top = x * x, len(_NUMERATOR) - 1
    numerator, denominator = _NUMERATOR[top], _DENOMINATOR[top]
    for j in range(top - 1, -1, -1):
        numerator = numerator * y + _NUMERATOR[j]
        denominator = denominator * y + _DENOMINATOR[j]
    return numerator / (_SQRT_PI * x * denominator)


@numba.njit(inline="always", cache=True)
def expm1_given_exp(e, x):
    """e^x - 1 given e = exp(x): e - 1 below x = -ln 2, where e < 1/2 and the difference loses
    nothing (within 1 ulp), else expm1(x); a kernel that needs both exp(x) and expm1(x) pays one
    transcendental call for arguments below -ln 2."""
    return e - 1.0 if x < -0.6931471805599453 else math.expm1(x)


# --- noise tables ----------------------------------------------------------------------------------
# A law f = h(w, r) g(u) without a closed-form D tabulates D_g(u) = D(u) / h, the (F-22) integral of g,
# for the a = kT nu of a simulation (a law module's tabulate_<c>, which evaluates its quadrature at the
# points of table_points and hands the values to table_zone). Piecewise polynomials in x = u/sqrt(a): zone
# 0 is [0, 2^-TABLE_LOW), zone k >= 1 the octave [2^(k-1-TABLE_LOW), 2^(k-TABLE_LOW)), up to x = 2^TABLE_HIGH;
# each zone is cut into a power of two of equal pieces, as few as pass the checks; on a piece, the
# interpolant at the TABLE_TERMS Chebyshev points in powers of t = (x - centre)/half-width (Estrin's
# scheme, like erfcx). The tables follow the law's n parameters in params:
#   params[n] = number of tables, then per table: its length, a, 1/sqrt(a), the n parameters it was built
#   for, per zone (offset of its first row in the table or -1, pieces), rows (centre, 1/half, coefficients).
# table_value returns -1.0 where no table applies (another a or other parameters, x beyond the zones, a
# zone left untabulated): the kernel then integrates by quadrature.

TABLE_TERMS = 12
TABLE_ROW = TABLE_TERMS + 2
TABLE_LOW, TABLE_HIGH = 10, 20
TABLE_ZONES = 1 + TABLE_LOW + TABLE_HIGH
_TABLE_BOTTOM, _TABLE_TOP = 2.0**-TABLE_LOW, 2.0**TABLE_HIGH
#: Where each piece is checked against the quadrature, in t: both ends (the pieces join) and between the nodes.
TABLE_CHECKS = numpy.array((-1.0, -0.5, 0.0, 0.5, 1.0))
TABLE_POINTS = TABLE_TERMS + 5


def _chebyshev_matrices():
    """Chebyshev points cos(theta_i), theta_i = pi (i + 1/2)/TABLE_TERMS; the matrix from values there to
    Chebyshev coefficients (a discrete cosine transform); and from those to powers of t (T_k's coefficients)."""
    n = TABLE_TERMS
    theta = [math.pi * (i + 0.5) / n for i in range(n)]
    nodes = numpy.array([math.cos(x) for x in theta])
    transform = numpy.array([[(1.0 if m == 0 else 2.0) / n * math.cos(m * x) for x in theta] for m in range(n)])
    powers = numpy.zeros((n, n))  # row k: T_k in powers of t
    powers[0, 0], powers[1, 1] = 1.0, 1.0
    for k in range(2, n):
        powers[k, 1:] = 2.0 * powers[k - 1, :-1]
        powers[k] -= powers[k - 2]
    return nodes, transform, numpy.ascontiguousarray(powers.T)


TABLE_NODES, TABLE_TRANSFORM, TABLE_POWERS = _chebyshev_matrices()


@numba.njit(inline="always", cache=True)
def _estrin(c, o, t):
    """sum_p c[o + p] t^p for p < TABLE_TERMS by Estrin's scheme."""
    t2 = t * t
    t4 = t2 * t2
    low = (c[o] + c[o + 1] * t) + (c[o + 2] + c[o + 3] * t) * t2
    middle = (c[o + 4] + c[o + 5] * t) + (c[o + 6] + c[o + 7] * t) * t2
    high = (c[o + 8] + c[o + 9] * t) + (c[o + 10] + c[o + 11] * t) * t2
    return low + (middle + high * t4) * t4


@numba.njit(cache=True)
def _zone(k):
    """(lower end, width) of zone k in x."""
    if k == 0:
        return 0.0, _TABLE_BOTTOM
    lower = 2.0 ** (k - 1 - TABLE_LOW)
    return lower, lower


@numba.njit(cache=True)
def table_points(k, pieces):
    """Where zone k cut into ``pieces`` needs D_g: per piece its TABLE_TERMS nodes, then its TABLE_CHECKS."""
    lower, width = _zone(k)
    half = 0.5 * width / pieces
    xs = numpy.empty(pieces * TABLE_POINTS)
    for j in range(pieces):
        centre = lower + (2 * j + 1) * half
        for i in range(TABLE_TERMS):
            xs[j * TABLE_POINTS + i] = centre + half * TABLE_NODES[i]
        for i in range(TABLE_CHECKS.size):
            xs[j * TABLE_POINTS + TABLE_TERMS + i] = centre + half * TABLE_CHECKS[i]
    return xs


@numba.njit(cache=True)
def table_zone(k, pieces, values, tolerance):
    """The rows of zone k cut into ``pieces``, from D_g at table_points(k, pieces); no rows (shape (0, TABLE_ROW))
    unless every piece passes: its two highest Chebyshev coefficients below ``tolerance`` times the lowest,
    and its polynomial within ``tolerance`` (relative) of D_g at the checks. NaN or inf values fail."""
    lower, width = _zone(k)
    half = 0.5 * width / pieces
    rows = numpy.empty((pieces, TABLE_ROW))
    chebyshev = numpy.empty(TABLE_TERMS)
    for j in range(pieces):
        base = j * TABLE_POINTS
        for m in range(TABLE_TERMS):
            total = 0.0
            for i in range(TABLE_TERMS):
                total += TABLE_TRANSFORM[m, i] * values[base + i]
            chebyshev[m] = total
        if not abs(chebyshev[TABLE_TERMS - 2]) + abs(chebyshev[TABLE_TERMS - 1]) <= tolerance * abs(chebyshev[0]):
            return numpy.empty((0, TABLE_ROW))
        rows[j, 0], rows[j, 1] = lower + (2 * j + 1) * half, 1.0 / half
        for p in range(TABLE_TERMS):
            total = 0.0
            for m in range(TABLE_TERMS):
                total += TABLE_POWERS[p, m] * chebyshev[m]
            rows[j, 2 + p] = total
        for i in range(TABLE_CHECKS.size):
            exact = values[base + TABLE_TERMS + i]
            if not abs(_estrin(rows[j], 2, TABLE_CHECKS[i]) - exact) <= tolerance * abs(exact):
                return numpy.empty((0, TABLE_ROW))
    return rows


@numba.njit(cache=True)
def table_block(a, params, zones):
    """One table (the layout above) for a and the parameters ``params`` from the rows of each zone."""
    n = params.size
    count = 0
    for rows in zones:
        count += rows.shape[0]
    head = 3 + n + 2 * TABLE_ZONES
    block = numpy.empty(head + TABLE_ROW * count)
    block[0], block[1], block[2] = block.size, a, 1.0 / math.sqrt(a)
    block[3 : 3 + n] = params
    offset = head
    for k in range(TABLE_ZONES):
        rows = zones[k]
        block[3 + n + 2 * k] = offset if rows.shape[0] > 0 else -1.0
        block[4 + n + 2 * k] = rows.shape[0]
        for j in range(rows.shape[0]):
            block[offset : offset + TABLE_ROW] = rows[j]
            offset += TABLE_ROW
    return block


@numba.njit(cache=True)
def table_join(params, blocks):
    """params followed by the number of tables and the tables."""
    size = params.size + 1
    for block in blocks:
        size += block.size
    joined = numpy.empty(size)
    joined[: params.size] = params
    joined[params.size] = len(blocks)
    offset = params.size + 1
    for block in blocks:
        joined[offset : offset + block.size] = block
        offset += block.size
    return joined


@numba.njit(inline="always", cache=True)
def table_value(u, a, params, n):
    """D_g(u) from the table for a and params[:n] among those after params[:n]; -1.0 where none applies."""
    if params.size <= n:
        return -1.0
    o = n + 1
    for _ in range(int(params[n])):
        if params[o + 1] == a:
            same = True
            for i in range(n):
                same = same and params[o + 3 + i] == params[i]
            if same:
                return _table_lookup(u, params, o, n)
        o += int(params[o])
    return -1.0


@numba.njit(inline="always", cache=True)
def _table_lookup(u, params, o, n):
    """D_g(u) from the table at params[o:]; -1.0 beyond its zones or in a zone it leaves to the quadrature."""
    x = u * params[o + 2]
    if not (x >= 0.0 and x < _TABLE_TOP):  # NaN too
        return -1.0
    if x < _TABLE_BOTTOM:
        k, s = 0, x * 2.0**TABLE_LOW
    else:
        m, e = math.frexp(x)
        k, s = e + TABLE_LOW, 2.0 * m - 1.0
    zone = o + 3 + n + 2 * k
    first, pieces = params[zone], params[zone + 1]
    if first < 0.0:
        return -1.0
    j = min(int(s * pieces), int(pieces) - 1)
    row = o + int(first) + TABLE_ROW * j
    return _estrin(params, row + 2, (x - params[row]) * params[row + 1])
