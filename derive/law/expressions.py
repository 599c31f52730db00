"""Law expressions as data: a whitelist parser from text to SymPy, and limits on size and time.

A law's friction and weight come from files anyone may hand over, so their text is never evaluated
as Python (SymPy's ``parse_expr`` and ``sympify`` run ``eval``). :func:`parse_expression` parses the
text with :mod:`ast`, accepts only the grammar below and builds the SymPy expression node by node:

- numbers: int and float literals (not bool, complex or strings); ``pi`` is the constant π;
- names: ``u``, ``r``, ``w`` and the law's parameters (a weight: ``r`` and the parameters); any other
  name is refused, SymPy's own included (``E``, ``I``, ``oo``, ``gamma``, ...: write ``exp(1)``);
- the operators ``+ - * / **`` and unary ``-``, ``+``;
- calls by bare name of :data:`FUNCTIONS`, without keywords;
- ``Piecewise((expr, condition), ..., (expr, True))``: tuples only as its arguments, comparisons
  ``< <= > >=`` (chained: ``a < u <= b``) and ``True`` only as its conditions.

Anything else (attributes, subscripts, lambdas, comprehensions, strings, keywords, comments,
unknown names or functions) raises a one-line :class:`LawError` naming the offending piece. Size
limits keep every expression far from SymPy's recursion limits: :data:`MAX_CHARS` characters,
:data:`MAX_NODES` nodes, :data:`MAX_DEPTH` levels of nesting (a chain ``a + b - c`` or ``a*b/c`` is
one level), integer literals of at most :data:`MAX_INTEGER_BITS` bits and numeric exponents of at
most :data:`MAX_EXPONENT` in magnitude.

:func:`time_limit` bounds the wall time of a SymPy computation (derivation, verification, a limit),
which no size limit can: SymPy's cost grows steeply with a polynomial's degree.
"""

from __future__ import annotations

import ast
import math
import signal
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager

import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.printing.str import StrPrinter

from .lawdata import LawFileError
from .symbols import reserved_reason

MAX_CHARS = 2000
MAX_NODES = 500
MAX_DEPTH = 50
MAX_INTEGER_BITS = 128
#: Largest magnitude of a numeric exponent (u**60 is fine; u**10**6 would stall the derivation).
MAX_EXPONENT = 100
#: Largest exact number a power of numbers may produce, in bits (2**10000 has 3011 digits).
MAX_POWER_BITS = 10_000
#: Characters of the offending text repeated in an error message.
SNIPPET = 60


class LawError(LawFileError):
    """A friction law that cannot have a thermodynamically consistent noise amplitude."""


#: Functions a law may call: name -> (SymPy function, fewest and most arguments).
FUNCTIONS = {
    "Min": (sp.Min, 1, MAX_NODES),
    "Max": (sp.Max, 1, MAX_NODES),
    "Abs": (sp.Abs, 1, 1),
    "exp": (sp.exp, 1, 1),
    "log": (sp.log, 1, 2),
    "sqrt": (sp.sqrt, 1, 1),
    "sin": (sp.sin, 1, 1),
    "cos": (sp.cos, 1, 1),
    "tan": (sp.tan, 1, 1),
    "sinh": (sp.sinh, 1, 1),
    "cosh": (sp.cosh, 1, 1),
    "tanh": (sp.tanh, 1, 1),
    "atan": (sp.atan, 1, 1),
    "asinh": (sp.asinh, 1, 1),
    "erf": (sp.erf, 1, 1),
    "erfc": (sp.erfc, 1, 1),
    "Heaviside": (sp.Heaviside, 1, 1),
    "sign": (sp.sign, 1, 1),
    "Piecewise": (sp.Piecewise, 1, MAX_NODES),
}
#: Named constants: only pi (E is refused: write exp(1)).
CONSTANTS = {"pi": sp.pi}
#: Hints for names SymPy would have read as its own objects.
_HINTS = {
    "E": "write exp(1) for Euler's number",
    "I": "f must be real",
    "oo": "infinity is not a value of f",
    "zoo": "infinity is not a value of f",
    "nan": "f must be finite",
    "true": "True is only a Piecewise condition",
}
_APPLY = {ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b, ast.Mult: lambda a, b: a * b, ast.Div: lambda a, b: a / b}
_COMPARISONS = {ast.Lt: sp.Lt, ast.LtE: sp.Le, ast.Gt: sp.Gt, ast.GtE: sp.Ge}
_KINDS = {
    ast.Attribute: "attribute access",
    ast.Subscript: "a subscript",
    ast.Lambda: "a lambda",
    ast.ListComp: "a comprehension",
    ast.SetComp: "a comprehension",
    ast.DictComp: "a comprehension",
    ast.GeneratorExp: "a comprehension",
    ast.List: "a list",
    ast.Dict: "a dict",
    ast.Set: "a set",
    ast.IfExp: "an if-expression (write Piecewise)",
    ast.BoolOp: "and/or (write a chained comparison, a < u <= b)",
    ast.NamedExpr: "an assignment",
    ast.JoinedStr: "a string",
    ast.Await: "await",
    ast.Yield: "yield",
    ast.YieldFrom: "yield",
    ast.Starred: "a starred argument",
    ast.Slice: "a slice",
}


def snippet(text: str, limit: int = SNIPPET) -> str:
    """``text`` on one line, cut to ``limit`` characters."""
    flat = " ".join(text.split())
    return flat if len(flat) <= limit else flat[: limit - 3] + "..."


class _Parser:
    """Checks an ast tree against the grammar and builds its SymPy expression."""

    def __init__(self, text: str, names: dict[str, sp.Symbol], what: str, excluded: tuple[str, ...]):
        self.text, self.names, self.what, self.excluded = text, names, what, excluded

    def fail(self, problem: str, node: ast.AST | None = None) -> LawError:
        piece = ast.get_source_segment(self.text, node) if node is not None else None
        where = f" {snippet(piece)!r}" if piece else ""
        return LawError(f"{self.what}: {problem}{where}")

    def build(self, node: ast.AST, depth: int) -> sp.Expr:
        if depth > MAX_DEPTH:
            raise self.fail(f"too large: nested deeper than {MAX_DEPTH} levels at")
        if isinstance(node, ast.Constant):
            return self.number(node)
        if isinstance(node, ast.Name):
            return self.name(node)
        if isinstance(node, ast.BinOp):
            return self.chain(node, depth)
        if isinstance(node, ast.UnaryOp):
            if isinstance(node.op, ast.USub):
                return -self.build(node.operand, depth + 1)
            if isinstance(node.op, ast.UAdd):
                return self.build(node.operand, depth + 1)
            raise self.fail("only unary - and + are allowed, not", node)
        if isinstance(node, ast.Call):
            return self.call(node, depth)
        if isinstance(node, ast.Compare):
            raise self.fail("a comparison is only allowed as a Piecewise condition:", node)
        if isinstance(node, ast.Tuple):
            raise self.fail("a tuple is only allowed as a Piecewise argument (expr, condition):", node)
        kind = _KINDS.get(type(node), type(node).__name__)
        raise self.fail(f"{kind} is not allowed:", node)

    def number(self, node: ast.Constant) -> sp.Expr:
        value = node.value
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            kind = {bool: "True/False", str: "a string", bytes: "bytes", complex: "a complex number"}.get(type(value), repr(value))
            raise self.fail(f"{kind} is not allowed here:", node)
        if isinstance(value, int):
            if value.bit_length() > MAX_INTEGER_BITS:
                raise self.fail(f"too large: an integer over {MAX_INTEGER_BITS} bits:", node)
            return sp.Integer(value)
        if not math.isfinite(value):
            raise self.fail("a number must be finite:", node)
        return sp.Float(repr(value))

    def name(self, node: ast.Name) -> sp.Expr:
        name = node.id
        if name in self.names:
            return self.names[name]
        if name in CONSTANTS:
            return CONSTANTS[name]
        if name in FUNCTIONS:
            raise self.fail(f"{name} is a function: write {name}(...), not", node)
        if name in self.excluded:
            raise self.fail(f"unknown name {name!r}: the weight w(r) is an expression in r and the parameters")
        hint = _HINTS.get(name)
        fix = "declare it as a parameter" + (f", or {hint}" if hint else "")
        raise self.fail(f"unknown name {name!r}: {fix}")

    def chain(self, node: ast.BinOp, depth: int) -> sp.Expr:
        """A left-nested chain of + and - (or * and /) is built iteratively, as one level."""
        if isinstance(node.op, ast.Pow):
            return self.power(node, depth)
        if type(node.op) not in _APPLY:
            symbol = "^ (write ** for a power)" if isinstance(node.op, ast.BitXor) else type(node.op).__name__
            raise self.fail(f"operator {symbol} is not allowed:", node)
        family = (ast.Add, ast.Sub) if isinstance(node.op, (ast.Add, ast.Sub)) else (ast.Mult, ast.Div)
        steps = []
        while isinstance(node, ast.BinOp) and isinstance(node.op, family):
            steps.append((node.op, node.right))
            node = node.left
        value = self.build(node, depth + 1)
        for op, right in reversed(steps):
            value = _APPLY[type(op)](value, self.build(right, depth + 1))
        return value

    def power(self, node: ast.BinOp, depth: int) -> sp.Expr:
        base, exponent = self.build(node.left, depth + 1), self.build(node.right, depth + 1)
        if exponent.is_number and bool(abs(exponent) > MAX_EXPONENT):  # TypeError if undecidable: refused below
            raise self.fail(f"too large: an exponent over {MAX_EXPONENT} in", node)
        if base.is_Rational and exponent.is_Rational:
            bits = abs(exponent.p) * max(base.p.bit_length(), base.q.bit_length())
            if bits > MAX_POWER_BITS:
                raise self.fail(f"too large: a number over {MAX_POWER_BITS} bits:", node)
        return base**exponent

    def call(self, node: ast.Call, depth: int) -> sp.Expr:
        if not isinstance(node.func, ast.Name):
            kind = _KINDS.get(type(node.func), "an expression")
            raise self.fail(f"only functions called by name are allowed, not {kind}:", node.func)
        name = node.func.id
        if name not in FUNCTIONS:
            known = name in self.names or name in CONSTANTS
            raise self.fail(f"{name!r} is not a function" if known else f"unknown function {name!r}; allowed: {', '.join(FUNCTIONS)}")
        if node.keywords:
            raise self.fail(f"keyword arguments are not allowed: {name}(...)", node.keywords[0])
        function, fewest, most = FUNCTIONS[name]
        if not fewest <= len(node.args) <= most:
            count = str(fewest) if fewest == most else f"{fewest} to {most}"
            raise self.fail(f"{name} takes {count} argument(s), got {len(node.args)}:", node)
        if name == "Piecewise":
            return self.piecewise(node, depth)
        args = [self.build(arg, depth + 1) for arg in node.args]
        return function(*args)

    def piecewise(self, node: ast.Call, depth: int) -> sp.Expr:
        pairs = []
        for arg in node.args:
            if not (isinstance(arg, ast.Tuple) and len(arg.elts) == 2):
                raise self.fail("a Piecewise argument must be a pair (expr, condition):", arg)
            pairs.append((self.build(arg.elts[0], depth + 2), self.condition(arg.elts[1], depth + 2)))
        return sp.Piecewise(*pairs)

    def condition(self, node: ast.AST, depth: int) -> sp.Basic:
        if isinstance(node, ast.Constant) and node.value is True:
            return sp.true
        if not isinstance(node, ast.Compare):
            raise self.fail("a Piecewise condition must be a comparison or True:", node)
        operands = [self.build(node.left, depth + 1), *(self.build(c, depth + 1) for c in node.comparators)]
        relations = []
        for k, op in enumerate(node.ops):
            if type(op) not in _COMPARISONS:
                raise self.fail("only <, <=, >, >= are allowed in a condition:", node)
            relations.append(_COMPARISONS[type(op)](operands[k], operands[k + 1]))
        return sp.And(*relations)


def parse_expression(text: str, names: dict[str, sp.Symbol], what: str, excluded: tuple[str, ...] = ()) -> sp.Expr:
    """The SymPy expression of ``text``, built from its checked syntax tree (never evaluated).

    Args:
        text: the expression as written in the law file.
        names: the symbols it may use, by name.
        what: the start of error messages, e.g. ``"law stick_slip: f"``.
        excluded: names known elsewhere but not here (``u``, ``w`` in a weight), for the message.
    """
    if not isinstance(text, str):
        raise LawError(f"{what}: must be a string, got {type(text).__name__}")
    text = text.strip()
    if len(text) > MAX_CHARS:
        raise LawError(f"{what}: too large: {len(text)} characters (limit {MAX_CHARS})")
    if not text:
        raise LawError(f"{what}: empty expression")
    if "#" in text:
        raise LawError(f"{what}: a comment ('#') is not allowed in an expression")
    try:
        tree = ast.parse(text, mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError) as error:
        detail = getattr(error, "msg", None) or str(error)
        column = f" at column {error.offset}" if getattr(error, "offset", None) else ""
        raise LawError(f"{what}: cannot parse {snippet(text)!r}: {snippet(detail)}{column}") from None
    nodes = sum(isinstance(node, ast.expr) for node in ast.walk(tree))
    if nodes > MAX_NODES:
        raise LawError(f"{what}: too large: {nodes} nodes (limit {MAX_NODES})")
    parser = _Parser(text, names, what, excluded)
    try:
        expr = parser.build(tree.body, 1)
    except LawError:
        raise
    except (TypeError, ValueError, ArithmeticError, RecursionError) as error:  # e.g. Piecewise of a non-condition
        raise LawError(f"{what}: cannot build {snippet(text)!r}: {snippet(str(error))}") from None
    if not isinstance(expr, sp.Expr):
        raise LawError(f"{what}: {snippet(text)!r} is not an expression")
    if expr.has(sp.zoo, sp.oo, -sp.oo, sp.nan):
        raise LawError(f"{what}: {snippet(text)!r} is infinite or undefined (a division by zero?)")
    return expr


def check_parameter_name(name: object, what: str) -> None:
    """A parameter's name becomes a symbol of the expressions and a variable of the kernels."""
    if not (isinstance(name, str) and name.isascii() and name.isidentifier()) or name.startswith(("cse", "_")):
        shown = snippet(repr(name)) if isinstance(name, str) else type(name).__name__
        raise LawError(f"{what}: parameter name {shown} must be an ASCII identifier not starting with '_' or 'cse'")
    if name in FUNCTIONS or name in CONSTANTS:
        raise LawError(f"{what}: parameter name {name!r} is the name of a function or constant of expressions; rename it")
    reason = reserved_reason(name)
    if reason:
        raise LawError(f"{what}: parameter name {name!r} is reserved: {reason}; rename it")


class _ExprText(StrPrinter):
    """SymPy's string form, with Euler's number spelled exp(1) (the parser refuses E)."""

    def _print_Exp1(self, expr):
        return "exp(1)"


def expression_text(expr: sp.Expr) -> str:
    """Text of a SymPy expression that :func:`parse_expression` reads back (where it can)."""
    return _ExprText().doprint(expr)


def check_expression(expr: sp.Expr, what: str) -> None:
    """The limits of :func:`parse_expression` for an expression built in Python."""
    if not isinstance(expr, sp.Expr):
        raise LawError(f"{what}: must be a string or a SymPy expression, got {type(expr).__name__}")
    nodes = sum(1 for _ in sp.preorder_traversal(expr))
    if nodes > MAX_NODES:
        raise LawError(f"{what}: too large: {nodes} nodes (limit {MAX_NODES})")
    undefined = sorted(str(f.func) for f in expr.atoms(AppliedUndef))
    if undefined:
        raise LawError(f"{what}: unknown function(s) {', '.join(undefined)}")


# --- time limits -----------------------------------------------------------------------------------


class _Expired(BaseException):
    """Raised by the alarm inside a computation; a BaseException so that no ``except Exception`` in
    SymPy swallows it. :func:`time_limit` turns it into the caller's error."""

    def __init__(self, token: object):
        super().__init__()
        self.token = token


_deadlines: list[tuple[float, object]] = []  # (monotonic deadline, token), innermost last
_previous_handler = None


def _arm() -> None:
    """Set the interval timer for the earliest open deadline (or clear it)."""
    if _deadlines:
        left = min(d for d, _ in _deadlines) - time.monotonic()
        signal.setitimer(signal.ITIMER_REAL, max(left, 1e-3))
    else:
        signal.setitimer(signal.ITIMER_REAL, 0)


def _expire(signum, frame) -> None:
    if not _deadlines:
        return
    deadline, token = min(_deadlines, key=lambda item: item[0])
    if deadline > time.monotonic():
        _arm()  # a limit that ended since the timer was set: wait for the next one
        return
    raise _Expired(token)


@contextmanager
def time_limit(seconds: float | None, error: BaseException) -> Iterator[None]:
    """Raise ``error`` if the block runs longer than ``seconds`` (None: no limit).

    Uses SIGALRM, so it limits only in the main thread of a Unix process (elsewhere the block runs
    without a limit). Limits nest: an outer limit that expires inside an inner one raises the outer
    error. A computation inside one C call (a huge integer power) is interrupted only when it returns.
    """
    global _previous_handler
    usable = seconds is not None and hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()
    if not usable:
        yield
        return
    token = object()
    if not _deadlines:
        _previous_handler = signal.signal(signal.SIGALRM, _expire)
    _deadlines.append((time.monotonic() + seconds, token))
    _arm()
    try:
        yield
    except _Expired as expired:
        if expired.token is not token:
            raise
        raise error from None
    finally:
        _deadlines[:] = [item for item in _deadlines if item[1] is not token]
        _arm()
        if not _deadlines:
            signal.signal(signal.SIGALRM, _previous_handler)
