"""Canonical SymPy symbols shared by the symbolic layer.

Conventions (docs/physics.md#units-and-symbols): ``u`` is the magnitude of the relative tangential contact
velocity (u >= 0), ``r`` the centre distance, ``w`` the value of a law's distance weight
w(r), ``kT`` the thermal energy and ``mu`` the contact mobility
mu = 1/m_i + 1/m_k + R_i^2/I_i + R_k^2/I_k (units 1/mass).
"""

from __future__ import annotations

import builtins
import keyword
import re

import sympy as sp

u = sp.Symbol("u", positive=True)
r = sp.Symbol("r", positive=True)
w = sp.Symbol("w", positive=True)
kT = sp.Symbol("kT", positive=True)
mu = sp.Symbol("mu", positive=True)

#: Integration variable of the integral representation (F-22).
s = sp.Symbol("s", positive=True)

#: Names a law may not use for its parameters (symbols, and names of the generated kernels).
RESERVED = frozenset({"u", "r", "w", "kT", "mu", "s", "params", "math", "numba", "erfcx", "friction", "weight"})

#: Python's keywords and builtins: not parameter names (a parameter ``min`` would shadow the ``min``
#: that the printer writes for ``Min`` in a kernel).
PYTHON_NAMES = frozenset(keyword.kwlist) | frozenset(dir(builtins))

#: The names that the generated code defines or calls besides :data:`RESERVED`: the Numba modules'
#: functions and constants (fricgen.derive.backends.numba_kernels) and the C++ plugin's
#: (fricgen.derive.backends.lammps_plugin). A parameter is a variable inside the kernels, where it
#: would hide one of them.
KERNEL_NAMES = frozenset(
    """friction_over_u friction_slope energy force force_field expm1_given_exp erfcx_right LAW NAME SOURCE_HASH PARAMETERS
    DEFAULTS RANGES UNITS CALCULI CLOSED_FORM HAS_WEIGHT panel next_cut gaussian_tail pair_energy pair_force mix stream_key
    normal_pair_at GL_NODES GL_WEIGHTS GOLDEN CONTACT_STREAM std""".split()
)
#: Families of generated names: per calculus, per branch switch, and fricgen's C++ helpers.
KERNEL_PATTERN = re.compile(r"(noise_amplitude|noise_sqrt|contact|switch)_\w*|fricgen\w*", re.IGNORECASE)

#: C and C++ keywords (C++20 and C11, alternative tokens included): a parameter is a C++ variable of the plugin.
CXX_KEYWORDS = frozenset(
    """alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t char16_t char32_t class compl concept
    const consteval constexpr constinit const_cast continue co_await co_return co_yield decltype default delete do double
    dynamic_cast else enum explicit export extern false final float for friend goto if import inline int long module mutable
    namespace new noexcept not not_eq nullptr operator or or_eq override private protected public register reinterpret_cast
    requires restrict return short signed sizeof static static_assert static_cast struct switch template this thread_local
    throw true try typedef typeid typename union unsigned using virtual void volatile wchar_t while xor xor_eq""".split()
)
#: Macros, typedefs and functions of the C and C++ standard libraries that the plugin includes
#: (<cmath>, <cstdint>, <cstdlib>, <cerrno>, <climits>, <cfloat>, <cassert>, <cstdio>), of LAMMPS's
#: headers (lmptype.h, pointers.h) and of MPI: a macro would rewrite the declaration of the
#: parameter, a function or a type would be hidden by it.
C_NAMES = frozenset(
    """INFINITY NAN HUGE_VAL HUGE_VALF HUGE_VALL MATH_ERRNO MATH_ERREXCEPT math_errhandling errno assert NULL EOF BUFSIZ
    FILENAME_MAX stdin stdout stderr EXIT_SUCCESS EXIT_FAILURE RAND_MAX MB_CUR_MAX CHAR_BIT CHAR_MAX CHAR_MIN SCHAR_MAX
    SCHAR_MIN UCHAR_MAX SHRT_MAX SHRT_MIN USHRT_MAX INT_MAX INT_MIN UINT_MAX LONG_MAX LONG_MIN ULONG_MAX LLONG_MAX LLONG_MIN
    ULLONG_MAX DBL_MAX DBL_MIN DBL_EPSILON DBL_DIG DBL_MANT_DIG DBL_TRUE_MIN FLT_MAX FLT_MIN FLT_EPSILON FLT_RADIX LDBL_MAX
    LDBL_MIN LDBL_EPSILON DECIMAL_DIG offsetof size_t ssize_t ptrdiff_t intptr_t uintptr_t intmax_t uintmax_t max_align_t
    nullptr_t div_t ldiv_t FILE va_list jmp_buf setjmp longjmp signal raise abort exit malloc calloc realloc free
    abs labs llabs fabs fmin fmax fdim fma fmod remainder remquo copysign nan nextafter nexttoward pow exp exp2 expm1 log
    log2 log10 log1p logb ilogb sqrt cbrt hypot sin cos tan asin acos atan atan2 sinh cosh tanh asinh acosh atanh erf erfc
    tgamma lgamma ceil floor trunc round lround llround rint lrint llrint nearbyint frexp ldexp modf scalbn scalbln isnan
    isinf isfinite isnormal signbit fpclassify isgreater isgreaterequal isless islessequal islessgreater isunordered
    bigint tagint imageint FLERR NEIGHMASK SBBITS HISTBITS HISTMASK MAXSMALLINT MAXTAGINT MAXBIGINT MAXIMAGEINT IMGMASK
    IMGMAX IMGBITS IMG2BITS IMGBIGMASK IMGBIGMAX IMGBIGBITS IMGBIG2BITS TAGINT_FORMAT BIGINT_FORMAT ATOTAGINT ATOBIGINT
    ATOIMAGEINT""".split()
)
#: Families of C macros and types: <cmath>'s M_ constants and FP_ classes, <cerrno>'s E codes, <cstdint>'s
#: fixed-width types and their limits, MPI's and LAMMPS's prefixes, and what C and C++ reserve to the
#: implementation (a double underscore anywhere).
C_PATTERN = re.compile(
    r"M_\w+|FP_\w+|E[A-Z][A-Z0-9_]*|E2BIG|u?int(_least|_fast)?\d+_t|U?INT(_LEAST|_FAST)?\d+_(MAX|MIN|C)|(U?INTMAX|U?INTPTR|SIZE"
    r"|PTRDIFF|SIG_ATOMIC|WCHAR|WINT)_(MAX|MIN|C)|MPI\w*|LMP\w*|LAMMPS\w*|PRI\w+|SCN\w+|\w*__\w*"
)


def reserved_reason(name: str) -> str | None:
    """Why ``name`` cannot name a law's parameter, in a few words, or None if it can: a symbol of the
    expressions, a name of the generated kernels, a Python keyword or builtin, a C or C++ keyword, or
    a macro, type or function of the C/C++ libraries, LAMMPS or MPI that the plugin includes."""
    if name in RESERVED or name in KERNEL_NAMES or KERNEL_PATTERN.fullmatch(name):
        return "a symbol or a name of the generated kernels"
    if name in PYTHON_NAMES:
        return "a Python keyword or builtin (the Numba kernels are Python)"
    if name in CXX_KEYWORDS:
        return "a C++ keyword (the LAMMPS plugin is C++)"
    if "__" in name:
        return "C and C++ reserve names with a double underscore to the compiler"
    if name in C_NAMES or C_PATTERN.fullmatch(name):
        return "a macro, type or function of C/C++, LAMMPS or MPI (the LAMMPS plugin's C++ would not compile)"
    return None
