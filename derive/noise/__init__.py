"""Stage 2, the noise and its proof: D(u, r) for a calculus, and why it is right.

Modules: ``derivation`` (:func:`derive_noise`: D from the zero-current ODE, F-20..22), ``phase_space``
(the pair's momenta, masses and normal), ``modes`` (each contact mode, sliding among them: its map
C_m, forces, noise and mobility mu_m), ``mode_proofs`` (the one proof path: the current of each
calculus on the pair phase space, F-47..50, and the facts of each mode), ``lemma_cache`` (those
law-independent facts, proven once and cached), ``reference`` (D evaluated independently by
mpmath), ``verification`` (:func:`prove`: the symbolic facts of one model), ``contact`` (a pair with
one law per mode). Imports the law stage, never a backend.
"""
