"""Thread scaling and ray rate of the renderer on bench/render/cornell_box.json.

    /usr/bin/python3 bench/thread_scaling.py [--build build] [--repeats 3] [--spp 64]

Runs bxdf_bench_render (bench/render) alternately at 1 and 2 threads, `--repeats` times each, and
prints the median wall time of each, the 1 -> 2 thread speed-up (goal >= 1.9x), and at 2 threads
the whole-render ray rate (closest-hit + shadow rays per second) against Embree's rtcIntersect1
closest-hit rate on random rays in the same scene at the same thread count (goal >= 85%). The
figures are only meaningful on an otherwise idle machine.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIELDS = {
    "seconds": r"^wall time\s+([0-9.eE+-]+) s",
    "rays_per_second": r"^rays/s\s+([0-9.eE+-]+)",
    "ceiling": r"rtcIntersect1 ([0-9.eE+-]+) rays/s",
}


def run(binary, threads, spp):
    out = subprocess.run([binary, "--threads", str(threads), "--spp", str(spp)], check=True,
                         capture_output=True, text=True).stdout
    values = {}
    for name, pattern in FIELDS.items():
        m = re.search(pattern, out, re.MULTILINE)
        if not m:
            raise RuntimeError(f"bxdf_bench_render printed no '{name}' line:\n{out}")
        values[name] = float(m.group(1))
    return values


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--spp", type=int, default=64)
    args = p.parse_args()
    if args.repeats < 1 or args.spp < 1:
        p.error(f"--repeats and --spp must be at least 1, got {args.repeats}, {args.spp}")
    binary = os.path.join(args.build, "bench", "render", "bxdf_bench_render")
    if not os.access(binary, os.X_OK):
        sys.exit(f"thread_scaling: {binary} is not built (make build)")
    runs = {1: [], 2: []}
    for _ in range(args.repeats):
        for threads in (1, 2):
            runs[threads].append(run(binary, threads, args.spp))
    median = {t: {k: statistics.median(r[k] for r in runs[t]) for k in FIELDS} for t in runs}
    load = os.getloadavg()[0]
    print(f"thread_scaling: cornell_box.json, {args.spp} spp, {args.repeats} runs per thread "
          f"count, load average {load:.1f} at the end")
    for t in (1, 2):
        m = median[t]
        print(f"  {t} thread{'s' if t > 1 else ' '}: {m['seconds']:.3f} s, "
              f"{m['rays_per_second'] / 1e6:.2f} M rays/s, Embree rtcIntersect1 ceiling "
              f"{m['ceiling'] / 1e6:.2f} M rays/s ({100 * m['rays_per_second'] / m['ceiling']:.0f}%)")
    print(f"  1 -> 2 thread speed-up: {median[1]['seconds'] / median[2]['seconds']:.2f}x (goal >= 1.9x)")


if __name__ == "__main__":
    main()
