#!/usr/bin/env python3
"""Timing of the Python API: 1,000,000 f evaluations per model and a 256x256 polar lobe bake.

Run: PYTHONPATH=build/python /usr/bin/python3 bench/python_bench.py [--n 1000000] [--repeat 7]
Goals (2 cores): >= 100 M f evaluations/s from Python; a 256x256 bake in < 20 ms.
The best of --repeat runs is reported (the machine is shared; the best run is the least
disturbed one), with the median beside it, and the process CPU time of that run: on a busy
machine, N / CPU time x cores is what dedicated cores would give (the load average is printed).
"""

import argparse
import os
import resource
import statistics
import time

import numpy as np

import bxdf

# (label, model, params): the two the goals name, plus Lambertian as the floor (conversion
# and chunking cost only). Models missing from the registry are reported as such.
CASES = [
    ("lambertian", "lambertian", {}),
    ("oren_nayar sigma=20", "oren_nayar", {"sigma": 20.0}),
    ("microfacet ggx smith", "microfacet", {"distribution": "ggx", "shadowing": "smith"}),
]


def cpu_seconds():
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def timed(fn, repeat):
    """(best wall time, median wall time, CPU time of the best run), in seconds."""
    runs = []
    for _ in range(repeat):
        c0, t0 = cpu_seconds(), time.perf_counter()
        fn()
        runs.append((time.perf_counter() - t0, cpu_seconds() - c0))
    best = min(runs)
    return best[0], statistics.median(r[0] for r in runs), best[1]


def directions(rng, n):
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2])
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args()
    rng = np.random.default_rng(1)
    wo64, wi64 = directions(rng, args.n), directions(rng, args.n)
    wo32, wi32 = wo64.astype(np.float32), wi64.astype(np.float32)
    registered = bxdf.models()
    cores = os.cpu_count()
    print(f"bxdf from {bxdf.__file__}; {cores} cores, load average {os.getloadavg()[0]:.1f}; "
          f"N = {args.n:,}; best (median) of {args.repeat}")
    for label, name, params in CASES:
        if name not in registered:
            print(f"  f  {label:24s} not registered on this branch")
            continue
        model = bxdf.make(name, **params)
        model.f(wo32[:1000], wi32[:1000])  # warm up threads
        for dtype_label, wo, wi in (("float32", wo32, wi32), ("float64", wo64, wi64)):
            best, med, cpu = timed(lambda: model.f(wo, wi), args.repeat)
            print(f"  f  {label:24s} {dtype_label}: {best * 1e3:7.2f} ms ({med * 1e3:7.2f})"
                  f"  {args.n / best / 1e6:7.1f} M evals/s;  CPU {cpu * 1e3:7.2f} ms"
                  f" -> {args.n / cpu * cores / 1e6:6.1f} M evals/s on {cores} free cores")
    model = bxdf.make("lambertian")
    for label, name, params in CASES:
        if name in registered:
            model = bxdf.make(name, **params)
    for parameterization in ("equal_area", "lat_long"):
        best, med, cpu = timed(lambda: bxdf.bake_lobe_polar(
            model, theta_o=45.0, resolution=256, parameterization=parameterization), args.repeat)
        print(f"  bake_lobe_polar 256x256 {parameterization:10s} ({model.name}): "
              f"{best * 1e3:6.2f} ms ({med * 1e3:6.2f}); CPU {cpu * 1e3:6.2f} ms")
    best, med, cpu = timed(lambda: bxdf.lobe_mesh(model, theta_o=45.0, resolution=64), args.repeat)
    print(f"  lobe_mesh resolution 64 ({model.name}): {best * 1e3:6.2f} ms ({med * 1e3:6.2f});"
          f" CPU {cpu * 1e3:6.2f} ms")


if __name__ == "__main__":
    main()
