"""Which of two builds of the bxdf module renders an exported scene faster: CPU time, interleaved.

    /usr/bin/python3 bench/ab_builds.py --old /tmp/ab_old --new /tmp/ab_new \\
        /tmp/area_light_room.pickle --spp 128 --threads 1 --pairs 8 --repeats 4

`--old` and `--new` are folders that each hold a `bxdf` package (a copy of build/python/bxdf
from each build); the scene comes from bench/export_harness_scene.py. Each pair runs
bench/render_exported.py once per build, in alternating order, each run rendering `--repeats`
times in its own process. A run's figure is its fastest render: on these VMs a process's renders
spread by ~8% and separate processes by more, and the fastest is the steadiest estimate of what a
build costs. Prints the median and range over the pairs of new/old, and the ratio of each
build's fastest render overall. Differences under ~2% are not resolved by 8 pairs.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("scene", help="pickle file from bench/export_harness_scene.py")
    p.add_argument("--old", required=True, help="folder holding the first build's bxdf package")
    p.add_argument("--new", required=True, help="folder holding the second build's bxdf package")
    p.add_argument("--spp", type=int, default=64, help="samples per pixel")
    p.add_argument("--threads", type=int, default=1, help="render threads")
    p.add_argument("--pairs", type=int, default=8, help="interleaved pairs of runs")
    p.add_argument("--repeats", type=int, default=4, help="renders per run (one process)")
    args = p.parse_args()
    for name in ("spp", "threads", "pairs", "repeats"):
        if getattr(args, name) < 1:
            p.error(f"--{name} must be at least 1, got {getattr(args, name)}")
    for name in ("old", "new"):
        folder = getattr(args, name)
        if not os.path.isdir(os.path.join(folder, "bxdf")):
            p.error(f"--{name} '{folder}' holds no bxdf package (copy build/python/bxdf into it)")
    if not os.path.isfile(args.scene):
        p.error(f"scene file '{args.scene}' does not exist (write it with "
                "bench/export_harness_scene.py)")
    return args


def fastest_render(folder, args):
    """The CPU seconds of the fastest of `--repeats` renders in one process of this build."""
    out = subprocess.run(
        [sys.executable, os.path.join(HERE, "render_exported.py"), args.scene, "--spp",
         str(args.spp), "--threads", str(args.threads), "--repeats", str(args.repeats)],
        env=dict(os.environ, PYTHONPATH=folder), capture_output=True, text=True, check=True).stdout
    seconds = [float(s) for s in re.findall(r"([0-9.]+) s CPU", out)]
    if len(seconds) != args.repeats:
        raise RuntimeError(f"ab_builds: expected {args.repeats} renders from {folder}, got:\n{out}")
    return min(seconds)


def main():
    args = parse_args()
    olds, news = [], []
    for pair in range(args.pairs):
        runs = [("old", args.old), ("new", args.new)]
        for name, folder in runs if pair % 2 == 0 else runs[::-1]:
            (olds if name == "old" else news).append(fastest_render(folder, args))
    ratios = [n / o for n, o in zip(news, olds)]
    print(f"ab_builds: {os.path.basename(args.scene)}, {args.spp} spp, {args.threads} thread(s), "
          f"{args.pairs} pairs x {args.repeats} renders: new/old CPU time median "
          f"{statistics.median(ratios):.3f} (pairs {min(ratios):.3f}-{max(ratios):.3f}), "
          f"fastest against fastest {min(news) / min(olds):.3f}")


if __name__ == "__main__":
    main()
