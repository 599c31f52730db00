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
from .law import manifests, potentials
from .law.catalogues import GENERATED, check_law_files, generate_command, inert, is_built_in, kernel_folder, law_names, source_checkout
from .law.expressions import time_limit
from .law.law_files import load_law
from .law.lawdata import CATALOGUE, NotAFile, read_regular, write_text_atomic
from .law.lawdata import POTENTIALS as POTENTIALS_SOURCE
from .law.laws import FrictionLaw
from .law.potentials import EXTERNAL_POTENTIALS, PAIR_POTENTIALS, check_external
from .noise.contact import ContactReport, prove_contact
from .noise.derivation import NoiseModel, derive_noise
from .noise.verification import Report, prove

#: Wall-time limit (seconds) of the derivation and verification of one law in one calculus: SymPy's
#: cost grows steeply with f (a polynomial of degree 30 takes minutes), and no size limit bounds it.
DERIVATION_TIME_LIMIT = 600.0
#: The contact modes whose Numba kernels are emitted: every mode (docs/physics-modes.md). The kernels
#: are the same functions of (u, w, r, mu, kT) in each; a law module of another mode than sliding
#: states it (MODE), and the Langevin engine applies it with that mode's map C_m and mobility mu_m.
EMITTED_MODES = ("sliding", "rolling", "spinning")
#: The modes the LAMMPS plugin applies: every mode, one pair style per law (a rolling or spinning law's exerts
#: couples only; pair_style hybrid/overlay combines them, docs/guide/lammps.md).
PLUGIN_MODES = EMITTED_MODES


class GenerationError(DeriveError, RuntimeError):
    """A model that failed verification: nothing is emitted for its law."""

    exit_status = 1


@dataclass(frozen=True)
class Written:
    """A file the generator wrote, kept or removed.

    Attributes
    ----------
    path : pathlib.Path
        The file.
    status : str
        "written", "unchanged" or "removed".
    sha256 : str
        Of the text written or found (not re-read from the file: what fricgen wrote).
    """

    path: Path
    status: str  # "written", "unchanged" or "removed"
    sha256: str = ""  # of the text written or found (not re-read from the file: what fricgen wrote)


def verify(model: NoiseModel) -> Report:
    """The proof of a noise model and the accuracy check of its printed Numba kernel, in one report.

    Parameters
    ----------
    model : NoiseModel
        The noise model of one law and calculus.

    Returns
    -------
    Report
        The checks of :func:`prove` and ``kernel_accuracy`` (with ``details["kernel_max_rel_error"]``);
        never raises for a wrong amplitude.

    Examples
    --------
    >>> from fricgen.derive import derive_noise, make_law, verify
    >>> law = make_law("viscous", "gamma_f*u", parameters={"gamma_f": {"default": 2.0, "unit": "kT t0/sigma^2"}})
    >>> verify(derive_noise(law, "ito")).verified
    True
    """
    start = time.perf_counter()
    proof = prove(model)
    error, where = kernel_accuracy(model, list(proof.reference_points))
    checks = {**proof.checks, "kernel_accuracy": error <= KERNEL_TOLERANCE}
    details = {**proof.details, "kernel_max_rel_error": f"{error:.2e}"}
    if not checks["kernel_accuracy"]:
        details["kernel_accuracy"] = f"relative error {error:.2e} > {KERNEL_TOLERANCE:.0e} at {where}"
    return dataclasses.replace(proof, checks=checks, details=details, seconds=proof.seconds + time.perf_counter() - start)


def verify_contact(models: list[NoiseModel], dims: tuple[int, ...] | None = None) -> ContactReport:
    """The proof of a pair with one law per contact mode, each law verified with its kernel check.

    Parameters
    ----------
    models : list of NoiseModel
        One noise model per contact mode (sliding, rolling, spinning), of one calculus.
    dims : tuple of int, optional
        The dimensions to prove (2, 3); None: those the modes exist in.

    Returns
    -------
    ContactReport
        The checks (:func:`fricgen.derive.noise.contact.prove_contact`) with each law's :func:`verify`
        report; its ``reason`` says why a combination is refused.
    """
    return prove_contact(models, dims, verifier=verify)


# --- files ---------------------------------------------------------------------------------------


def check_not_foreign(path: Path, text: str) -> None:
    """DeriveError (one line) unless writing ``path`` replaces only what fricgen wrote there: neither
    the file nor its two folders above (DIR/generated/laws) is a symbolic link that would lead the
    write out of the folder (the package's own generated/ aside), and a file there with other content
    is a file of the same kind (its first line is the header fricgen writes) or one whose sha256
    fricgen recorded; a file of the user's (a CMakeLists.txt of their own) is never overwritten."""
    if path.absolute().parent.resolve().is_relative_to(GENERATED.resolve()):
        return
    for link in (path, path.parent, path.parent.parent):
        if link.is_symlink():
            raise DeriveError(f"{inert(str(link))} is a symbolic link: fricgen writes only into folders of its own; replace it by a folder")
    try:
        data = read_regular(path, 1 << 22)
    except (OSError, NotAFile):
        return  # missing (written fresh), or reported by the caller
    if data.split(b"\n", 1)[0] != text.encode().split(b"\n", 1)[0] and manifests.sha256(data) not in manifests.known_digests():
        raise DeriveError(
            f"{inert(str(path))} exists and was not written by fricgen: move it away (or give another folder), then run again"
        )


def check_folder_path(folder: Path) -> None:
    """DeriveError (one line) where ``folder`` or a folder above it is a file (DIR/generated a file), so
    that nothing can be written into it."""
    blocked = next((path for path in (*reversed(folder.parents), folder) if path.exists() and not path.is_dir()), None)
    if blocked is not None:
        where = f"{inert(str(blocked))} is a file, not a folder: fricgen writes into {inert(str(folder))}"
        raise DeriveError(f"{where}; move it away, then generate again")


def write_if_changed(path: Path, text: str) -> Written:
    """Write ``text`` atomically unless the file already holds exactly that (keeps Numba's cache valid).
    DeriveError (one line) where something that is not a regular file (a folder, a FIFO) is in the way,
    or a file where a folder of the path should be (DIR/generated a file)."""
    check_folder_path(path.parent)
    check_not_foreign(path, text)
    try:
        if read_regular(path, len(text.encode()) + 1) == text.encode():
            return Written(path, "unchanged", manifests.sha256(text.encode()))
    except FileNotFoundError:
        pass
    except NotAFile as error:
        raise DeriveError(f"{inert(str(path))} is {error.kind}, not a file fricgen wrote: move it away, then generate again") from None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        write_text_atomic(path, text)
    except OSError as error:
        raise DeriveError(f"cannot write {inert(str(path))}: {error.strerror or error}") from None
    return Written(path, "written", manifests.sha256(text.encode()))


def stating_mode(text: str, mode: str) -> str:
    """A law module's text with ``MODE = '<mode>'`` after its HAS_WEIGHT line, for a law on another mode than
    sliding: the engines read it (fricgen.kernels.LawKernels.mode) and apply the law with the mode's map
    and mobility. A sliding law's module is left byte for byte as it was (no MODE: sliding)."""
    if mode == "sliding":
        return text
    line = next(x for x in text.splitlines(keepends=True) if x.startswith("HAS_WEIGHT = "))
    note = f"MODE = {mode!r}  # the contact mode: u is the speed |v_m| of the {mode} velocity (docs/physics-modes.md)\n"
    return text.replace(line, line + note, 1)


def verified_models(
    law: FrictionLaw, seconds: float | None = DERIVATION_TIME_LIMIT, emitted: tuple[str, ...] = EMITTED_MODES, backend: str = "Numba"
) -> tuple[dict[str, NoiseModel], list[Report]]:
    """Derive and verify a law for each of its calculi.

    Parameters
    ----------
    law : FrictionLaw
        The law.
    seconds : float, optional
        The time limit of each calculus [s]; None: no limit.
    emitted : tuple of str
        The contact modes the backend applies.
    backend : str
        The backend's name, for the error.

    Returns
    -------
    tuple of (dict of str to NoiseModel, list of Report)
        The models by calculus and their reports.

    Raises
    ------
    GenerationError
        On any failure, or for a law on a mode that the backend does not apply (not in ``emitted``).
    """
    if law.mode not in emitted:
        raise GenerationError(
            f"law {law.name}: mode {law.mode!r}: the {backend} backend emits no kernels for it (it applies {list(emitted)});"
            f" `fricgen verify {law.name}` proves it"
        )
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
    """Derive, verify and emit the kernels of a catalogue's laws (all by default).

    They go into ``output``, by default the catalogue's kernel folder (the package's generated/, or
    DIR/generated for a user's law folder DIR); the potentials with the built-in catalogue only.
    Idempotent: unchanged files are not touched. With ``names`` None, modules of laws no longer in the
    catalogue are removed. Every law is read, derived and verified before anything is written: a law
    that is refused or fails leaves the output as it was. The sha256 of every file written or found
    unchanged is recorded in the user's cache (not for the package's own generated/), which the kernel
    loader checks before it runs any of them (docs/trust-model.md).

    Parameters
    ----------
    names : list of str, optional
        The laws to generate; None: every law of the catalogue.
    catalogue : pathlib.Path
        The law folder; the built-in catalogue by default (writable only in a source checkout).
    output : pathlib.Path, optional
        Where the kernels go; None: the catalogue's kernel folder.

    Returns
    -------
    tuple of (list of Written, list of Report)
        The files written, kept or removed, and the verification report of each law and calculus.

    Raises
    ------
    GenerationError
        If a law fails its verification; nothing is written then.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import fricgen
    >>> from fricgen.derive import generate, make_law, save_law
    >>> folder = Path(tempfile.mkdtemp())
    >>> law = make_law("viscous", "gamma_f*u", parameters={"gamma_f": {"default": 2.0, "unit": "kT t0/sigma^2"}}, calculi=["ito"])
    >>> save_law(law, folder).name
    'viscous.toml'
    >>> written, reports = generate(["viscous"], catalogue=folder)
    >>> sorted(w.path.relative_to(folder).as_posix() for w in written)[2], [r.verified for r in reports]
    ('generated/laws/viscous.py', [True])
    >>> fricgen.load_law("viscous", folder=folder).calculi
    ('ito',)
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
    check_folder_path(output / "laws")  # before any derivation
    if POTENTIALS_SOURCE.read_bytes() != potentials.SOURCE:
        raise GenerationError(
            f"{POTENTIALS_SOURCE} changed since fricgen.derive.law.potentials was imported: the potentials and the weights of laws would be"
            " emitted from the old version; run `fricgen generate` in a new Python process"
        )
    available = law_names(catalogue) if built_in or names else check_law_files(catalogue)
    unknown = sorted(set(names or ()) - set(available))
    if unknown:
        raise GenerationError(f"unknown law(s) {unknown}; the catalogue {catalogue} has {available}")
    laws = {name: load_law(catalogue / f"{name}.toml") for name in names or available}  # all read (or refused) before any is derived
    reports, texts = [], {}
    for name, law in laws.items():
        models, law_reports = verified_models(law)
        reports += law_reports
        source = f"derive/law/catalogue/{name}.toml" if built_in else f"{catalogue.resolve().name}/{name}.toml"
        texts[name] = stating_mode(law_module(law, models, law.source_hash, source, generate_command(name, catalogue)), law.mode)
    record = not (output.resolve() == GENERATED.resolve())  # the package's own kernels are trusted as installed code
    if record:
        manifests.store()  # a cache folder to record the files in, or nothing is written
    written = [
        write_if_changed(
            output / "__init__.py", package_module("Emitted code only: every module here is written by fricgen.derive, never by hand.\n")
        ),
        write_if_changed(output / "special.py", special_module()),
        write_if_changed(output / "laws" / "__init__.py", package_module("Kernels of the friction laws, one module per law.\n")),
    ]
    if built_in:
        written += _emit_potentials(output)
    written += [write_if_changed(output / "laws" / f"{name}.py", text) for name, text in texts.items()]
    if names is None:
        for orphan in sorted((output / "laws").glob("*.py")):
            if orphan.stem != "__init__" and orphan.stem not in available:
                orphan.unlink()
                written.append(Written(orphan, "removed"))
    if record:
        _record(output, written)
    return written, reports


def _record(output: Path, written: list[Written]) -> None:
    """The sha256 of every file written or found unchanged, in the manifest of ``output`` (fricgen.derive.law.manifests)."""
    kept = {item.path.relative_to(output).as_posix(): item.sha256 for item in written if item.status != "removed"}
    gone = tuple(item.path.relative_to(output).as_posix() for item in written if item.status == "removed")
    manifests.record(output, kept, gone)


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
    "EMITTED_MODES",
    "GENERATED",
    "PLUGIN_MODES",
    "SIGNATURES",
    "GenerationError",
    "Written",
    "generate",
    "verified_models",
    "verify",
    "verify_contact",
    "law_module",
    "potential_module",
    "stating_mode",
    "write_if_changed",
]
