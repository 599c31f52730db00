"""fricgen: thermodynamically consistent frictional contacts, derived symbolically.

The runtime package. It does not import SymPy at import time; the symbolic layer lives in
``derive`` and is reached only by the commands that derive or verify (``fricgen verify``).
"""

__version__ = "0.1.0"
