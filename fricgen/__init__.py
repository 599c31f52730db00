"""fricgen: thermodynamically consistent frictional contacts, derived symbolically.

The runtime package, in layers (docs/physics.md explains the physics they follow); each
subpackage's ``__init__`` is its public API:

- ``fricgen.derive``: the symbolic layer (SymPy): laws, their noise and its proof, the code generators;
- ``fricgen.generated``: the code that fricgen.derive emitted for the built-in laws and potentials;
- ``fricgen.kernels``: the one loader of generated kernels and their types (the kernel ABI);
- ``fricgen.rng``: counter-based random numbers and the one registry of noise streams;
- ``fricgen.schema``, ``fricgen.errors``: typed configuration sections, one error family;
- ``fricgen.langevin``: the Langevin engine of frictional spheres (2-D and 3-D);
- ``fricgen.rods``: Brownian cluster dynamics of rods, with the exact theory;
- ``fricgen.app``: the ``fricgen`` command line, runs, sweeps and studies (the demo, the thermostat check).

The engines import only the kernel layer, the RNG, schema/errors and derive's plain-data modules
(``fricgen.derive.calculus``, ``fricgen.derive.law.lawdata``); never each other, the application or SymPy
(tests/test_layers.py). ``import fricgen`` itself loads nothing but the error family
(:func:`load_law` and :class:`LawKernels` are loaded on first use) and changes nothing: the compiled
layers set Numba up when the first of them is imported (:mod:`fricgen.compiled`: TBB, the thread
count, stale caches).
"""

from .errors import ConfigError, FricgenError, KernelError, SimulationError
from .lazy import on_first_use

__version__ = "0.1.0"

__all__ = ["ConfigError", "FricgenError", "KernelError", "LawKernels", "SimulationError", "__version__", "load_law"]

#: The names most used in a notebook, loaded on first use (``import fricgen`` stays light).
__getattr__, __dir__ = on_first_use(__name__, {"fricgen.kernels": ("LawKernels", "load_law")})
