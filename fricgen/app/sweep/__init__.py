"""A grid of runs as Dask tasks (``fricgen sweep``): ``config`` (the sweep file), ``runner`` (check,
run what is missing, gather), ``task`` (one point in a child process), ``results`` (table and figure)."""
