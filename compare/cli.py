"""python3 -m compare run [--scenes ...] [--engines ...] [--spp N] [--res W H] [--out DIR]
                         [--scheduler ADDRESS] [--workers N]"""
from __future__ import annotations

import argparse
import json
import os
import sys

from . import ENGINES, jobs, runner, scenes


def _override(text):
    """ENGINE:MATERIAL:PARAM=VALUE with VALUE as JSON,
    e.g. CYCLES:lambert_orange:reflectance=[.5,.5,.5]."""
    try:
        engine, material, assignment = text.split(":", 2)
        param, value = assignment.split("=", 1)
        return engine, material, param, json.loads(value)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"--override wants ENGINE:MATERIAL:PARAM=JSON, got {text!r}") from None


def build_parser():
    parser = argparse.ArgumentParser(prog="python3 -m compare",
                                     description="BxDF Lab / Cycles / POV-Ray comparison harness")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="render scenes in every engine and write a report")
    run.add_argument("--scenes", nargs="+", default=list(scenes.DEFAULT_SCENES),
                     choices=list(scenes.SCENES), metavar="SCENE",
                     help="scenes to render (default: all): " + ", ".join(scenes.SCENES))
    run.add_argument("--engines", nargs="+", default=list(ENGINES),
                     choices=list(ENGINES) + ["ANALYTIC"], metavar="ENGINE",
                     help="engines (default: BXDF_LAB CYCLES POVRAY_RENDER; ANALYTIC is added "
                          "where the scene has analytic truth)")
    run.add_argument("--spp", type=int, help="samples per pixel (default: per scene)")
    run.add_argument("--res", type=int, nargs=2, metavar=("W", "H"),
                     help="resolution (default: per scene)")
    run.add_argument("--out", default="out", help="output root; each run gets out/<run-id>/")
    run.add_argument("--scheduler", help="Dask scheduler address (default: local process pool)")
    run.add_argument("--workers", type=int, default=2, help="local pool size (default 2)")
    run.add_argument("--blender", default="blender", help="Blender executable")
    run.add_argument("--timeout", type=float, default=900.0, help="seconds per job")
    run.add_argument("--override", type=_override, action="append", default=[],
                     metavar="ENGINE:MATERIAL:PARAM=JSON",
                     help="change one material parameter in one engine only (a sensitivity "
                          "check: an exact pairing must then fail)")
    run.add_argument("--quiet", action="store_true", help="no progress bar")
    run.add_argument("--blend", metavar="FILE.blend",
                     help="render your own scene instead (BXDF_LAB, CYCLES, POV-Ray through the "
                          "add-on's Compare Renders): figure, numbers, pairing labels, node coverage")
    run.add_argument("--size", type=int, default=256,
                     help="with --blend: longest side of the renders in pixels (default 256)")
    sub.add_parser("scenes", help="list the scenes")
    return parser


def main(argv=None):
    args = build_parser().parse_args(argv)
    if args.command == "scenes":
        for name, make in scenes.SCENES.items():
            spec = make()
            truth = "analytic" if spec.has_analytic_truth() else "-"
            print(f"{name:28s} {truth:9s} {spec.description}")
        return 0
    if args.blend:
        from . import blend_run
        run_dir = blend_run.run(args.blend, out_root=args.out, size=args.size,
                                samples=args.spp or 32, blender=args.blender, timeout=args.timeout)
        print(f"report: {os.path.join(run_dir, 'index.html')}")
        return 0
    if args.spp is not None and args.spp < len(jobs.SEEDS):
        raise SystemExit(f"--spp must be at least {len(jobs.SEEDS)} (that many renders with "
                         f"different seeds share the samples), got {args.spp}")
    overrides = {}
    known = {m.name for name in args.scenes for m in scenes.get(name).materials()}
    for engine, material, param, value in args.override:
        if engine not in ENGINES:
            raise SystemExit(f"--override: engine must be one of {', '.join(ENGINES)}, "
                             f"got {engine!r}")
        if material not in known:
            raise SystemExit(f"--override: no material {material!r} in the chosen scenes; "
                             f"known: {', '.join(sorted(known))}")
        overrides.setdefault(engine, {}).setdefault(material, {})[param] = value
    run_dir = runner.run(args.scenes, args.engines, spp=args.spp, resolution=args.res,
                         out_root=args.out, scheduler=args.scheduler, workers=args.workers,
                         blender=args.blender, timeout=args.timeout, overrides=overrides,
                         quiet=args.quiet)
    with open(os.path.join(run_dir, "summary.json"), encoding="utf-8") as fh:
        summary = json.load(fh)
    flagged = [(s["name"], p["a"], p["b"]) for s in summary["scenes"] for p in s["pairings"]
               if p.get("flagged")]
    failed = [(s["name"], e) for s in summary["scenes"] for e, v in s["engines"].items()
              if v["status"] != "ok"]
    print(f"report: {os.path.join(run_dir, 'index.html')}")
    print(f"{len(failed)} failed engine runs, {len(flagged)} flagged exact pairings")
    for scene, a, b in flagged:
        print(f"  FLAGGED {scene}: {a} vs {b}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
