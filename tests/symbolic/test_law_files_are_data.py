"""Law files are data: their expressions are parsed by a whitelist, never run as Python, and every
bad file or expression is refused with one line naming the problem (parse level: no derivation)."""

import json
import os
import re
import time

import pytest
import sympy as sp
from sympy.parsing.sympy_parser import parse_expr

from fricgen.derive import catalogue, load_law, make_law, save_law
from fricgen.derive.errors import DeriveError
from fricgen.derive.law.expressions import MAX_CHARS, MAX_DEPTH, MAX_NODES, LawError, parse_expression, time_limit
from fricgen.derive.law.lawdata import CATALOGUE, LawFileError, read_law_data, source_hash
from fricgen.derive.law.symbols import r, u, w

GAMMA = {"gamma_f": {"default": 1.0}}


def _one_line(error: BaseException) -> str:
    message = str(error)
    assert message and "\n" not in message and len(message) < 300, message
    return message


def _refused(expected: str, call, *args, **kwargs) -> str:
    with pytest.raises(DeriveError) as caught:
        call(*args, **kwargs)
    assert isinstance(caught.value, LawFileError) and isinstance(caught.value, ValueError)
    message = _one_line(caught.value)
    assert expected in message, message
    return message


# --- expressions ---------------------------------------------------------------------------------

BAD_EXPRESSIONS = [
    ("__import__('os').system('true') + w*gamma_f*u", "attribute access"),
    ("__import__('os')", "unknown function '__import__'"),
    ("eval('u')", "unknown function 'eval'"),
    ("exec('u = 1')", "unknown function 'exec'"),
    ("open('x').read()", "attribute access"),
    ("getattr(u, 'real')", "unknown function 'getattr'"),
    ("u.__class__", "attribute access"),
    ("().__class__.__bases__[0]", "a subscript"),
    ("gamma_f*[u][0]", "a subscript"),
    ("(lambda: u)()", "a lambda"),
    ("lambda: u", "a lambda"),
    ("[u for u in (1, 2)]", "a comprehension"),
    ("sum(x for x in (u,))", "unknown function 'sum'"),
    ("{u: 1}", "a dict"),
    ("{u}", "a set"),
    ("[u, w]", "a list"),
    ("'u'", "a string"),
    ("b'u'", "bytes"),
    ("f'{u}'", "a string"),
    ("u*1j", "a complex number"),
    ("u*True", "True/False"),
    ("u*None", "None"),
    ("u if w else gamma_f", "if-expression"),
    ("u and w", "and/or"),
    ("(x := u)", "an assignment"),
    ("u ^ 2", "write ** for a power"),
    ("u // 2", "operator FloorDiv"),
    ("u % 2", "operator Mod"),
    ("u @ w", "operator MatMult"),
    ("u << 2", "operator LShift"),
    ("~u", "only unary - and +"),
    ("not u", "only unary - and +"),
    ("E*gamma_f*u", "unknown name 'E': declare it as a parameter, or write exp(1)"),
    ("I*gamma_f*u", "unknown name 'I'"),
    ("oo*u", "unknown name 'oo'"),
    ("gamma*u", "unknown name 'gamma'"),
    ("zeta*u", "unknown name 'zeta'"),
    ("S(1)*u", "unknown function 'S'"),
    ("N(u)", "unknown function 'N'"),
    ("gamma_f*v", "unknown name 'v'"),
    ("kT*u", "unknown name 'kT'"),
    ("gamma_f*g(u)", "unknown function 'g'"),
    ("gamma_f(u)", "'gamma_f' is not a function"),
    ("exp*u", "exp is a function"),
    ("sympify('u')", "unknown function 'sympify'"),
    ("exp(u, 2)", "exp takes 1 argument(s), got 2"),
    ("Min()", "Min takes 1 to"),
    ("exp(x=u)", "keyword arguments are not allowed"),
    ("exp(*[u])", "a starred argument"),
    ("u < 1", "only allowed as a Piecewise condition"),
    ("(u, w)", "only allowed as a Piecewise argument"),
    ("Piecewise(u, True)", "must be a pair (expr, condition)"),
    ("Piecewise((u, u))", "must be a comparison or True"),
    ("Piecewise((u, u == 1), (1, True))", "only <, <=, >, >="),
    ("Piecewise((u, 'u > 1'), (1, True))", "must be a comparison or True"),
    ("gamma_f*u +", "cannot parse"),
    ("gamma_f*u; 1", "cannot parse"),
    ("u\0", "cannot parse"),
    ("", "empty expression"),
    ("   ", "empty expression"),
    ("gamma_f*u  # a comment", "a comment ('#')"),
    ("u/0", "infinite or undefined"),
    ("u*1e999", "a number must be finite"),
    ("u**1000", "too large: an exponent over"),
    ("9**9**9*u", "too large"),
    ("(3**100)**100*u", "too large: a number over"),
    ("u*" + "9" * 60, "too large: an integer over"),
    ("u" + "+u" * MAX_NODES, "too large:"),
    ("u" + " " * MAX_CHARS, None),  # trailing blanks are stripped: fine
    ("u*" + "1" * (MAX_CHARS - 1), "too large: 2001 characters"),
    ("exp(" * (MAX_DEPTH + 5) + "u" + ")" * (MAX_DEPTH + 5), "too large: nested deeper than"),
    ("-" * (MAX_DEPTH + 5) + "u", "too large: nested deeper than"),
]


@pytest.mark.parametrize(("text", "problem"), BAD_EXPRESSIONS, ids=[f"{k}" for k in range(len(BAD_EXPRESSIONS))])
def test_bad_expressions_are_refused_on_one_line(text, problem):
    if problem is None:
        assert make_law("fine", text, GAMMA).friction == u
        return
    message = _refused(problem, make_law, "bad", text, GAMMA)
    assert message.startswith("law bad: f")


def test_there_are_at_least_forty_bad_expressions():
    assert sum(problem is not None for _, problem in BAD_EXPRESSIONS) >= 40


@pytest.mark.parametrize(
    ("weight", "problem"),
    [
        ("u*r", "the weight w(r) is an expression in r and the parameters"),
        ("w", "neither a potential"),
        ("lj", "neither a potential (wca"),
        ("__import__('os').getcwd()", "attribute access"),
        ("r**2 + E", "unknown name 'E'"),
        (3, "weight must be a string"),
    ],
)
def test_bad_weights_are_refused(weight, problem):
    message = _refused(problem, make_law, "bad", "gamma_f*u", GAMMA, weight=weight)
    assert message.startswith("law bad: weight")


def test_python_in_a_law_file_is_refused_without_running_it(tmp_path):
    marker = tmp_path / "PWNED"
    payloads = [
        f"__import__('os').system('touch {marker}') + w*gamma_f*u",
        f"__import__('pathlib').Path('{marker}').touch() or u",
        f"(lambda: open('{marker}', 'w'))() and u",
        f"[open('{marker}', 'w') for _ in (1,)][0] and u",
        f"exec(\"open('{marker}', 'w')\") or u",
        f"Piecewise((u, open('{marker}', 'w') > 0), (u, True))",
        f"exp(u).func.__globals__['__builtins__']['open']('{marker}', 'w')",
    ]
    for k, payload in enumerate(payloads):
        path = tmp_path / f"evil{k}.toml"
        path.write_text(f'name = "evil{k}"\nweight = "wca"\nfriction = {json.dumps(payload)}\n[parameters.gamma_f]\ndefault = 1.0\n')
        assert read_law_data(path)["friction"] == payload
        _refused("law evil", load_law, path)
        assert not marker.exists(), payload
    weight = tmp_path / "evil_weight.toml"
    weight.write_text(f'name = "evil_weight"\nfriction = "w*u"\nweight = "__import__(\'os\').system(\'touch {marker}\')"\n')
    _refused("attribute access", load_law, weight)
    assert not marker.exists()


def test_a_huge_expression_is_refused_at_once():
    started = time.perf_counter()
    message = _refused("too large: ", make_law, "bad", "+".join(["gamma_f*u"] * 20_000), GAMMA)
    assert time.perf_counter() - started < 1.0 and "gamma_f*u+gamma_f*u+gamma_f" not in message
    deep = "(" * 250 + "u" + ")" * 250  # beyond Python's own parser's nesting limit
    _refused("cannot parse", make_law, "bad", deep, GAMMA)


def test_the_parser_builds_what_sympy_builds_for_the_catalogue():
    """The same SymPy trees as sympy's parse_expr (trusted text here), so hashes and kernels are unchanged."""
    for law in catalogue().values():
        names = {"u": u, "r": r, "w": w, **law.symbols}
        assert sp.srepr(parse_expr(law.source, local_dict=dict(names))) == sp.srepr(law.friction), law.name


def test_allowed_grammar():
    g = sp.Symbol("g", positive=True)
    names = {"u": u, "w": w, "r": r, "g": g}
    read = lambda text: parse_expression(text, names, "test")  # noqa: E731
    assert read("g*exp(u**(19/10))") == g * sp.exp(u ** sp.Rational(19, 10))
    assert read("pi*g*u") == sp.pi * g * u
    assert read("-u + +w - 2.5*r/4") == -u + w - sp.Float("2.5") * r / 4
    assert read("Piecewise((g*u, 0 < u <= 1), (g, True))") == sp.Piecewise((g * u, sp.And(u > 0, u <= 1)), (g, True))
    assert read("Max(Min(u, w), Abs(r - 1))") == sp.Max(sp.Min(u, w), sp.Abs(r - 1))
    assert read("log(u, 2) + sqrt(u) + erfc(u) + erf(u) + tanh(u) + atan(u) + Heaviside(u - 1) + sign(u)") is not None
    assert read("  (u\n + w)  ") == u + w


def test_parameters_may_not_shadow_functions_constants_or_python_names():
    for name, problem in [
        ("exp", "name of a function"),
        ("pi", "constant"),
        ("min", "reserved"),
        ("lambda", "reserved"),
        ("kT", "reserved"),
    ]:
        _refused(problem, make_law, "bad", f"{name}*u", {name: {"default": 1.0}})
    _refused("ASCII identifier", make_law, "bad", "u", {"γ": {"default": 1.0}})
    _refused("ASCII identifier", make_law, "bad", "u", {"_hidden": {"default": 1.0}})
    assert make_law("fine", "E*u", {"E": {"default": 2.0}}).friction == 2 * u / 2 * sp.Symbol("E", positive=True)


@pytest.mark.parametrize(
    ("name", "problem"),
    [
        ("INFINITY", "a macro, type or function of C/C++"),
        ("NAN", "a macro, type or function of C/C++"),
        ("M_PI", "a macro, type or function of C/C++"),
        ("errno", "a macro, type or function of C/C++"),
        ("EDOM", "a macro, type or function of C/C++"),
        ("fabs", "a macro, type or function of C/C++"),
        ("uint64_t", "a macro, type or function of C/C++"),
        ("MPI_COMM_WORLD", "a macro, type or function of C/C++"),
        ("FLERR", "a macro, type or function of C/C++"),
        ("new", "a C++ keyword"),
        ("template", "a C++ keyword"),
        ("register", "a C++ keyword"),
        ("a__b", "double underscore"),
        ("erfcx", "a name of the generated kernels"),
        ("expm1_given_exp", "a name of the generated kernels"),
        ("switch_0", "a name of the generated kernels"),
        ("noise_amplitude_ito", "a name of the generated kernels"),
        ("friction_over_u", "a name of the generated kernels"),
        ("fricgen_powi", "a name of the generated kernels"),
        ("gaussian_tail", "a name of the generated kernels"),
        ("params", "a name of the generated kernels"),
        ("std", "a name of the generated kernels"),
        ("_gaussian_tail", "not starting with '_'"),
        ("abs", "a Python keyword or builtin"),
        ("class", "a Python keyword or builtin"),
    ],
)
def test_parameter_names_of_the_target_languages_and_our_helpers_are_refused(name, problem):
    """A parameter is a variable of the Numba and the C++ kernels: names those languages reserve, or
    that the generated code defines, are refused when the law is read, on one line."""
    with pytest.raises(LawError, match=re.escape(problem)) as refused:
        make_law("bad", f"{name}*u", {name: {"default": 1.0}})
    assert "\n" not in str(refused.value) and f"parameter name {name!r}" in str(refused.value)


def test_ordinary_physics_names_stay_allowed():
    for name in ("E", "E0", "F0", "U0", "A", "T", "gamma_t", "mu_s", "alpha", "theta", "k", "t", "lo", "total", "order", "D"):
        assert make_law("fine", f"{name}*u", {name: {"default": 1.0}}).parameters[0].name == name


def test_expressions_from_python_are_written_so_that_they_load(tmp_path):
    g = sp.Symbol("gamma_f", positive=True)
    law = make_law("euler", sp.E * g * u * (2 + sp.tanh(u)), GAMMA)
    assert law.source == "exp(1)*gamma_f*u*(tanh(u) + 2)"
    assert load_law(save_law(law, tmp_path)) == law
    _refused("unknown function(s) f", make_law, "bad", sp.Function("f")(u), GAMMA)
    _refused("must be a string or a SymPy expression", make_law, "bad", 3, GAMMA)


# --- law files -----------------------------------------------------------------------------------

GOOD = {"name": '"x"', "friction": '"w*gamma_f*u"', "weight": '"wca"', "calculi": '["ito"]'}


def _file(tmp_path, **fields):
    """A law file x.toml from GOOD with fields replaced (None: left out); ``tables`` appended as is."""
    tables = fields.pop("tables", "[parameters.gamma_f]\ndefault = 1.0\n")
    lines = [f"{k} = {v}" for k, v in {**GOOD, **fields}.items() if v is not None]
    path = tmp_path / "x.toml"
    path.write_text("\n".join(lines) + "\n" + tables)
    return path


BAD_FILES = [
    ({"calculi": '"ito"'}, "calculi must be a list of strings"),
    ({"calculi": "[]"}, "calculi must not be empty"),
    ({"calculi": '["ito", "euler"]'}, "unknown calculus str 'euler'"),
    ({"calculi": "[1]"}, "unknown calculus int 1"),
    ({"parameters": "3", "tables": ""}, "parameters must be a table"),
    ({"tables": "[parameters]\ngamma_f = 3\n"}, "parameters.gamma_f must be a table with a default"),
    ({"tables": "[parameters.gamma_f]\nunit = '1'\n"}, "parameters.gamma_f needs a default"),
    ({"tables": "[parameters.gamma_f]\ndefault = true\n"}, "parameters.gamma_f.default must be a number, got bool True"),
    ({"tables": "[parameters.gamma_f]\ndefault = '1.0'\n"}, "parameters.gamma_f.default must be a number, got str"),
    ({"tables": "[parameters.gamma_f]\ndefault = 1.0\nunit = 3\n"}, "parameters.gamma_f.unit must be a string"),
    ({"tables": "[parameters.gamma_f]\ndefault = 1.0\ndescription = []\n"}, "parameters.gamma_f.description must be a string"),
    ({"tables": "[parameters.gamma_f]\ndefault = 1.0\nmin = 0\n"}, "parameters.gamma_f has unknown key(s) ['min']"),
    ({"tables": "[parameters.gamma_f]\ndefault = -1.0\n"}, "needs a finite positive default"),
    ({"tables": "[parameters.gamma_f]\ndefault = inf\n"}, "needs a finite positive default"),
    ({"tables": "[parameters.gamma_f]\ndefault = nan\n"}, "needs a finite positive default"),
    ({"tables": "[parameters.gamma_f]\ndefault = 1" + "0" * 400 + "\n"}, "needs a finite positive default"),
    ({"tables": '[parameters."a b"]\ndefault = 1.0\n[parameters.gamma_f]\ndefault = 1.0\n'}, "parameter name 'a b'"),
    ({"tables": '[parameters."a\\nb"]\ndefault = 1.0\n'}, "parameter name 'a\\nb'"),
    ({"tables": "[parameters.exp]\ndefault = 1.0\n"}, "'exp' is the name of a function"),
    ({"name": "3"}, "name must be a string, got int 3"),
    ({"name": '"y"'}, "must equal the file name 'x'"),
    ({"name": None}, "missing key 'name'"),
    ({"friction": None}, "missing key 'friction'"),
    ({"friction": "3"}, "friction must be a string, got int 3"),
    ({"friction": '["u"]'}, "friction must be a string, got list"),
    ({"weight": "1.5"}, "weight must be a string, got float 1.5"),
    ({"description": "1979-05-27"}, "description must be a string, got date"),
    ({"reference": "{a = 1}"}, "reference must be a string, got dict"),
    ({"frictoin": '"u"'}, "unknown key(s) ['frictoin']"),
    ({"friction": '"E*u"'}, "unknown name 'E'"),
]


@pytest.mark.parametrize(("fields", "problem"), BAD_FILES, ids=[f"{k}" for k in range(len(BAD_FILES))])
def test_bad_law_files_are_refused_on_one_line(tmp_path, fields, problem):
    _refused(problem, load_law, _file(tmp_path, **fields))


def test_unreadable_law_files(tmp_path):
    binary = tmp_path / "binary.toml"
    binary.write_bytes(b'name = "binary"\nfriction = "u"\n\xff\xfe\x00')
    _refused("not a text law file: byte 31 is not UTF-8", load_law, binary)
    _refused("not a text law file", read_law_data, binary)  # what the kernel loader reads (KernelError there)
    nul = tmp_path / "nul.toml"
    nul.write_bytes(b'name = "nul"\nfriction = "u\x00"\n')
    _refused("not valid TOML", load_law, nul)
    huge = tmp_path / "huge.toml"
    huge.write_text('name = "huge"\nfriction = "u"\n' + "#" * 100_000)
    _refused("too large for a law file", load_law, huge)
    _refused("no such law file", load_law, tmp_path / "missing.toml")
    (tmp_path / "folder.toml").mkdir()
    _refused("is a folder, not a law file", load_law, tmp_path / "folder.toml")
    os.mkfifo(tmp_path / "fifo.toml")  # opened without blocking: refused at once, never waited on
    _refused("is a FIFO (named pipe), not a law file", load_law, tmp_path / "fifo.toml")
    (tmp_path / "dangling.toml").symlink_to(tmp_path / "nowhere.toml")
    _refused("is a dangling symbolic link, not a law file", load_law, tmp_path / "dangling.toml")
    for bad in ("__init__", "lambda"):
        path = tmp_path / f"{bad}.toml"
        path.write_text(f'name = "{bad}"\nfriction = "u"\n')
        _refused("must not start with an underscore or be a Python keyword", load_law, path)


def test_python_api_types_are_checked():
    _refused("calculi must be a non-empty list", make_law, "bad", "u", calculi="ito")
    _refused("calculi must be a non-empty list", make_law, "bad", "u", calculi=["ito", "euler"])
    _refused("parameters must be a table", make_law, "bad", "u", 3)
    _refused("needs a finite positive default", make_law, "bad", "gamma_f*u", {"gamma_f": {"default": True}})
    _refused("description must be a string", make_law, "bad", "u", description=3)
    _refused("law name 3", make_law, 3, "u")


def test_save_law_refuses_to_overwrite(tmp_path):
    law = make_law("soft", "w*kappa_f*(1 - exp(-u))", {"kappa_f": {"default": 2.0}}, weight="wca")
    path = save_law(law, tmp_path)
    assert save_law(law, tmp_path) == path  # the same text: nothing to overwrite
    other = make_law("soft", "w*kappa_f*(1 - exp(-u))", {"kappa_f": {"default": 3.0}}, weight="wca")
    message = _refused("overwrite=True", save_law, other, tmp_path)
    assert str(path) in message and load_law(path) == law
    assert save_law(other, tmp_path, overwrite=True) == path and load_law(path) == other
    assert sorted(p.name for p in tmp_path.iterdir()) == ["soft.toml"]  # no temporary file left


def test_the_hash_is_that_of_the_bytes_read(tmp_path):
    """load_law hashes the data it built the law from; byte-identical files hash alike (and as the loader does)."""
    copy = tmp_path / "linear.toml"
    copy.write_bytes((CATALOGUE / "linear.toml").read_bytes())
    law = load_law(copy)
    assert law.source_hash == source_hash(read_law_data(copy)) == load_law(CATALOGUE / "linear.toml").source_hash
    copy.write_text(copy.read_text().replace("default = 1.0", "default = 2.0"))
    assert law.source_hash != source_hash(read_law_data(copy))


def test_time_limits_nest():
    class Outer(Exception):
        pass

    class Inner(Exception):
        pass

    def busy(seconds):
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            pass

    with pytest.raises(Outer):
        with time_limit(0.2, Outer()):
            with time_limit(5.0, Inner()):
                busy(2.0)
    with pytest.raises(Inner):
        with time_limit(5.0, Outer()):
            with time_limit(0.2, Inner()):
                busy(2.0)
    with time_limit(0.1, Outer()):
        pass
    busy(0.3)  # no stray alarm once the limits are closed
    with time_limit(None, Outer()):
        busy(0.01)
