"""The Numba backend: ``kernel_code`` (pieces of kernel text, the kernel ABI's signatures), ``modules``
(the text of each generated module), ``accuracy`` (the printed kernels run as Python against mpmath)."""
