"""Stage 1, the law: a friction law as data.

Modules: ``symbols`` (u, w, r, kT, mu, ...), ``expressions`` (the parser of law expressions: data,
never code), ``ranges`` (parameter ranges and the proof that f >= 0 over them), ``lawdata`` (law files
read as plain data, hashes; no SymPy), ``laws`` (:class:`FrictionLaw`: load, make, save), ``potentials``
(WCA, sticky, external fields), ``catalogues`` (where a law's name is looked up: user folders, then
the built-in ``catalogue/``; no SymPy). Imports no later stage.
"""
