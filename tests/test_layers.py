"""The architecture, enforced: data flows one way between the layers, and the code stays small.

Layers: derive (SymPy) -> generated (emitted kernels) -> fricgen's kernel layer (kernels, rng,
schema, errors) -> the engines (fricgen.langevin, fricgen.rods) -> the application (fricgen.app).
"""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
KERNEL_LAYER = {"fricgen.kernels", "fricgen.rng", "fricgen.schema", "fricgen.errors"}
ENGINES = ("fricgen.langevin", "fricgen.rods")
#: What an engine may import from derive: the plain-data modules, no SymPy.
DERIVE_DATA = {"derive.calculus", "derive.lawdata", "derive.catalogues", "derive.errors"}


def _modules_after(statement):
    code = f"import sys; {statement}; print(' '.join(sorted(sys.modules)))"
    return set(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split())


def _module_name(path: Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


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
    return [path for package in packages for path in sorted((ROOT / package.replace(".", "/")).rglob("*.py"))]


def _ours(names):
    """The imported names that are modules of this repository."""
    return {n for n in names if n.split(".")[0] in ("fricgen", "derive", "generated") and _is_module(n)}


def _is_module(name):
    path = ROOT / name.replace(".", "/")
    return path.with_suffix(".py").exists() or (path / "__init__.py").exists()


def test_import_fricgen_leaves_sympy_out():
    statement = (
        "import fricgen, fricgen.app.cli, fricgen.langevin, fricgen.rods, fricgen.kernels; fricgen.kernels.load_law_kernels('linear')"
    )
    assert "sympy" not in _modules_after(statement)


def test_derive_does_not_import_the_runtime():
    loaded = _modules_after("import derive")
    assert not {"fricgen", "numba"} & loaded


@pytest.mark.parametrize("path", _files(*ENGINES), ids=lambda p: str(p.relative_to(ROOT)))
def test_engines_import_only_the_kernel_layer(path):
    """An engine imports its own package, the kernel layer and derive's plain data: never the other
    engine, the application, the symbolic layer's SymPy modules or SymPy itself."""
    own = _module_name(path).split(".")[:2]
    allowed = KERNEL_LAYER | DERIVE_DATA
    imported = _imports(path)
    assert "sympy" not in {n.split(".")[0] for n in imported}
    bad = {n for n in _ours(imported) if n.split(".")[:2] != own and n not in allowed and n != "fricgen"}
    assert not bad, f"{path.name} imports {sorted(bad)}"


@pytest.mark.parametrize("name", sorted(KERNEL_LAYER))
def test_the_kernel_layer_imports_no_engine(name):
    """The kernel layer reaches derive's plain data and generated/ (the loader), nothing above it."""
    path = ROOT / (name.replace(".", "/") + ".py")
    bad = {n for n in _ours(_imports(path)) if n not in KERNEL_LAYER | DERIVE_DATA and not n.startswith("generated")}
    assert not bad, f"{path.name} imports {sorted(bad)}"


@pytest.mark.parametrize("path", _files("generated"), ids=lambda p: str(p.relative_to(ROOT)))
def test_generated_code_imports_only_math_numpy_numba(path):
    roots = {n.split(".")[0] for n in _imports(path)}
    assert roots <= {"math", "numpy", "numba", "generated"}, roots


@pytest.mark.parametrize("path", [p for p in _files("derive") if "kernel_sources" not in p.parts], ids=lambda p: str(p.relative_to(ROOT)))
def test_derive_never_imports_the_runtime(path):
    """(derive/kernel_sources/ holds code that the generator copies into generated/, not derive's own.)"""
    roots = {n.split(".")[0] for n in _imports(path)}
    assert not roots & {"fricgen", "numba", "generated"}, roots


HAND_WRITTEN = _files("fricgen", "derive")


@pytest.mark.parametrize("path", HAND_WRITTEN, ids=lambda p: str(p.relative_to(ROOT)))
def test_modules_stay_small_and_calls_short(path):
    """No module over 400 lines, no function with more than 10 parameters."""
    source = path.read_text()
    assert source.count("\n") <= 400, f"{path.name}: {source.count(chr(10))} lines"
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            count = len(node.args.posonlyargs) + len(node.args.args) + len(node.args.kwonlyargs)
            assert count <= 10, f"{path.name}: {node.name} takes {count} parameters"
