"""The LAMMPS backend: ``code`` (kernels in C++), ``templates`` (the pair style and the plugin),
``module`` (the files of one law's plugin)."""
