"""Stage 2, the noise and its proof: D(u, r) for a calculus, and why it is right.

Modules: ``derivation`` (:func:`derive_noise`: D from the zero-current ODE, F-20..22), ``phase_space``
(the current of each calculus on the pair phase space, F-47..50), ``lemma_cache`` (the law-independent
lemma, proven once and cached), ``reference`` (D evaluated independently by mpmath), ``verification``
(:func:`prove`: the symbolic facts of one model). Imports the law stage, never a backend.
"""
