"""A run of a TOML file (``fricgen run``): ``config``, ``build``, ``runner``, ``observables``, ``progress``,
``outputs``, ``registry`` (the studies of a kind of run) and ``examples/`` (bundled configurations)."""
