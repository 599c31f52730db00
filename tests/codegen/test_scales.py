"""The built-in laws' printed noise kernels hold their accuracy at the edges of the scales a run may
take (fricgen.schema.SCALES: kT and the contact mobility mu from 1e-6 to 1e6), not only at the scales
of order one that verify checks: D against mpmath at u = 0 and 1e-6 ... 1e3 sqrt(a), with the noise
tables where the law has them."""

from __future__ import annotations

import pytest

from fricgen.derive import catalogue
from fricgen.derive.backends.numba_kernels.accuracy import KERNEL_TOLERANCE, kernel_accuracy
from fricgen.derive.noise.derivation import derive_noise
from fricgen.derive.noise.reference import reference_points
from fricgen.schema import SCALES

#: (kT, mu, w, r, factor on the parameters): the four corners of SCALES for kT and mu.
CORNERS = tuple((temperature, mobility, 1.0, 1.0, 1.0) for temperature in SCALES for mobility in SCALES)
LAWS = catalogue()


@pytest.mark.parametrize(("name", "calculus"), [(name, c) for name, law in sorted(LAWS.items()) for c in law.calculi])
def test_noise_kernels_hold_their_accuracy_at_the_edges_of_the_scales(name, calculus):
    model = derive_noise(LAWS[name], calculus)
    points = reference_points(model, model.variance_scale, CORNERS)
    assert len({p.case for p in points}) == len(CORNERS) and all(p.exact is not None for p in points)
    worst, where = kernel_accuracy(model, points)
    assert worst <= KERNEL_TOLERANCE, f"{name} ({calculus}): relative error {worst:.2e} at {where}"
