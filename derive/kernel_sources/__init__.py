"""Numerical kernels written by hand that the emitter copies into ``generated/`` (never imported here)."""
