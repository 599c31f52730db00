"""The driver: law -> model -> proof -> backend emit -> backend check, read top to bottom.

Each stage takes the previous stage's frozen result, so a notebook can stop at any of them::

    law = load_law(path)                     # stage 1, fricgen.derive.law: the law as data
    model = derive_noise(law, "ito")         # stage 2, fricgen.derive.noise: D(u, w, r) ...
    report = verify(model)                   # ... its proof, and the Numba kernel's accuracy check
    generate([law.name])                     # stage 3, the Numba backend: modules in generated/

:func:`verify` is the proof (:func:`fricgen.derive.noise.verification.prove`) plus the check of the
printed Numba kernel against the proof's reference values (``kernel_accuracy``: relative error below
1e-10 against mpmath, :mod:`fricgen.derive.backends.numba_kernels.accuracy`). :func:`generate` derives,
verifies and writes, for a user's law folder DIR into DIR/generated/ (without the potentials, which
are built-in only; see fricgen.derive.law.catalogues)::

    generated/__init__.py
    generated/special.py              erfcx, expm1_given_exp (derive/backends/special_functions/special.py)
    generated/laws/<law>.py           weight, friction, friction_over_u, and per calculus
                                      noise_amplitude_<c>, noise_sqrt_<c>, contact_<c>
    generated/potentials/<name>.py    energy, force; external potentials U(x) also force_field

Kernel signatures are uniform so that engines can use any law: ``friction(u, w, r, params)`` and
``noise_amplitude_<c>(u, w, r, mu, kT, params)`` with params the parameter values in the order of the
module's ``PARAMETERS`` (their admissible ranges in ``RANGES``: (lower, upper, lower closed, upper
closed) each). Files are rewritten only when their content changes (Numba's cache is keyed on the
file's timestamp), atomically (a temporary file, then ``os.replace``). A law's kernels carry the hash
of the bytes its law was read from (``FrictionLaw.source_hash``): a law file edited during a
generation leaves kernels that the loader refuses as stale. The LAMMPS backend has its own driver
step, :func:`fricgen.derive.backends.lammps_plugin.module.plugin_files`, fed by :func:`verified_models`.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass
from pathlib import Path

from .backends.numba_kernels.accuracy import KERNEL_TOLERANCE, kernel_accuracy
from .backends.numba_kernels.kernel_code import CONTACT_SIGNATURE, DECORATOR, SIGNATURES
from .backends.numba_kernels.modules import law_module, package_module, potential_module, special_module
from .errors import DeriveError
from .law import potentials
from .law.catalogues import GENERATED, generate_command, is_built_in, kernel_folder, source_checkout
from .law.expressions import time_limit
from .law.lawdata import CATALOGUE, write_text_atomic
from .law.lawdata import POTENTIALS as POTENTIALS_SOURCE
from .law.laws import FrictionLaw, load_law
from .law.potentials import EXTERNAL_POTENTIALS, PAIR_POTENTIALS, check_external
from .noise.derivation import NoiseModel, derive_noise
from .noise.verification import Report, prove

#: Wall-time limit (seconds) of the derivation and verification of one law in one calculus: SymPy's
#: cost grows steeply with f (a polynomial of degree 30 takes minutes), and no size limit bounds it.
DERIVATION_TIME_LIMIT = 600.0


class GenerationError(DeriveError, RuntimeError):
    """A model that failed verification: nothing is emitted for its law."""

    exit_status = 1


@dataclass(frozen=True)
class Written:
    """A file the generator wrote, kept or removed."""

    path: Path
    status: str  # "written", "unchanged" or "removed"


def verify(model: NoiseModel) -> Report:
    """The proof of ``model`` and the accuracy check of its printed Numba kernel, in one report
    (``kernel_accuracy``, with ``details["kernel_max_rel_error"]``); never raises for a wrong amplitude."""
    start = time.perf_counter()
    proof = prove(model)
    error, where = kernel_accuracy(model, list(proof.reference_points))
    checks = {**proof.checks, "kernel_accuracy": error <= KERNEL_TOLERANCE}
    details = {**proof.details, "kernel_max_rel_error": f"{error:.2e}"}
    if not checks["kernel_accuracy"]:
        details["kernel_accuracy"] = f"relative error {error:.2e} > {KERNEL_TOLERANCE:.0e} at {where}"
    return dataclasses.replace(proof, checks=checks, details=details, seconds=proof.seconds + time.perf_counter() - start)


# --- files ---------------------------------------------------------------------------------------


def write_if_changed(path: Path, text: str) -> Written:
    """Write ``text`` atomically unless the file already holds exactly that (keeps Numba's cache valid)."""
    if path.exists() and path.read_bytes() == text.encode():
        return Written(path, "unchanged")
    path.parent.mkdir(parents=True, exist_ok=True)
    write_text_atomic(path, text)
    return Written(path, "written")


def verified_models(law: FrictionLaw, seconds: float | None = DERIVATION_TIME_LIMIT) -> tuple[dict[str, NoiseModel], list[Report]]:
    """Derive and verify the law for each of its calculi, each within ``seconds`` (None: no limit);
    raise GenerationError on any failure."""
    models, reports = {}, []
    for c in law.calculi:
        slow = GenerationError(f"law {law.name} ({c}): derivation and verification took over {seconds} s: nothing emitted")
        with time_limit(seconds, slow):
            model = derive_noise(law, c)
            report = verify(model)
        reports.append(report)
        if not report.verified:
            failed = [k for k, v in report.checks.items() if not v]
            raise GenerationError(f"law {law.name} ({c}) failed verification {failed} {report.details}: nothing emitted")
        models[c] = model
    return models, reports


def generate(names: list[str] | None = None, catalogue: Path = CATALOGUE, output: Path | None = None) -> tuple[list[Written], list[Report]]:
    """Derive, verify and emit laws of the catalogue (all by default) and helpers into ``output``, by
    default the catalogue's kernel folder (the package's generated/, or DIR/generated for a user's law
    folder DIR); the potentials with the built-in catalogue only.

    Idempotent: unchanged files are not touched. With ``names`` None, modules of laws no longer
    in the catalogue are removed.
    """
    catalogue, built_in = Path(catalogue), is_built_in(catalogue)
    if built_in and output is None and not source_checkout():
        raise DeriveError(
            f"the built-in laws' kernels belong to the installed package ({GENERATED}), which fricgen never writes to: they are"
            " regenerated in a source checkout (pip install -e .). For a law of your own, or a changed copy of a built-in one,"
            f" put its file in a folder of yours (a copy of a built-in law under a new name) and run `fricgen generate --laws DIR`"
            f" (the built-in law files are in {CATALOGUE})"
        )
    output = kernel_folder(catalogue) if output is None else Path(output)
    if POTENTIALS_SOURCE.read_bytes() != potentials.SOURCE:
        raise GenerationError(
            f"{POTENTIALS_SOURCE} changed since fricgen.derive.law.potentials was imported: the potentials and the weights of laws would be"
            " emitted from the old version; run `fricgen generate` in a new Python process"
        )
    available = sorted(p.stem for p in catalogue.glob("*.toml"))
    unknown = sorted(set(names or ()) - set(available))
    if unknown:
        raise GenerationError(f"unknown law(s) {unknown}; the catalogue {catalogue} has {available}")
    written = [
        write_if_changed(
            output / "__init__.py", package_module("Emitted code only: every module here is written by fricgen.derive, never by hand.\n")
        ),
        write_if_changed(output / "special.py", special_module()),
        write_if_changed(output / "laws" / "__init__.py", package_module("Kernels of the friction laws, one module per law.\n")),
    ]
    if built_in:
        written += _emit_potentials(output)
    reports = []
    for name in names or available:
        path = catalogue / f"{name}.toml"
        law = load_law(path)
        models, law_reports = verified_models(law)
        reports += law_reports
        source = f"derive/law/catalogue/{name}.toml" if built_in else f"{catalogue.resolve().name}/{name}.toml"
        text = law_module(law, models, law.source_hash, source, generate_command(name, catalogue))
        written.append(write_if_changed(output / "laws" / f"{name}.py", text))
    if names is None:
        for orphan in sorted((output / "laws").glob("*.py")):
            if orphan.stem != "__init__" and orphan.stem not in available:
                orphan.unlink()
                written.append(Written(orphan, "removed"))
    return written, reports


def _emit_potentials(output: Path) -> list[Written]:
    """The package of the potentials' kernels (external ones checked periodic first)."""
    for potential in EXTERNAL_POTENTIALS.values():
        try:
            check_external(potential)
        except ValueError as error:
            raise GenerationError(f"{error}: nothing emitted") from error
    written = [write_if_changed(output / "potentials" / "__init__.py", package_module("Kernels of the conservative potentials.\n"))]
    for potential in {**PAIR_POTENTIALS, **EXTERNAL_POTENTIALS}.values():
        written.append(write_if_changed(output / "potentials" / f"{potential.name}.py", potential_module(potential)))
    return written


__all__ = [
    "CONTACT_SIGNATURE",
    "DECORATOR",
    "GENERATED",
    "SIGNATURES",
    "GenerationError",
    "Written",
    "generate",
    "verified_models",
    "verify",
    "law_module",
    "potential_module",
    "write_if_changed",
]
