"""The contact law of a simulation, resolved and checked once: each contact mode's kernels and parameters.

A run's ``[law]`` section names up to three laws (``name``, ``rolling``, ``spinning``); each acts on the
contact mode its file says (sliding, rolling or spinning; docs/physics-modes.md). :func:`bind` checks
the kernels handed for those names against the section, once: one law per mode, each on a mode the
dimension has, each with the run's calculus, each parameter within the law's range. The result,
:class:`ContactLaw`, is what the engine takes (:class:`~fricgen.langevin.simulation.Simulation`); it
looks nothing up. Names are resolved into kernels at the edges (the command line, a run file,
``fricgen.load_law`` in a notebook), never here.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from ..errors import ConfigError
from ..kernels import LawKernels
from .config import Law

#: The keys of [law] that name a law, with the keys of their parameter overrides and the mode a key
#: requires (None: the law's own).
LAW_KEYS = (("name", "parameters", None), ("rolling", "rolling_parameters", "rolling"), ("spinning", "spinning_parameters", "spinning"))


@dataclass(frozen=True)
class ModeLaw:
    """One law of a contact.

    Attributes
    ----------
    kernels : LawKernels
        Its kernels.
    parameters : mapping of str to float
        Its parameter overrides, checked against the law's ranges.
    key : str
        The key of ``[law]`` that named it (``name``, ``rolling`` or ``spinning``).
    """

    kernels: LawKernels
    parameters: Mapping[str, float]
    key: str

    def record(self) -> list[str]:
        """What a file on disk keeps of the law (checked when it is read back).

        Returns
        -------
        list of str
            [name, law file, hash].
        """
        return [self.kernels.name, str(self.kernels.path or ""), self.kernels.source_hash]


@dataclass(frozen=True)
class ContactLaw:
    """The laws of a pair's contact modes, resolved and checked (:func:`bind`).

    Attributes
    ----------
    calculus : str
        The calculus of every law's noise ('ito', 'stratonovich', 'hk').
    laws : tuple of ModeLaw
        The laws in the order of ``[law]`` (``name`` first).
    """

    calculus: str
    laws: tuple[ModeLaw, ...]

    @property
    def modes(self) -> dict[str, ModeLaw]:
        """The laws by the contact mode each acts on."""
        return {law.kernels.mode: law for law in self.laws}

    @property
    def names(self) -> list[str]:
        """The laws' names, in the order of ``[law]``."""
        return [law.kernels.name for law in self.laws]

    @property
    def first(self) -> ModeLaw:
        """The law of ``law.name``."""
        return self.laws[0]


def named_keys(section: Law) -> list[tuple[str, str, str | None]]:
    """The rows of :data:`LAW_KEYS` whose key names a law in ``section`` (``name`` always), in order."""
    return [(key, params, mode) for key, params, mode in LAW_KEYS if key == "name" or getattr(section, key) is not None]


def law_names(section: Law) -> list[str]:
    """The names of the laws of a ``[law]`` section.

    Parameters
    ----------
    section : Law
        The section.

    Returns
    -------
    list of str
        ``name``, then ``rolling`` and ``spinning`` where given.
    """
    return [getattr(section, key) for key, _, _ in named_keys(section)]


def bind(section: Law, kernels: LawKernels | Sequence[LawKernels], dim: int) -> ContactLaw:
    """The contact law of a ``[law]`` section from the kernels of its laws, checked once.

    Parameters
    ----------
    section : Law
        The ``[law]`` section.
    kernels : LawKernels or sequence of LawKernels
        The kernels of its laws: ``name``, then ``rolling`` and ``spinning`` where given, in this order.
    dim : int
        The dimension of the pairs, 2 or 3.

    Returns
    -------
    ContactLaw
        The bound laws.

    Raises
    ------
    ConfigError
        Naming the key, for kernels of other laws than the section names, a law on another mode than
        its key says, two laws on one mode, a mode the pair does not have (spinning in 2-D), a
        calculus a law lacks or a parameter out of its law's range.

    Examples
    --------
    >>> import fricgen
    >>> from fricgen.langevin import Law
    >>> from fricgen.langevin.contact_law import bind
    >>> bind(Law(name="coulomb_newton"), fricgen.load_law("coulomb_newton"), dim=3).names
    ['coulomb_newton']
    """
    handed = [kernels] if isinstance(kernels, LawKernels) else list(kernels)
    named, names = named_keys(section), law_names(section)
    if [k.name for k in handed] != names:
        if len(names) == len(handed) == 1:
            given = f"is {names[0]!r}, but the kernels handed to the simulation are those of {handed[0].name!r}"
        else:
            given = f"names the laws {names}, but the kernels handed to the simulation are those of {[k.name for k in handed]}"
        raise ConfigError("law.name", given, "give one law per name")
    found: dict[str, ModeLaw] = {}
    for (key, params, mode), law in zip(named, handed, strict=True):
        acts = law.mode
        if mode is not None and acts != mode:
            problem = f"law {law.name} acts on the {acts} mode, not {mode}"
            raise ConfigError(f"law.{key}", problem, f'name a law whose file says mode = "{mode}"')
        if acts in found:
            other = found[acts]
            problem = f"a second law for the {acts} mode ({other.key} names {other.kernels.name})"
            raise ConfigError(f"law.{key}", problem, "one law per mode")
        if acts == "spinning" and dim == 2:
            raise ConfigError(f"law.{key}", f"law {law.name} acts on spinning, which does not exist in 2-D", "remove it, or run in 3-D")
        if section.calculus not in law.calculi:
            problem, fix = f"law {law.name} has no {section.calculus!r} noise", f"choose a calculus of {list(law.calculi)}"
            raise ConfigError("law.calculus" if key == "name" else f"law.{key}", problem, fix)
        overrides = dict(getattr(section, params))
        try:
            law.parameters(**overrides)
        except ConfigError as error:
            raise ConfigError(error.key.replace("law.parameters", f"law.{params}", 1), error.problem, error.fix) from None
        found[acts] = ModeLaw(law, overrides, f"law.{key}")
    return ContactLaw(section.calculus, tuple(found.values()))


__all__ = ["ContactLaw", "ModeLaw", "bind", "law_names"]
