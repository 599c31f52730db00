"""The API reference is one a physicist can work from: every public callable that docs/api documents
has a numpy-style docstring whose Parameters name each argument and whose Returns say what comes back
(with units, docs/api/index.md), and the examples in those docstrings run.

"Public" is what the API pages render: the members of each ``automodule`` directive of docs/api (a
module's ``__all__``, or the listed ``:members:``, less ``:exclude-members:``), each ``autofunction``,
and the public methods and properties a documented class defines itself. A class documents its
constructor's arguments under Parameters, or its fields under Attributes (dataclasses and named
tuples), and only there: the API pages leave undocumented members out (conf.py), so a field with a
``#:`` comment as well would appear twice. A property needs a docstring to appear at all.
"""

import ast
import dataclasses
import doctest
import enum
import importlib
import inspect
import io
import re
import textwrap
from pathlib import Path

import pytest
from sphinx.pycode import ModuleAnalyzer

ROOT = Path(__file__).resolve().parents[1]
DIRECTIVE = re.compile(r"^\.\. (automodule|autofunction|autoclass):: (\S+)\n((?:[ \t]+:[^\n]*\n)*)", re.MULTILINE)
SECTION = re.compile(r"^(\w+)\n-{3,}\n(.*?)(?=^\w+\n-{3,}\n|\Z)", re.MULTILINE | re.DOTALL)
ENTRY = re.compile(r"^(\*{0,2}\w+(?:, \*{0,2}\w+)*)(?: : .*)?$", re.MULTILINE)


def _option(options: str, name: str) -> list[str] | None:
    match = re.search(rf":{name}:(.*)", options)
    return None if match is None else [part.strip() for part in match.group(1).split(",") if part.strip()]


def documented() -> dict[str, object]:
    """{qualified name: object} of the callables the API pages render."""
    found = {}
    for page in sorted((ROOT / "docs" / "api").glob("*.md")):
        for kind, target, options in DIRECTIVE.findall(page.read_text()):
            if kind != "automodule":
                module, _, name = target.rpartition(".")
                found[target] = getattr(importlib.import_module(module), name)
                continue
            module = importlib.import_module(target)
            members = _option(options, "members")
            names = members or getattr(module, "__all__", [])
            excluded = set(_option(options, "exclude-members") or [])
            for name in names:
                if name not in excluded and (inspect.isfunction(getattr(module, name)) or inspect.isclass(getattr(module, name))):
                    found[f"{target}.{name}"] = getattr(module, name)
    for name, obj in list(found.items()):
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            for member, value in vars(obj).items():
                function = value.__func__ if isinstance(value, (classmethod, staticmethod)) else value
                if not member.startswith("_") and (inspect.isfunction(function) or isinstance(value, property)):
                    found[f"{name}.{member}"] = value if isinstance(value, property) else function
    return found


def sections(doc: str) -> dict[str, list[str]]:
    """{numpy-style section: the names its entries define} of a docstring."""
    doc = inspect.cleandoc(doc or "")
    return {title: [n.strip("*") for entry in ENTRY.findall(body) for n in entry.split(", ")] for title, body in SECTION.findall(doc)}


def _returns_a_value(function) -> bool:
    annotation = inspect.signature(function).return_annotation
    if annotation is not inspect.Signature.empty:
        return annotation not in (None, "None")
    tree = ast.parse(textwrap.dedent(inspect.getsource(function))).body[0]
    nested = {
        id(n) for node in ast.walk(tree) if node is not tree and isinstance(node, (ast.FunctionDef, ast.Lambda)) for n in ast.walk(node)
    }
    return any(isinstance(n, ast.Return) and n.value is not None and id(n) not in nested for n in ast.walk(tree))


def _field_comments(cls) -> list[str]:
    """The fields of a class that also carry a ``#:`` comment (Sphinx would show them a second time)."""
    analyzer = ModuleAnalyzer.for_module(cls.__module__)
    return [name for (scope, name) in analyzer.find_attr_docs() if scope == cls.__qualname__]


def problems(obj) -> list[str]:
    """What the docstring of a public callable (or the one line of a property) lacks."""
    if isinstance(obj, property):
        return [] if (obj.__doc__ or "").strip() else ["a property without a docstring (it would not be shown)"]
    found = sections(obj.__doc__)
    if inspect.isclass(obj):
        if issubclass(obj, (BaseException, enum.Enum)):
            return []
        if dataclasses.is_dataclass(obj) or hasattr(obj, "_fields"):
            fields = [f.name for f in dataclasses.fields(obj)] if dataclasses.is_dataclass(obj) else list(obj._fields)
            listed = found.get("Attributes", []) + found.get("Parameters", [])
            twice = [f"field {name} has a #: comment besides its entry" for name in _field_comments(obj)]
            return [f"field {field} is not under Attributes or Parameters" for field in fields if field not in listed] + twice
        function = obj.__init__
    else:
        function = obj
    arguments = [p.name for p in inspect.signature(function).parameters.values() if p.name not in ("self", "cls")]
    missing = [f"argument {name} is not under Parameters" for name in arguments if name not in found.get("Parameters", [])]
    if not inspect.isclass(obj) and _returns_a_value(function) and not {"Returns", "Yields"} & found.keys():
        missing.append("no Returns section")
    return missing


def test_every_public_callable_documents_its_parameters_and_returns():
    public = documented()
    assert {
        "fricgen.load_law",
        "fricgen.langevin.Simulation",
        "fricgen.derive.derive_noise",
        "fricgen.langevin.Simulation.run",
    } <= public.keys()
    lacking = {name: problem for name, obj in public.items() if (problem := problems(obj))}
    assert not lacking, f"{len(lacking)} of {len(public)} public callables lack docs:\n" + "\n".join(
        f"{n}: {p}" for n, p in lacking.items()
    )


def test_the_check_sees_what_is_missing():
    def speed(v, *, m=1.0):
        """The speed.

        Parameters
        ----------
        v : float
            Velocity [sigma/t0].
        """
        return abs(v)

    @dataclasses.dataclass
    class Box:
        """A box.

        Attributes
        ----------
        length : float
            [sigma]
        """

        length: float
        height: float

    assert problems(speed) == ["argument m is not under Parameters", "no Returns section"]
    assert problems(Box) == ["field height is not under Attributes or Parameters"]
    assert problems(_Twice) == ["field length has a #: comment besides its entry"]
    assert problems(property(lambda self: 1.0)) == ["a property without a docstring (it would not be shown)"]


@dataclasses.dataclass
class _Twice:
    """A field documented twice (a negative control of the check).

    Attributes
    ----------
    length : float
        [sigma]
    """

    #: The length [sigma].
    length: float


EXAMPLES = sorted({obj.__module__ for obj in documented().values() if not isinstance(obj, property)})
#: The entry points whose docstrings must show an example.
ENTRY_POINTS = ("fricgen.load_law", "fricgen.langevin.Simulation", "fricgen.derive.derive_noise", "fricgen.derive.generate")


def test_the_entry_points_show_an_example():
    public = documented()
    assert [name for name in ENTRY_POINTS if "Examples" not in sections(public[name].__doc__)] == []


@pytest.mark.parametrize("module", EXAMPLES)
def test_the_examples_of_the_docstrings_run(module, tmp_path, monkeypatch):
    """Each ``>>>`` example of a documented module runs, in a fresh folder, and prints what it shows."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("FRICGEN_LAWS", raising=False)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    report = io.StringIO()
    for test in doctest.DocTestFinder().find(importlib.import_module(module)):
        runner.run(test, out=report.write)
    assert runner.failures == 0, report.getvalue()[-6000:]
