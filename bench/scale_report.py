"""Memory and BVH build at scale: ~10 million triangles, unique and instanced, BXDF_LAB (CLI and
Blender) against Cycles. A report, not a test; run on an otherwise idle machine:

    /usr/bin/python3 bench/scale_report.py [--build build] [--spheres 100] [--segments 320]

The scene is a grid of `--spheres` UV spheres of `--segments` x segments/2 (about 100k triangles
each, 10.2M in all), under a sun, rendered at 128x128, 1 sample, 2 threads. "unique" gives every
sphere its own mesh; "instanced" links one mesh to every sphere object. Each Blender render runs in
its own Blender process: the process's resident set is read before bpy.ops.render.render, the
peak is reset (/proc/self/clear_refs) and read after it, and the difference divided by the
triangle count is the peak memory per triangle. The CLI renders the same spheres from a scene
file, unique ("meshes": one sphere each) and instanced ("prototypes" + "instances": one sphere
placed N times), its peak measured by /usr/bin/time against a one-sphere scene. Build times:
BXDF_LAB's own split (export, conversion, BVH) and, for Cycles, the time from its "Building BVH"
status line to its first "Sample" line.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def sphere_centres(n):
    side = int(round(n ** 0.5 + 0.4999))
    return [((i % side - (side - 1) / 2) * 2.2, (i // side - (side - 1) / 2) * 2.2, 0.0)
            for i in range(n)]


# ---------------------------------------------------------------- inside Blender
def worker(args):
    import resource  # noqa: F401  (Linux only, as /proc)
    import time

    import bpy
    sys.path.insert(0, os.path.join(ROOT, "blender_addon"))
    import addon_utils
    addon_utils.enable("bxdf_lab", default_set=True)
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_uv_sphere_add(segments=args.segments, ring_count=args.segments // 2,
                                         radius=1.0)
    first = bpy.context.active_object
    mesh = first.data
    triangles_per_sphere = sum(len(p.vertices) - 2 for p in mesh.polygons)
    centres = sphere_centres(args.spheres)
    first.location = centres[0]
    for i, c in enumerate(centres[1:]):
        data = mesh if args.kind == "instanced" else mesh.copy()
        obj = bpy.data.objects.new(f"sphere_{i + 1}", data)
        obj.location = c
        scene.collection.objects.link(obj)
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.rotation_euler = (0.6, 0.2, 0.0)
    scene.collection.objects.link(sun)
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    extent = 1.2 * max(abs(c[0]) for c in centres) + 2.0
    cam.location = (0.0, -2.2 * extent, 1.5 * extent)
    from mathutils import Vector
    cam.rotation_euler = (Vector((0, 0, 0)) - cam.location).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(cam)
    scene.camera = cam
    r = scene.render
    r.resolution_x = r.resolution_y = 128
    r.resolution_percentage = 100
    r.threads_mode, r.threads = "FIXED", 2
    r.engine = args.engine
    scene.cycles.samples = 1
    scene.cycles.use_denoising = False
    scene.bxdf_lab_render.samples = 1
    scene.bxdf_lab_render.threads = 2
    bpy.context.view_layer.update()

    def status(key):
        with open("/proc/self/status", encoding="ascii") as fh:
            return int(re.search(rf"^{key}:\s+(\d+) kB", fh.read(), re.M).group(1)) * 1024

    before = status("VmRSS")
    with open("/proc/self/clear_refs", "w", encoding="ascii") as fh:
        fh.write("5")  # resets VmHWM to the current resident set
    started = time.perf_counter()
    r.filepath = os.path.join(args.workdir, f"{args.engine}_{args.kind}.exr")
    bpy.ops.render.render(write_still=True)
    seconds = time.perf_counter() - started
    peak = status("VmHWM")
    result = {"engine": args.engine, "kind": args.kind, "triangles": triangles_per_sphere * len(centres),
              "render_seconds": seconds, "rss_before": before, "peak": peak}
    if args.engine == "BXDF_LAB":
        from bxdf_lab import render_report
        result["summary"] = render_report.last("render").summary
        # The conversion and BVH split, from one more render through the binding directly.
        from bxdf_lab import export, renderer
        data = export.export_scene(bpy.context.evaluated_depsgraph_get())
        _, stats = renderer.render(data, renderer.settings_dict(scene.bxdf_lab_render), None)
        result["convert_seconds"], result["bvh_seconds"] = stats["convert_seconds"], stats["bvh_seconds"]
    print("SCALE_RESULT " + json.dumps(result), flush=True)


# ---------------------------------------------------------------- driver
def cycles_bvh_seconds(log):
    """Seconds between Cycles' first BVH status line and its first sample line, from the
    'Time:MM:SS.ss' stamps Blender prints in the background."""
    stamps = []
    for line in log.splitlines():
        m = re.search(r"Time:(\d+):(\d+\.\d+)", line)
        if m:
            stamps.append((60 * int(m.group(1)) + float(m.group(2)), line))
    start = next((t for t, line in stamps if "BVH" in line), None)
    end = next((t for t, line in stamps if start is not None and t >= start and "Sample" in line), None)
    return None if start is None or end is None else end - start


def blender_run(engine, kind, args, workdir):
    cmd = ["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python",
           os.path.abspath(__file__), "--", "--worker", "--engine", engine, "--kind", kind,
           "--spheres", str(args.spheres), "--segments", str(args.segments), "--workdir", workdir]
    env = dict(os.environ, BXDF_PYTHONPATH=os.path.join(os.path.abspath(args.build), "python"))
    env["PYTHONPATH"] = env["BXDF_PYTHONPATH"]
    out = subprocess.run(cmd, capture_output=True, text=True, env=env)
    m = re.search(r"^SCALE_RESULT (.*)$", out.stdout, re.M)
    if out.returncode != 0 or not m:
        raise RuntimeError(f"{engine} {kind} failed ({out.returncode}):\n{out.stdout[-3000:]}\n{out.stderr[-3000:]}")
    result = json.loads(m.group(1))
    if engine == "CYCLES":
        result["bvh_seconds"] = cycles_bvh_seconds(out.stdout)
    return result


def cli_run(args, workdir, spheres, instanced=False):
    scene = {"camera": {"position": [0, -40, 30], "look_at": [0, 0, 0], "up": [0, 0, 1]},
             "render": {"width": 128, "height": 128},
             "materials": {"grey": {"model": "lambertian", "params": {"reflectance": 0.5}}},
             "lights": [{"type": "sun", "direction": [-0.3, 0.5, -1], "strength": 3, "angle": 0}]}
    sphere = {"shape": "sphere", "radius": 1.0, "segments": args.segments, "rings": args.segments // 2,
              "material": "grey"}
    if instanced:
        scene["prototypes"] = {"sphere": dict(sphere, center=[0, 0, 0])}
        scene["instances"] = [{"prototype": "sphere", "matrix": [[1, 0, 0, c[0]], [0, 1, 0, c[1]], [0, 0, 1, c[2]]]}
                              for c in sphere_centres(spheres)]
    else:
        scene["meshes"] = [dict(sphere, center=list(c)) for c in sphere_centres(spheres)]
    path = os.path.join(workdir, f"cli_{spheres}_{'instanced' if instanced else 'unique'}.json")
    with open(path, "w", encoding="utf-8") as fh:
        json.dump(scene, fh)
    binary = os.path.join(args.build, "plugin", "tools", "bxdf-render")
    out = subprocess.run(["/usr/bin/time", "-f", "TIME %M %e", binary, path, "-o",
                          os.path.join(workdir, "cli.exr"), "--spp", "1", "--threads", "2", "--quiet"],
                         capture_output=True, text=True, check=True)
    peak_kb, wall = re.search(r"TIME (\d+) ([0-9.]+)", out.stderr).groups()
    render = float(re.search(r"spp, ([0-9.]+) s", out.stdout).group(1))
    return {"peak": int(peak_kb) * 1024, "wall": float(wall), "render": render}


def main():
    if "--worker" in sys.argv:
        p = argparse.ArgumentParser()
        for name in ("--engine", "--kind", "--workdir"):
            p.add_argument(name)
        p.add_argument("--spheres", type=int)
        p.add_argument("--segments", type=int)
        p.add_argument("--worker", action="store_true")
        worker(p.parse_args(sys.argv[sys.argv.index("--") + 1:]))
        return
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--spheres", type=int, default=100)
    p.add_argument("--segments", type=int, default=320)
    args = p.parse_args()
    if args.spheres < 1 or args.segments < 8:
        p.error(f"--spheres must be >= 1 and --segments >= 8, got {args.spheres}, {args.segments}")
    workdir = tempfile.mkdtemp(prefix="bxdf-scale-")
    small = cli_run(args, workdir, 1)
    triangles = args.spheres * 2 * args.segments * (args.segments // 2 - 1)
    print(f"scale_report: {args.spheres} spheres of {args.segments}x{args.segments // 2}, 128x128, "
          f"1 spp, 2 threads; load average {os.getloadavg()[0]:.1f}")
    for kind in ("unique", "instanced"):
        big = cli_run(args, workdir, args.spheres, instanced=kind == "instanced")
        print(f"  CLI      {kind:9s} {triangles / 1e6:6.2f} M triangles: peak {big['peak'] / 2**20:7.0f} MiB, "
              f"{(big['peak'] - small['peak']) / triangles:6.1f} B/triangle over a one-sphere scene; "
              f"load + BVH + render {big['wall']:.2f} s (render {big['render']:.2f} s)", flush=True)
    for kind in ("unique", "instanced"):
        for engine in ("BXDF_LAB", "CYCLES"):
            r = blender_run(engine, kind, args, workdir)
            per = (r["peak"] - r["rss_before"]) / r["triangles"]
            bvh = r.get("bvh_seconds")
            extra = (f"; {r['summary']}; conversion {r['convert_seconds']:.2f} s, BVH {bvh:.2f} s"
                     if engine == "BXDF_LAB" else
                     f"; BVH {bvh:.2f} s" if bvh is not None else "; BVH time not found in the log")
            print(f"  {engine:8s} {kind:9s} {r['triangles'] / 1e6:6.2f} M triangles: peak +"
                  f"{(r['peak'] - r['rss_before']) / 2**20:7.0f} MiB during the render, {per:6.1f} "
                  f"B/triangle; render {r['render_seconds']:.2f} s{extra}", flush=True)
    for name in os.listdir(workdir):
        os.remove(os.path.join(workdir, name))
    os.rmdir(workdir)


if __name__ == "__main__":
    main()
