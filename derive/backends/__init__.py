"""Stage 3, the backends: printed code for each target, checked against the proof's numbers.

``printing`` (the SymPy printer with the stable rewrites, shared), ``special_functions`` (erfcx and
friends, shared), ``numba_kernels`` (the modules in generated/ and their accuracy check),
``lammps_plugin`` (a LAMMPS pair style in C++). A backend imports the earlier stages and the shared
modules, never another backend (tests/test_layers.py).
"""
