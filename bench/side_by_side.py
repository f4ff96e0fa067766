"""BXDF_LAB against Cycles in one Blender process, interleaved, at equal samples and threads.

    blender -b --factory-startup --python-exit-code 1 --python bench/side_by_side.py -- \
        --scene cornell --spp 64 256 --threads 2 --reference-spp 1024 --repeats 3

(`make bench` runs it on cornell and principled_showroom through tools/run-bench.sh, `bash
bench/final_figures.sh` on every harness scene with global illumination.) The scene is a harness
scene (compare/scenes.py), its materials set up by the add-on exactly as the harness does, so each engine renders what it
renders in `make report`. For every sample count both engines render `--repeats` times with
different seeds, alternating (BXDF_LAB, Cycles, BXDF_LAB, ...), each render timed as the user sees
it (bpy.ops.render.render: export, BVH, render, hand-back). The converged reference is the average
of both engines' `--reference-spp` renders, so neither engine is favoured. Printed per sample count:
each engine's median time, the time ratio, each engine's RMSE against the reference, and the
time-to-equal-error ratio (MSE x time; below 1 means BXDF_LAB reaches a given error sooner) with
its 90% bootstrap interval, then the same ratios on the process's CPU time (steadier than wall
time on a shared machine). `--json FILE` also writes every number.

A render's squared error is dominated by a few bright pixels in scenes with caustics or glossy
interreflections (in cycles_glass_room the 1% of pixels with the highest variance hold 63-74% of
it), so one render's MSE swings several-fold from seed to seed: with 3 renders per engine the
MSE ratio of sweep_principled_transmission read 1.37 where 40 read 0.75. The interval says how
far the printed ratio can be trusted; use `--repeats` 12 or more for figures to quote.
"""
import argparse
import atexit
import json
import os
import shutil
import statistics
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
ENGINES = ("BXDF_LAB", "CYCLES")


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="side_by_side.py", description=__doc__.splitlines()[0])
    p.add_argument("--scene", default="cornell", help="harness scene name (compare/scenes.py)")
    p.add_argument("--spp", type=int, nargs="+", default=[64, 256], help="sample counts")
    p.add_argument("--threads", type=int, default=2, help="threads for both engines")
    p.add_argument("--reference-spp", type=int, default=1024,
                   help="samples of each engine's reference render")
    p.add_argument("--repeats", type=int, nargs="+", default=[3],
                   help="renders per engine and sample count: one number for every --spp, or "
                        "one per --spp value (e.g. 96 24 for 64 256: the same samples per row)")
    p.add_argument("--first-seed", type=int, default=0,
                   help="seeds first-seed .. first-seed + repeats - 1 (the same every run unless "
                        "changed: a heavy-tailed error needs other seeds to be checked)")
    p.add_argument("--res", type=int, nargs=2, metavar=("W", "H"), default=None,
                   help="resolution (default: the scene's)")
    p.add_argument("--adaptive", type=float, default=None, metavar="THRESHOLD",
                   help="both engines with Cycles' Adaptive Sampling at this Noise Threshold "
                        "(0 = automatic; minimum samples automatic); the references without")
    p.add_argument("--json", default=None, help="also write the results to this file")
    args = p.parse_args(argv)
    for name in ("threads", "reference_spp"):
        if getattr(args, name) < 1:
            p.error(f"--{name.replace('_', '-')} must be at least 1, got {getattr(args, name)}")
    if any(r < 1 for r in args.repeats):
        p.error(f"--repeats values must be at least 1, got {args.repeats}")
    if len(args.repeats) == 1:
        args.repeats = args.repeats * len(args.spp)
    elif len(args.repeats) != len(args.spp):
        p.error(f"--repeats takes one number or one per --spp value ({len(args.spp)}), "
                f"got {args.repeats}")
    if args.first_seed < 0:
        p.error(f"--first-seed must be at least 0, got {args.first_seed}")
    if any(s < 1 for s in args.spp):
        p.error(f"--spp values must be at least 1, got {args.spp}")
    return args


def set_up_scene(scene_name, resolution, world_dir=None):
    """Builds the harness scene once, with every material set up for both engines. Generated world
    images go to `world_dir`, or to a temporary folder removed when the process ends."""
    from dataclasses import replace

    use_module_paths()
    from compare import scenes

    spec = scenes.get(scene_name)
    if resolution:
        spec = replace(spec, resolution=tuple(resolution))
    return set_up_spec(spec, world_dir)


def set_up_spec(spec, world_dir=None):
    """Builds a scene spec (compare/scenes.py) in Blender, every material set up for both engines."""
    use_module_paths()
    import bpy

    from compare import bpy_build, driver, engine_setup, material_setup

    driver.enable_addons({"engine": "BXDF_LAB", "repo_root": ROOT})
    bpy_build.clear_scene()
    materials = {m.name: bpy.data.materials.new(m.name) for m in spec.materials()}
    # Generated world images (a z-gradient world) go to a folder of their own.
    if world_dir is None:
        world_dir = tempfile.mkdtemp(prefix="bxdf-side-by-side-world-")
        atexit.register(shutil.rmtree, world_dir, True)  # read until the last render
    objects = bpy_build.build(spec, materials, world_dir)
    engine_setup.common_settings(spec)
    labels = {}
    for mat_spec in spec.materials():
        owner = next(objects[o.name] for o in spec.objects if o.material.name == mat_spec.name)
        # The model first (BXDF_LAB renders it), then the add-on's Cycles node tree from it.
        labels[mat_spec.name] = material_setup.setup(materials[mat_spec.name], owner,
                                                     mat_spec.model, mat_spec.params, "CYCLES")
    return spec, labels


def render(engine, spec, spp, seed, threads, path, cycles_pattern=None, adaptive=None):
    """Renders once; returns (seconds, CPU seconds of the whole process, HxWx3 linear image).
    `cycles_pattern`: Cycles' sampling_pattern instead of the harness's (its default, PMJ).
    `adaptive`: Cycles' Adaptive Sampling on at this Noise Threshold, which both engines read."""
    import bpy

    from compare import driver, engine_setup, imageio

    configure = engine_setup.configure_cycles if engine == "CYCLES" else engine_setup.configure_bxdf_lab
    configure(spec, spp, seed, threads)
    if engine == "CYCLES" and cycles_pattern:
        bpy.context.scene.cycles.sampling_pattern = cycles_pattern
    if adaptive is not None:
        cycles = bpy.context.scene.cycles
        cycles.use_adaptive_sampling = True
        cycles.adaptive_threshold = adaptive
        cycles.adaptive_min_samples = 0
    bpy.context.scene.render.filepath = path
    start, cpu_start = time.perf_counter(), time.process_time()
    bpy.ops.render.render(write_still=True)
    seconds = time.perf_counter() - start
    cpu_seconds = time.process_time() - cpu_start  # every thread of Blender's process
    driver.raise_engine_error(engine, seed)
    if not os.path.isfile(path):
        raise RuntimeError(f"{engine} wrote no image for seed {seed}")
    image = imageio.read(path)
    os.remove(path)
    return seconds, cpu_seconds, image


def render_references(spec, spp, threads, folder):
    """Each engine's `spp` render (seed 9999, apart from the compared renders' seeds) and their
    mean, the converged reference that favours neither engine: (per-engine images, mean)."""
    references = [render(e, spec, spp, 9999, threads, os.path.join(folder, f"ref_{e}.exr"))[2]
                  for e in ENGINES]
    return references, 0.5 * (references[0] + references[1])


def bootstrap_interval(mse_b, mse_c, seconds_b, seconds_c, rounds=2000, seed=1):
    """The 5th and 95th percentiles of MSE x time ratio over bootstrap resamples of each
    engine's renders (their MSEs and times resampled together, as the ratio is computed)."""
    import numpy as np

    rng = np.random.default_rng(seed)
    mse_b, mse_c = np.asarray(mse_b), np.asarray(mse_c)
    t_b, t_c = np.asarray(seconds_b), np.asarray(seconds_c)
    ratios = []
    for _ in range(rounds):
        ib = rng.integers(0, len(mse_b), len(mse_b))
        ic = rng.integers(0, len(mse_c), len(mse_c))
        ratios.append((mse_b[ib].mean() * np.median(t_b[ib])) /
                      (mse_c[ic].mean() * np.median(t_c[ic])))
    low, high = np.quantile(ratios, [0.05, 0.95])
    return float(low), float(high)


def use_module_paths():
    """Puts the repository (compare/) and the bxdf module on sys.path: BXDF_PYTHONPATH's build
    before the repository's build/python, so that another build can be measured."""
    for path in (ROOT, os.path.join(ROOT, "build", "python"), os.environ.get("BXDF_PYTHONPATH", "")):
        if path and path not in sys.path:
            sys.path.insert(0, path)  # the last inserted is searched first


def main():
    args = parse_args()
    use_module_paths()
    import numpy as np

    spec, labels = set_up_scene(args.scene, args.res)
    work = tempfile.mkdtemp(prefix="bxdf-side-by-side-")
    out = lambda tag: os.path.join(work, f"{tag}.exr")  # noqa: E731

    _, reference = render_references(spec, args.reference_spp, args.threads, work)
    width, height = spec.resolution
    renders = ", ".join(f"{n} at {spp} spp (seeds {args.first_seed}-{args.first_seed + n - 1})"
                        for spp, n in zip(args.spp, args.repeats))
    print(f"side_by_side: scene {args.scene} ({width}x{height}, max_bounces {spec.max_bounces}), "
          f"{args.threads} threads each, interleaved renders per engine: {renders}"
          f"{'' if args.adaptive is None else f', adaptive sampling at noise threshold {args.adaptive}'}"
          f"; reference = "
          f"mean of both engines at {args.reference_spp} spp; "
          f"materials: {', '.join(f'{k} {v}' for k, v in labels.items())}")
    rows = []
    for spp, repeats in zip(args.spp, args.repeats):
        seconds = {e: [] for e in ENGINES}
        cpu_seconds = {e: [] for e in ENGINES}
        mse = {e: [] for e in ENGINES}
        for r in range(args.first_seed, args.first_seed + repeats):
            for engine in ENGINES:
                t, cpu, image = render(engine, spec, spp, r, args.threads, out(f"{engine}_{spp}_{r}"),
                                       adaptive=args.adaptive)
                seconds[engine].append(t)
                cpu_seconds[engine].append(cpu)
                mse[engine].append(float(np.mean((image - reference) ** 2)))
        row = {"spp": spp, "renders": repeats}
        for engine in ENGINES:
            row[engine] = {"median_seconds": statistics.median(seconds[engine]),
                           "seconds": seconds[engine],
                           "median_cpu_seconds": statistics.median(cpu_seconds[engine]),
                           "cpu_seconds": cpu_seconds[engine],
                           "rmse": float(np.sqrt(np.mean(mse[engine]))),
                           "mse": float(np.mean(mse[engine]))}
        b, c = row["BXDF_LAB"], row["CYCLES"]
        row["time_ratio"] = b["median_seconds"] / c["median_seconds"]
        row["equal_error_ratio"] = (b["mse"] * b["median_seconds"]) / (c["mse"] * c["median_seconds"])
        row["equal_error_ratio_90"] = bootstrap_interval(mse["BXDF_LAB"], mse["CYCLES"],
                                                         seconds["BXDF_LAB"], seconds["CYCLES"])
        row["mse_ratio"] = b["mse"] / c["mse"]
        row["cpu_ratio"] = b["median_cpu_seconds"] / c["median_cpu_seconds"]
        row["cpu_equal_error_ratio"] = ((b["mse"] * b["median_cpu_seconds"]) /
                                        (c["mse"] * c["median_cpu_seconds"]))
        rows.append(row)
    print(f"{'spp':>6} {'BXDF_LAB s':>11} {'Cycles s':>9} {'time ratio':>11} "
          f"{'RMSE BXDF_LAB':>14} {'RMSE Cycles':>12} {'MSE ratio':>10} {'equal-error ratio':>18} "
          f"{'90% interval':>14}")
    for row in rows:
        b, c = row["BXDF_LAB"], row["CYCLES"]
        low, high = row["equal_error_ratio_90"]
        print(f"{row['spp']:>6} {b['median_seconds']:>11.3f} {c['median_seconds']:>9.3f} "
              f"{row['time_ratio']:>11.2f} {b['rmse']:>14.5f} {c['rmse']:>12.5f} "
              f"{row['mse_ratio']:>10.2f} {row['equal_error_ratio']:>18.2f} "
              f"{f'{low:.2f}-{high:.2f}':>14}")
    # On a shared machine the wall times swing with the other load; the process's CPU time (both
    # engines run 2 threads in this one process) is steadier, and its ratios are printed too.
    print(f"{'spp':>6} {'BXDF_LAB cpu s':>15} {'Cycles cpu s':>13} {'cpu ratio':>10} "
          f"{'MSE x cpu ratio':>16}")
    for row in rows:
        b, c = row["BXDF_LAB"], row["CYCLES"]
        print(f"{row['spp']:>6} {b['median_cpu_seconds']:>15.3f} {c['median_cpu_seconds']:>13.3f} "
              f"{row['cpu_ratio']:>10.2f} {row['cpu_equal_error_ratio']:>16.2f}")
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump({"scene": args.scene, "threads": args.threads, "adaptive": args.adaptive,
                       "reference_spp": args.reference_spp, "rows": rows}, fh, indent=1)
    os.rmdir(work)


if __name__ == "__main__":
    if ROOT not in sys.path:
        sys.path.insert(0, ROOT)
    from compare import blender_main
    blender_main.run(main)
