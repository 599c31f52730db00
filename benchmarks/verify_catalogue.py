"""Benchmark: time to derive and verify every catalogue law for all three calculi.

Target (issue 2): the whole catalogue, all calculi, under 60 s on the 2-core machine.
Prints the one-off phase-space lemmas (per dimension and calculus) apart from the per-law work.
Run: python benchmarks/verify_catalogue.py
"""

from __future__ import annotations

import time

from derive import catalogue, derive_noise, verify
from derive.phase_space import covariance_identities, zero_current_lemma


def main() -> None:
    start = time.perf_counter()
    print("phase-space lemmas (once per process):")
    for dim in (3, 2):
        t = time.perf_counter()
        covariance_identities(dim)
        print(f"  covariance {dim}-D            {time.perf_counter() - t:7.2f} s")
        for calculus in ("ito", "stratonovich", "hk"):
            t = time.perf_counter()
            holds = zero_current_lemma(dim, calculus)
            print(f"  zero current {dim}-D {calculus:13s} {time.perf_counter() - t:6.2f} s  holds={holds}")
    print("per law and calculus (derive + verify):")
    for name, law in catalogue().items():
        for calculus in ("ito", "stratonovich", "hk"):
            t = time.perf_counter()
            report = verify(derive_noise(law, calculus))
            status = "verified" if report.verified else "not verified" + ("" if calculus in law.calculi else " (excluded by the law)")
            print(f"  {name:16s} {calculus:13s} {time.perf_counter() - t:6.2f} s  {status}")
    total = time.perf_counter() - start
    print(f"total {total:.1f} s (target < 60 s): {'OK' if total < 60 else 'SLOW'}")


if __name__ == "__main__":
    main()
