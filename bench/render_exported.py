"""Renders a scene written by bench/export_harness_scene.py with the bxdf module alone (no Blender).

    PYTHONPATH=build/python /usr/bin/python3 bench/render_exported.py /tmp/cornell.pickle \
        --spp 16 --threads 2 --repeats 3

Prints, per render, the wall time and the process's CPU time of bxdf.render (seeds 1, 2, ...)
and its ray counts. For a steady figure to compare builds by, count instructions instead of time:

    valgrind --tool=callgrind --toggle-collect='bxdf::render::PathBatch::trace*' \
        /usr/bin/python3 bench/render_exported.py /tmp/cornell.pickle --spp 4 --threads 1

(the instructions of the path tracing itself, the same in every run of the same build).
"""
import argparse
import os
import pickle
import sys
import time


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("scene", help="pickle file from bench/export_harness_scene.py")
    p.add_argument("--spp", type=int, default=16, help="samples per pixel")
    p.add_argument("--threads", type=int, default=2, help="render threads")
    p.add_argument("--repeats", type=int, default=1, help="renders, seeds 1, 2, ...")
    args = p.parse_args()
    for name in ("spp", "threads", "repeats"):
        if getattr(args, name) < 1:
            p.error(f"--{name} must be at least 1, got {getattr(args, name)}")
    if not os.path.isfile(args.scene):
        p.error(f"scene file '{args.scene}' does not exist (write it with "
                "bench/export_harness_scene.py)")
    return args


def main():
    args = parse_args()
    try:
        import bxdf
    except ImportError as e:
        sys.exit(f"render_exported: cannot import bxdf ({e}); run with PYTHONPATH=build/python")
    with open(args.scene, "rb") as f:
        exported = pickle.load(f)
    settings = dict(exported["settings"], samples=args.spp, threads=args.threads)
    for seed in range(1, args.repeats + 1):
        settings["seed"] = seed
        wall, cpu = time.perf_counter(), time.process_time()
        _, stats = bxdf.render(exported["scene"], settings, None, bottom_up=True,
                               partial_images=False, return_stats=True)
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        print(f"{exported['harness_scene']}: {args.spp} spp, {args.threads} threads, seed {seed}: "
              f"{wall:.3f} s wall, {cpu:.3f} s CPU, {stats['rays']} rays, "
              f"{stats['shadow_rays']} shadow rays", flush=True)


if __name__ == "__main__":
    main()
