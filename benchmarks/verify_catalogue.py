"""Benchmark: time to derive and verify every catalogue law for all three calculi, and to regenerate
a new law in a fresh process with the lemma cache cold and warm.

Targets: the whole catalogue, all calculi, under 60 s on the 2-core machine (issue 2); verify +
generate of one new law in a new process under 10 s with a warm lemma cache (fricgen.derive.noise.lemma_cache).
Prints the one-off phase-space lemmas (per mode, dimension and calculus: proven, then read from the cache)
apart from the per-law work. The cache lives in a temporary folder (FRICGEN_CACHE), never the user's.

Run: python benchmarks/verify_catalogue.py [--skip-catalogue] [--skip-regeneration]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

#: New laws for the regeneration benchmark: one with a closed-form D, one with the integral (F-22).
NEW_LAWS = {
    "bench_quadratic": ("w*(gamma_f*u + beta_f*u**2)", {"gamma_f": {"default": 1.0}, "beta_f": {"default": 0.5}}),
    "bench_saturating": ("w*kappa_f*u/(u + u0)", {"kappa_f": {"default": 2.0}, "u0": {"default": 0.3}}),
}


def lemmas() -> float:
    """Prove (or read) the law-independent facts through the cache; print each; return the total."""
    from fricgen.derive.noise import lemma_cache, modes

    total = 0.0
    for mode in modes.CONTACT_MODES:
        for dim in modes.dimensions(mode):
            t = time.perf_counter()
            lemma_cache.facts(mode, dim)
            total += (spent := time.perf_counter() - t)
            print(f"  {mode:8s} facts {dim}-D                 {spent:7.2f} s")
            for calculus in ("ito", "stratonovich", "hk"):
                t = time.perf_counter()
                lemma = lemma_cache.lemma(mode, dim, calculus)
                total += (spent := time.perf_counter() - t)
                print(f"  {mode:8s} zero current {dim}-D {calculus:13s} {spent:6.2f} s  holds={lemma.holds} nu/mu={lemma.nu_over_mu}")
    return total


def catalogue_run() -> None:
    from fricgen.derive import catalogue, derive_noise, verify

    start = time.perf_counter()
    print("phase-space lemmas (once per process, or read from the cache):")
    lemmas()
    print("per law and calculus (derive + verify):")
    for name, law in catalogue().items():
        for calculus in ("ito", "stratonovich", "hk"):
            t = time.perf_counter()
            report = verify(derive_noise(law, calculus))
            status = "verified" if report.verified else "not verified" + ("" if calculus in law.calculi else " (excluded by the law)")
            error = report.details.get("kernel_max_rel_error", "-")
            print(f"  {name:16s} {calculus:13s} {time.perf_counter() - t:6.2f} s  {status}  kernel error {error}")
    total = time.perf_counter() - start
    print(f"total {total:.1f} s (target < 60 s): {'OK' if total < 60 else 'SLOW'}")


def child(folder: str, name: str) -> None:
    """In a fresh process: verify every calculus of the law, then generate it (which verifies again)."""
    start = time.perf_counter()
    from fricgen.derive import derive_noise, load_law, make_law, save_law, verify
    from fricgen.derive.driver import generate

    timings = {"import": time.perf_counter() - start}
    friction, parameters = NEW_LAWS[name]
    catalogue = Path(folder) / "catalogue"
    catalogue.mkdir(parents=True, exist_ok=True)
    save_law(make_law(name, friction, parameters, weight="wca"), catalogue)
    timings["lemma"] = lemmas()
    t = time.perf_counter()
    law = load_law(catalogue / f"{name}.toml")
    reports = [verify(derive_noise(law, c)) for c in law.calculi]
    timings["verify"] = time.perf_counter() - t
    t = time.perf_counter()
    generate([name], catalogue=catalogue, output=Path(folder) / "generated")
    timings["generate"] = time.perf_counter() - t
    timings["verified"] = all(r.verified for r in reports)
    timings["closed_form"] = [r.closed_form for r in reports]
    print("RESULT " + json.dumps(timings))


def regeneration_run() -> None:
    print("regenerating one new law in a fresh process (verify all calculi + generate), lemma cache cold then warm:")
    with tempfile.TemporaryDirectory() as folder:
        for name in NEW_LAWS:
            env = {**os.environ, "FRICGEN_CACHE": str(Path(folder) / f"cache-{name}")}  # empty: cold
            for state in ("cold", "warm"):
                work = tempfile.mkdtemp(dir=folder)
                t = time.perf_counter()
                done = subprocess.run(
                    [sys.executable, __file__, "--child", work, name], env=env, capture_output=True, text=True, check=False
                )
                wall = time.perf_counter() - t
                lines = [x for x in done.stdout.splitlines() if x.startswith("RESULT ")]
                if done.returncode or not lines:
                    print(f"  {name} {state}: failed\n{done.stdout}\n{done.stderr}")
                    continue
                r = json.loads(lines[-1][len("RESULT ") :])
                print(
                    f"  {name:17s} {state}: process {wall:6.2f} s = import {r['import']:.2f} + lemma {r['lemma']:.2f}"
                    f" + verify {r['verify']:.2f} + generate {r['generate']:.2f} (+ start-up)  verified={r['verified']}"
                    + (f"  target < 10 s: {'OK' if wall < 10 else 'SLOW'}" if state == "warm" else "")
                )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--child", nargs=2, metavar=("FOLDER", "LAW"), help=argparse.SUPPRESS)
    parser.add_argument("--skip-catalogue", action="store_true")
    parser.add_argument("--skip-regeneration", action="store_true")
    args = parser.parse_args()
    if args.child:
        child(*args.child)
        return
    if not args.skip_regeneration:
        regeneration_run()
    if not args.skip_catalogue:
        with tempfile.TemporaryDirectory() as folder:
            os.environ["FRICGEN_CACHE"] = folder  # a cold cache: the lemmas are proven in this process
            catalogue_run()


if __name__ == "__main__":
    main()
