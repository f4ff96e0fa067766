"""The fixed cost of a render in Blender: BXDF_LAB's phases and Cycles' whole render, at 1 sample.

    blender -b --factory-startup --python-exit-code 1 --python bench/fixed_cost.py -- \
        --scene cornell --renders 10 --threads 2

Builds a harness scene as bench/side_by_side.py does (materials set up by the add-on for both
engines), renders it once per engine to warm up (module import, Cycles' kernels), then `--renders`
times per engine, alternating, at `--spp` samples (1: what is left is the cost of getting the
scene in and the image out). Each render is timed as the user sees it (bpy.ops.render.render,
no file written); BXDF_LAB's time is split into the engine's phases (engine.PHASES, from the
render report's timings) plus Blender's own share (the operator's time outside the engine's
render()). Cycles' time has no such split, so both engines also render at twice the samples, and
each engine's fixed cost is estimated the same way, as 2 T(spp) - T(2 spp) (the operator's
medians): what a render costs besides its samples. Prints medians in ms and the load average,
which says how much of the machine other processes took.
"""
import argparse
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="fixed_cost.py", description=__doc__.splitlines()[0])
    p.add_argument("--scene", default="cornell", help="harness scene name (compare/scenes.py)")
    p.add_argument("--renders", type=int, default=10, help="timed renders per engine")
    p.add_argument("--spp", type=int, default=1, help="samples per pixel")
    p.add_argument("--threads", type=int, default=2, help="threads for both engines")
    args = p.parse_args(argv)
    for name in ("renders", "spp", "threads"):
        if getattr(args, name) < 1:
            p.error(f"--{name} must be at least 1, got {getattr(args, name)}")
    return args


def timed_render(engine, spec, spp, seed, threads, cpu_seconds=None):
    """Renders once (no file); returns the operator's seconds, and appends the process's CPU
    seconds (all threads) to `cpu_seconds` when given."""
    import bpy

    from compare import driver, engine_setup

    configure = engine_setup.configure_cycles if engine == "CYCLES" else engine_setup.configure_bxdf_lab
    configure(spec, spp, seed, threads)
    start, cpu_start = time.perf_counter(), time.process_time()
    bpy.ops.render.render(write_still=False)
    seconds = time.perf_counter() - start
    if cpu_seconds is not None:
        cpu_seconds.append(time.process_time() - cpu_start)
    driver.raise_engine_error(engine, seed)
    return seconds


def main():
    args = parse_args()
    if HERE not in sys.path:
        sys.path.insert(0, HERE)
    import side_by_side

    spec, _ = side_by_side.set_up_scene(args.scene, None)  # enables the add-on
    from bxdf_lab import engine, render_report
    for name in ("BXDF_LAB", "CYCLES"):  # warm-up: first-render costs are not the fixed cost
        timed_render(name, spec, args.spp, 0, args.threads)
    phases = {p: [] for p in engine.PHASES + ("blender", "operator")}
    cycles = []
    doubled = {"BXDF_LAB": [], "CYCLES": []}  # the operator's seconds at 2 spp
    cpu = {"BXDF_LAB": [], "CYCLES": []}  # the process's CPU seconds at spp
    for r in range(args.renders):
        seconds = timed_render("BXDF_LAB", spec, args.spp, r, args.threads, cpu["BXDF_LAB"])
        timings = render_report.last("render").timings
        if not timings:
            raise RuntimeError(f"BXDF_LAB render {r} recorded no timings (cancelled or failed?)")
        for p in engine.PHASES:
            phases[p].append(timings[p])
        phases["blender"].append(seconds - timings["total"])
        phases["operator"].append(seconds)
        cycles.append(timed_render("CYCLES", spec, args.spp, r, args.threads, cpu["CYCLES"]))
        for name in doubled:
            doubled[name].append(timed_render(name, spec, 2 * args.spp, r, args.threads))

    width, height = spec.resolution
    print(f"fixed_cost: scene {args.scene} ({width}x{height}), {args.spp} spp, {args.threads} "
          f"threads, median of {args.renders} renders per engine, load average "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    ms = lambda xs: 1000.0 * statistics.median(xs)  # noqa: E731
    print("BXDF_LAB ms: " + ", ".join(f"{p} {ms(phases[p]):.1f}" for p in phases))
    print(f"CYCLES ms: operator {ms(cycles):.1f}")
    fixed = {"BXDF_LAB": 2 * ms(phases["operator"]) - ms(doubled["BXDF_LAB"]),
             "CYCLES": 2 * ms(cycles) - ms(doubled["CYCLES"])}
    print(f"{2 * args.spp} spp ms: BXDF_LAB {ms(doubled['BXDF_LAB']):.1f}, CYCLES "
          f"{ms(doubled['CYCLES']):.1f}; fixed cost 2 T({args.spp}) - T({2 * args.spp}): "
          f"BXDF_LAB {fixed['BXDF_LAB']:.1f}, CYCLES {fixed['CYCLES']:.1f}")
    print(f"BXDF_LAB / CYCLES (operator): {statistics.median(phases['operator']) / statistics.median(cycles):.2f}; "
          f"process CPU ms (steadier on a shared machine): BXDF_LAB {ms(cpu['BXDF_LAB']):.1f}, "
          f"CYCLES {ms(cpu['CYCLES']):.1f}")


if __name__ == "__main__":
    if ROOT not in sys.path:
        sys.path.insert(0, ROOT)
    from compare import blender_main
    blender_main.run(main)
