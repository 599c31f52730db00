"""The architecture, enforced: data flows one way between the layers, and the code stays small.

Layers: fricgen.derive (SymPy) -> fricgen.generated (emitted kernels) -> fricgen's kernel layer
(kernels, rng, schema, errors, compiled, accuracy) -> the engines (fricgen.langevin, fricgen.rods) -> the application
(fricgen.app). Inside fricgen.derive, the stages: law -> noise (derivation and proof) -> backends
(one per target, sharing the printing and the special functions) -> the driver.

The repository keeps derive/ and generated/ at the top; they install as fricgen.derive and
fricgen.generated (pyproject.toml's package-dir), which is how module names are formed here.
"""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
KERNEL_LAYER = {
    "fricgen.kernels",
    "fricgen.law_kernels",
    "fricgen.rng",
    "fricgen.schema",
    "fricgen.errors",
    "fricgen.lazy",
    "fricgen.compiled",
    "fricgen.accuracy",
}
ENGINES = ("fricgen.langevin", "fricgen.rods")
#: The modules that compile an engine when imported (on a cold cache about 200 s for the Langevin engine, 40 s for BCD).
COMPILING = ("fricgen.langevin.integrator", "fricgen.langevin.simulation", "fricgen.rods.bcd", "fricgen.rods.simulation")
#: What an engine may import from derive: the plain-data modules, no SymPy.
DERIVE_DATA = {
    "fricgen.derive.calculus",
    "fricgen.derive.law.lawdata",
    "fricgen.derive.law.catalogues",
    "fricgen.derive.law.manifests",
    "fricgen.derive.errors",
}


def _modules_after(statement):
    code = f"import sys; {statement}; print(' '.join(sorted(sys.modules)))"
    return set(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split())


#: Folders of the repository and the packages they install as.
PACKAGE_DIRS = {"fricgen": "fricgen", "derive": "fricgen.derive", "generated": "fricgen.generated"}


def _module_name(path: Path) -> str:
    top, *parts = path.relative_to(ROOT).with_suffix("").parts
    parts = [*PACKAGE_DIRS[top].split("."), *parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _path(name: str) -> Path:
    """The repository path (without suffix) of the module or package ``name``."""
    for top, package in sorted(PACKAGE_DIRS.items(), key=lambda item: -len(item[1])):
        if name == package or name.startswith(package + "."):
            return ROOT / top / name.removeprefix(package).lstrip(".").replace(".", "/")
    return ROOT / name.replace(".", "/")


def _imports(path: Path) -> set[str]:
    """Absolute names of the modules that a file imports (relative imports resolved)."""
    package = _module_name(path).split(".")
    if path.name != "__init__.py":
        package = package[:-1]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = package[: len(package) - node.level + 1] if node.level else []
            module = ".".join([*base, *(node.module.split(".") if node.module else [])])
            found.add(module)
            found |= {f"{module}.{alias.name}" for alias in node.names}  # from package import module
    return found


def _files(*packages):
    return [path for package in packages for path in sorted(_path(package).rglob("*.py"))]


def _ours(names):
    """The imported names that are modules of this repository."""
    return {n for n in names if n.split(".")[0] == "fricgen" and _is_module(n)}


def _is_module(name):
    path = _path(name)
    return path.with_suffix(".py").exists() or (path / "__init__.py").exists()


def test_import_fricgen_leaves_sympy_out():
    statement = (
        "import fricgen, fricgen.app.cli, fricgen.langevin, fricgen.rods, fricgen.kernels; fricgen.kernels.load_law_kernels('linear')"
    )
    assert "sympy" not in _modules_after(statement)


def test_every_public_name_is_listed_before_its_engine_loads():
    """The packages' costly names load on first use (fricgen.lazy), yet dir() lists every name of __all__, as autodoc
    (the API reference) and tab completion need, without loading an engine."""
    packages = ("fricgen", "fricgen.app", "fricgen.langevin", "fricgen.rods")
    check = "m = importlib.import_module({0!r}); assert set(m.__all__) <= set(dir(m)), {0!r}"
    code = "import importlib; " + "; ".join(check.format(p) for p in packages)
    loaded = _modules_after(code)
    assert not set(COMPILING) & loaded


def test_derive_does_not_import_the_runtime():
    """(fricgen.generated itself, a docstring, is imported by importlib.resources to locate the kernels' folder.)"""
    loaded = _modules_after("import fricgen.derive; fricgen.derive.verify")
    assert not {"numba", "fricgen.kernels", "fricgen.langevin", "fricgen.rods", "fricgen.app", "fricgen.generated.special"} & loaded


def test_top_level_derive_and_generated_are_not_packages_of_the_install():
    """Installed, the repository's derive/ and generated/ exist only as fricgen.derive and
    fricgen.generated (run outside the checkout, so that its folders are not on sys.path)."""
    code = "import importlib.util as u; print(u.find_spec('derive'), u.find_spec('generated'), u.find_spec('fricgen.derive') is not None)"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT / "tests")
    assert done.stdout.split() == ["None", "None", "True"]


@pytest.mark.parametrize("path", _files(*ENGINES), ids=lambda p: str(p.relative_to(ROOT)))
def test_engines_import_only_the_kernel_layer(path):
    """An engine imports its own package, the kernel layer and derive's plain data: never the other
    engine, the application, the symbolic layer's SymPy modules or SymPy itself."""
    own = _module_name(path).split(".")[:2]
    allowed = KERNEL_LAYER | DERIVE_DATA
    imported = _imports(path)
    assert "sympy" not in {n.split(".")[0] for n in imported}
    bad = {n for n in _ours(imported) if n.split(".")[:2] != own and n not in allowed and n not in ("fricgen", "fricgen.derive")}
    assert not bad, f"{path.name} imports {sorted(bad)}"


@pytest.mark.parametrize("name", sorted(KERNEL_LAYER))
def test_the_kernel_layer_imports_no_engine(name):
    """The kernel layer reaches derive's plain data and generated/ (the loader), nothing above it."""
    path = _path(name).with_suffix(".py")
    allowed = KERNEL_LAYER | DERIVE_DATA | {"fricgen.derive"}
    bad = {n for n in _ours(_imports(path)) if n not in allowed and not n.startswith("fricgen.generated")}
    assert not bad, f"{path.name} imports {sorted(bad)}"


@pytest.mark.parametrize("path", _files("fricgen.generated"), ids=lambda p: str(p.relative_to(ROOT)))
def test_generated_code_imports_only_math_numpy_numba(path):
    imported = _imports(path)
    assert {n.split(".")[0] for n in imported} <= {"math", "numpy", "numba", "fricgen"}, imported
    assert all(n.startswith("fricgen.generated") for n in imported if n.startswith("fricgen")), imported


SPECIAL_SOURCE = ROOT / "derive" / "backends" / "special_functions" / "special.py"


@pytest.mark.parametrize("path", [p for p in _files("fricgen.derive") if p != SPECIAL_SOURCE], ids=lambda p: str(p.relative_to(ROOT)))
def test_derive_never_imports_the_runtime(path):
    """(special_functions/special.py is code that the generator copies into generated/, not derive's own.)"""
    imported = _imports(path)
    assert not {n.split(".")[0] for n in imported} & {"numba"}, imported
    outside = {n for n in _ours(imported) if not n.startswith("fricgen.derive")} - {"fricgen"}
    assert not outside, outside


#: The stages of fricgen.derive in order, and what each may import of the others.
STAGES = {
    "fricgen.derive.law": {"fricgen.derive.calculus", "fricgen.derive.errors"},
    "fricgen.derive.noise": {"fricgen.derive.calculus", "fricgen.derive.errors", "fricgen.derive.law"},
    "fricgen.derive.backends": {"fricgen.derive.calculus", "fricgen.derive.errors", "fricgen.derive.law", "fricgen.derive.noise"},
}
BACKENDS = ("fricgen.derive.backends.numba_kernels", "fricgen.derive.backends.lammps_plugin")


def _stage_files():
    return [(stage, path) for stage in STAGES for path in _files(stage) if path != SPECIAL_SOURCE]


@pytest.mark.parametrize("stage, path", _stage_files(), ids=lambda x: str(x.relative_to(ROOT)) if isinstance(x, Path) else "")
def test_derive_stages_import_only_earlier_stages(stage, path):
    """law -> noise and proof -> backends; the driver alone sees them all. So the proof imports no
    backend, and no stage imports the driver."""
    allowed = STAGES[stage] | {stage}
    found = {n for n in _ours(_imports(path)) if n.startswith("fricgen.derive.")}
    bad = {n for n in found if not any(n == a or n.startswith(a + ".") for a in allowed)}
    assert not bad, f"{path.name} imports {sorted(bad)}"


@pytest.mark.parametrize("path", [p for b in BACKENDS for p in _files(b)], ids=lambda p: str(p.relative_to(ROOT)))
def test_backends_never_import_each_other(path):
    own = _module_name(path).split(".")[:4]
    others = {b for b in BACKENDS if b.split(".") != own}
    found = {n for n in _ours(_imports(path)) if any(n == b or n.startswith(b + ".") for b in others)}
    assert not found, f"{path.name} imports {sorted(found)}"


#: The groups of fricgen.app by what a user does, and the groups each may import: cli -> sweep -> run
#: <- studies. A run imports no other group: it finds the studies of its kinds of run in run.registry.
APP_GROUPS = {
    "fricgen.app.cli": {"fricgen.app.cli", "fricgen.app.sweep", "fricgen.app.run", "fricgen.app.studies"},
    "fricgen.app.sweep": {"fricgen.app.sweep", "fricgen.app.run"},
    "fricgen.app.studies": {"fricgen.app.studies", "fricgen.app.run"},
    "fricgen.app.run": {"fricgen.app.run"},
}


@pytest.mark.parametrize("path", _files(*APP_GROUPS), ids=lambda p: str(p.relative_to(ROOT)))
def test_app_groups_import_only_the_groups_below(path):
    """No group of the application imports one above or beside it, nor fricgen.app itself (whose
    __init__ names them all); the engines never import the application (see above)."""
    group = ".".join(_module_name(path).split(".")[:3])
    found = {n for n in _ours(_imports(path)) if n == "fricgen.app" or n.startswith("fricgen.app.")}
    bad = {n for n in found if ".".join(n.split(".")[:3]) not in APP_GROUPS[group]}
    assert not bad, f"{path.name} imports {sorted(bad)}"


def test_every_kind_of_run_finds_its_study():
    """Importing any module of the application (here the runner alone) registers a study for each
    kind of run."""
    code = "import fricgen.app.run.runner as r, fricgen.app.run.config as c; print(' '.join(r.STUDIES), '|', ' '.join(c.KINDS))"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    registered, kinds = (set(part.split()) for part in done.stdout.split("|"))
    assert registered == kinds and kinds, done.stdout


HAND_WRITTEN = _files("fricgen", "fricgen.derive")


@pytest.mark.parametrize("path", HAND_WRITTEN, ids=lambda p: str(p.relative_to(ROOT)))
def test_modules_stay_small_and_calls_short(path):
    """No module over 400 lines, no function with more than 10 parameters."""
    source = path.read_text()
    assert source.count("\n") <= 400, f"{path.name}: {source.count(chr(10))} lines"
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            count = len(node.args.posonlyargs) + len(node.args.args) + len(node.args.kwonlyargs)
            assert count <= 10, f"{path.name}: {node.name} takes {count} parameters"


#: The names that resolve a law's name into kernels (a look-up on a search path of law folders).
RESOLVERS = {"load_law", "load_law_kernels", "LawSearch", "environment_search"}


@pytest.mark.parametrize("path", _files(*ENGINES), ids=lambda p: str(p.relative_to(ROOT)))
def test_engines_import_no_resolver(path):
    """An engine takes resolved laws (kernels, a ContactLaw) and looks no name up: it imports none of
    the names that resolve one."""
    tree = ast.parse(path.read_text())
    imported = {alias.name for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) for alias in node.names}
    assert not imported & RESOLVERS, f"{path.name} imports {sorted(imported & RESOLVERS)}"


#: Where FRICGEN_LAWS may be read: the command line's edge and the notebook's (fricgen.load_law).
LAW_EDGES = {ROOT / "fricgen" / "app" / "cli" / "laws.py", ROOT / "fricgen" / "kernels.py"}


@pytest.mark.parametrize("path", _files("fricgen", "fricgen.derive"), ids=lambda p: str(p.relative_to(ROOT)))
def test_no_ambient_law_state(path):
    """Law folders travel as a value (LawSearch) handed on from an edge: no context variable holds
    them, and the environment variable is read at the edges alone."""
    text = path.read_text()
    assert "ContextVar" not in text
    if path not in LAW_EDGES:
        assert "os.environ.get(LAWS_ENV" not in text and 'environ.get("FRICGEN_LAWS"' not in text, path.name
