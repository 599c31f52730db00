"""The kernel layer: the kernel ABI, and the one loader of generated kernels, refused when stale.

The ABI is the Numba function type of each kind of generated kernel (fricgen.derive.driver compiles every
kernel for exactly its type, tests/codegen/test_abi.py checks it); the engines take kernels as
first-class functions of these types, so one compiled engine serves every law and potential:

- ``SCALAR_KERNEL``: ``weight(r, params)``, a potential's ``energy(x, params)`` and ``force(x, params)``;
- ``FRICTION_KERNEL``: ``friction(u, w, r, params)``, ``friction_over_u(u, w, r, params)`` and
  ``friction_slope(u, w, r, params)`` = df/du;
- ``NOISE_KERNEL``: ``noise_amplitude_<c>(u, w, r, mu, kT, params)`` and ``noise_sqrt_<c>(...)``;
- ``CONTACT_KERNEL``: ``contact_<c>(u, w, r, mu, kT, params)`` -> ``(f/u, D)``;
- ``FIELD_KERNEL``: ``force_field(xs, params, out)`` of an external potential (out[i] = force(xs[i])).

``params`` is a contiguous float64 array. :func:`no_weight` is the weight of laws without one.

Generated kernels carry the hash of their source: a law's kernels that of its law file (and of
derive/law/potentials.py when its weight is a potential), a potential's that of derive/law/potentials.py.
If the source was edited since, loading fails with the command that regenerates them. After a
regeneration in the same process (a notebook), the module is reloaded, so the new kernels take
effect at once. SymPy is never imported here.

Kernels are code, law folders data: the built-in kernels (fricgen.generated) are trusted as
installed code; a user folder's DIR/generated/ runs only when every file of it that loading runs is,
byte for byte, what fricgen wrote there on this machine, as recorded in the user's cache
(:mod:`fricgen.derive.law.manifests`; docs/trust-model.md). A kernel edited by hand, or a file dropped
there, is refused with the command that regenerates it, before anything of the folder runs.

A law's name is looked up on a search path (:class:`~fricgen.derive.law.catalogues.LawSearch`: the user's
law folders, then the built-in catalogue) handed in by the caller; only :func:`load_law`, the notebook's
edge, reads ``FRICGEN_LAWS``. The kernels of a user folder DIR are those generated into DIR/generated/
(``fricgen generate --laws DIR LAW``); potentials are built-in only.
"""

from __future__ import annotations

import fricgen.compiled  # noqa: F401  (first: sets Numba up before anything imports it)

# isort: split

import ast
import hashlib
import importlib
import importlib.util
import os
import sys
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import numba
from numba import types

import fricgen.derive.law.manifests as manifests
from fricgen.derive.law.catalogues import BUILT_IN, LAWS_ENV, CatalogueError, LawSearch, generate_command, is_built_in, kernel_folder
from fricgen.derive.law.lawdata import LawFileError, hashed_sources, potential_source_hash, read_law_data, source_hash

from .errors import KernelError
from .law_kernels import LawKernels

# --- the kernel ABI --------------------------------------------------------------------------------

_F = types.float64
_V = types.Array(_F, 1, "C")  # float64[::1]: params, and the positions and forces of force_field

#: weight(r, params), energy(x, params), force(x, params) -> float64.
SCALAR_KERNEL = types.FunctionType(_F(_F, _V))
#: friction(u, w, r, params), friction_over_u(u, w, r, params), friction_slope(u, w, r, params) -> float64.
FRICTION_KERNEL = types.FunctionType(_F(_F, _F, _F, _V))
#: noise_amplitude_<c>(u, w, r, mu, kT, params) -> D, noise_sqrt_<c>(...) -> sqrt(D).
NOISE_KERNEL = types.FunctionType(_F(_F, _F, _F, _F, _F, _V))
#: contact_<c>(u, w, r, mu, kT, params) -> (f/u, D).
CONTACT_KERNEL = types.FunctionType(types.UniTuple(_F, 2)(_F, _F, _F, _F, _F, _V))
#: force_field(xs, params, out): out[i] = force(xs[i], params).
FIELD_KERNEL = types.FunctionType(types.void(_V, _V, _V))


@numba.njit(SCALAR_KERNEL.signature, cache=True)
def no_weight(r, params):
    """The weight w(r) = 1 of laws without a distance weight (friction acts within the potential's range).

    Parameters
    ----------
    r : float
        Centre distance [sigma] (unused).
    params : numpy.ndarray
        The law's parameter array (unused).

    Returns
    -------
    float
        1.0 [1].
    """
    return 1.0


def _import(module_name: str, missing: Callable[[], KernelError], what: str, reload: bool = False) -> ModuleType:
    """Import (or reload) a generated module. Its absence, or that of a module of its package, raises
    ``missing()``; a dependency that cannot be imported (numba not installed, a broken special.py) a
    KernelError that says so."""
    try:
        return importlib.reload(sys.modules[module_name]) if reload else importlib.import_module(module_name)
    except ModuleNotFoundError as error:
        if error.name is None or error.name.split(".")[0] == module_name.split(".")[0]:
            raise missing() from error
        raise KernelError(f"{error.name} is not installed: {what} need it ({error}); install it, e.g. pip install {error.name}") from error
    except ImportError as error:
        raise KernelError(f"cannot import {what} ({module_name}): {error}") from error


#: The files of a user's kernel folder that loading a law runs, besides its laws/<law>.py.
PACKAGE_FILES = ("__init__.py", "special.py", "laws/__init__.py")


def _user_kernels(
    catalogue: Path, name: str, missing: Callable[[], KernelError], command: str, check: Callable[[str | None], None]
) -> ModuleType:
    """The module of law ``name`` from a user folder's DIR/generated/, run only once every file it needs
    (:data:`PACKAGE_FILES` and laws/<name>.py) proved to be the bytes that fricgen wrote there
    (:func:`fricgen.derive.law.manifests.verified`): checked before any of them runs. The verified bytes
    run from their trusted copies in the user's cache, under a package name of the folder's own, with
    an empty __path__ (no other module of the folder can be imported); a module is run again when its
    bytes changed (a regeneration in the same process). Stale kernels (their SOURCE_HASH, read from
    the text, not that of the law file) are refused before they run: ``check(hash)`` raises."""
    folder = kernel_folder(catalogue)
    law_file = f"laws/{name}.py"
    blocked = next((path for path in (folder, folder / "laws") if os.path.lexists(path) and not path.is_dir()), None)
    if blocked is not None:
        raise KernelError(f"{blocked} is a file, not the folder of the kernels of law {name}: move it away, then run `{command}`")
    if not os.path.lexists(folder / law_file):
        raise missing()
    try:
        sources = manifests.verified(folder, [*PACKAGE_FILES, law_file], command)
    except manifests.UntrustedFile as error:
        raise KernelError(str(error)) from None
    check(_source_hash(sources[law_file]))
    package = "fricgen_user_laws_" + hashlib.sha256(str(folder).encode()).hexdigest()[:16]
    parts = [(package, "__init__.py"), (f"{package}.special", "special.py"), (f"{package}.laws", "laws/__init__.py")]
    for module_name, file in [*parts, (f"{package}.laws.{name}", law_file)]:
        _run_verified(module_name, folder, file, sources[file])
    return sys.modules[f"{package}.laws.{name}"]


def _source_hash(source: bytes) -> str | None:
    """The SOURCE_HASH a law module's text assigns (a string literal at module level), or None."""
    try:
        tree = ast.parse(source)
    except (SyntaxError, ValueError):
        return None
    for node in tree.body:
        if isinstance(node, ast.Assign) and [getattr(t, "id", None) for t in node.targets] == ["SOURCE_HASH"]:
            return node.value.value if isinstance(node.value, ast.Constant) and isinstance(node.value.value, str) else None
    return None


def _run_verified(module_name: str, folder: Path, file: str, source: bytes) -> ModuleType:
    digest = hashlib.sha256(source).hexdigest()
    current = sys.modules.get(module_name)
    if current is not None and getattr(current, "__fricgen_sha256__", None) == digest:
        return current
    try:
        copy = manifests.trusted_copy(folder, file, source)
    except manifests.UntrustedFile as error:
        raise KernelError(str(error)) from None
    is_package = file.endswith("__init__.py")
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader(module_name, None, origin=str(copy), is_package=is_package))
    module.__file__, module.__fricgen_sha256__ = str(copy), digest
    if is_package:
        module.__path__ = []
    sys.modules[module_name] = module
    try:
        exec(compile(source, str(copy), "exec", dont_inherit=True), module.__dict__)  # noqa: S102 - fricgen's own verified code
    except ImportError as error:
        sys.modules.pop(module_name, None)
        raise KernelError(f"cannot run the kernels of {folder / file}: {error}; install what they need, e.g. pip install numba") from error
    except BaseException:
        sys.modules.pop(module_name, None)
        raise
    parent, _, child = module_name.rpartition(".")
    if parent:
        setattr(sys.modules[parent], child, module)
    return module


def load_law_kernels(name: str, search: LawSearch = BUILT_IN) -> LawKernels:
    """The kernels of a law, from the first catalogue of a search that has it.

    Parameters
    ----------
    name : str
        The law's name.
    search : LawSearch
        Where to look: the built-in catalogue alone by default; ``LawSearch.only(folder)`` for one
        user folder, whose kernels run only if fricgen wrote them on this machine (docs/trust-model.md).

    Returns
    -------
    LawKernels
        The law's compiled kernels.

    Raises
    ------
    KernelError
        If the law is unknown, or its kernels missing, untrusted or stale (with the command that
        regenerates them).

    Examples
    --------
    >>> from fricgen.kernels import load_law_kernels
    >>> load_law_kernels("coulomb").calculi
    ('ito', 'stratonovich')
    """
    try:
        path = search.find(name)
        data = read_law_data(path)
        digest = source_hash(data)
    except (CatalogueError, LawFileError) as error:
        raise KernelError(str(error)) from error
    command = generate_command(name, path.parent)

    def missing():
        return KernelError(f"no generated kernels for law {name}: run `{command}`")

    def check(found: str | None) -> None:
        if found != digest:
            changed = hashed_sources(path, data)
            raise KernelError(f"the kernels of law {name} are stale: {changed} changed after they were generated; run `{command}`")

    if is_built_in(path.parent):
        module_name = f"fricgen.generated.laws.{name}"
        module = _import(module_name, missing, f"the kernels of law {name}")
        if module.SOURCE_HASH != digest:
            module = _import(module_name, missing, f"the kernels of law {name}", reload=True)  # regenerated since it was imported?
        check(module.SOURCE_HASH)
    else:
        module = _user_kernels(path.parent, name, missing, command, check)
        check(module.SOURCE_HASH)
    return LawKernels(name, module, path)


def load_law(name: str, folder: str | Path | None = None) -> LawKernels:
    """The compiled kernels of a friction law, resolved once, to hand to an engine.

    The notebook's edge of the law search: ``FRICGEN_LAWS`` is read here and nowhere below.

    Parameters
    ----------
    name : str
        The law's name (``<name>.toml`` in a law folder or the built-in catalogue).
    folder : str or pathlib.Path, optional
        The user's law folder that holds ``<name>.toml``, its kernels generated into
        ``folder/generated/`` by ``fricgen generate --laws folder NAME``. None looks the name up in
        the folders of ``FRICGEN_LAWS``, then in the built-in catalogue.

    Returns
    -------
    LawKernels
        The law's kernels, e.g. for ``Simulation(config, particles, state, law=law)``.

    Raises
    ------
    KernelError
        If the law is unknown, its kernels missing or stale (with the command that regenerates them).

    Examples
    --------
    >>> import fricgen
    >>> law = fricgen.load_law("stribeck")
    >>> law.parameter_names[:3], law.mode
    (('kappa_s', 'kappa_d', 'u_s'), 'sliding')
    """
    try:
        search = LawSearch.of(folder, named_by="load_law's folder") if folder is not None else LawSearch.parse(os.environ.get(LAWS_ENV, ""))
    except CatalogueError as error:
        raise KernelError(str(error)) from error
    return load_law_kernels(name, search)


def load_potential(name: str) -> ModuleType:
    """The generated module of a built-in potential.

    Parameters
    ----------
    name : str
        The potential's name in derive/law/potentials.py (e.g. ``"wca"``).

    Returns
    -------
    module
        With ``energy(x, params)`` [kT] and ``force(x, params)`` [kT/sigma] = -dU/dx, ``PARAMETERS`` and
        ``DEFAULTS``; an external potential also ``force_field(xs, params, out)``.

    Raises
    ------
    KernelError
        If the potential is unknown, or its kernels missing or stale.

    Examples
    --------
    >>> from fricgen.kernels import load_potential
    >>> wca = load_potential("wca")
    >>> import numpy as np
    >>> p = np.array(wca.DEFAULTS)  # epsilon [kT], sigma [sigma]
    >>> wca.PARAMETERS, wca.force(1.0, p), wca.energy(2.0, p)  # 24 eps/sigma at r = sigma; 0 beyond 2^(1/6) sigma
    (('epsilon', 'sigma'), 24.0, 0.0)
    """
    module_name = f"fricgen.generated.potentials.{name}"

    def missing():
        import fricgen.generated.potentials

        there = sorted(p.stem for p in Path(fricgen.generated.potentials.__file__).parent.glob("*.py") if p.stem != "__init__")
        return KernelError(f"no generated potential {name!r} (there are {there}): a new one needs `fricgen generate`")

    module = _import(module_name, missing, f"the kernels of potential {name}")
    digest = potential_source_hash(name)
    if getattr(module, "SOURCE_HASH", None) != digest:
        module = _import(module_name, missing, f"the kernels of potential {name}", reload=True)  # regenerated since it was imported?
    if getattr(module, "SOURCE_HASH", None) != digest:
        raise KernelError(
            f"the kernels of potential {name} are stale: derive/law/potentials.py changed after they were generated; run `fricgen generate`"
        )
    return module


__all__ = [
    "CONTACT_KERNEL",
    "FIELD_KERNEL",
    "FRICTION_KERNEL",
    "NOISE_KERNEL",
    "SCALAR_KERNEL",
    "KernelError",
    "LawKernels",
    "load_law",
    "load_law_kernels",
    "load_potential",
    "no_weight",
]
