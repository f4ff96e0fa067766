"""`python3 -m compare run --blend FILE.blend`: the user's own scene through the add-on's Compare
Renders (bxdf_lab.compare): BXDF_LAB, CYCLES and POVRAY_RENDER at a preview size, the figure, the
numbers, each material's pairing label and its node coverage, in <out>/<run-id>/index.html.

run() starts `blender -b FILE.blend --python compare/blend_run.py -- ARGS.json`; the same file,
run inside Blender, enables the add-on and calls the operator."""
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO_ROOT = os.path.dirname(HERE)


def run(blend, out_root="out", size=256, samples=32, blender="blender", timeout=1800.0):
    """Renders `blend` (never modified: Blender saves nothing); returns the run folder."""
    from .runner import bxdf_python_paths, new_run_dir

    if not os.path.isfile(blend):
        raise SystemExit(f"--blend: no such file {blend!r}")
    run_dir = new_run_dir(out_root)
    args = {"out": os.path.abspath(run_dir), "size": size, "samples": samples,
            "python_paths": [os.path.abspath(p) for p in bxdf_python_paths()],
            "addon_dir": os.path.join(REPO_ROOT, "blender_addon")}
    args_path = os.path.join(run_dir, "blend_run.json")
    with open(args_path, "w", encoding="utf-8") as fh:
        json.dump(args, fh)
    log_path = os.path.join(run_dir, "blender.log")
    with open(log_path, "w", encoding="utf-8") as log:
        done = subprocess.run([blender, "-b", os.path.abspath(blend), "--python-exit-code", "1",
                               "--python", os.path.abspath(__file__), "--", args_path],
                              stdout=log, stderr=subprocess.STDOUT, timeout=timeout)
    if done.returncode != 0 or not os.path.exists(os.path.join(run_dir, "index.html")):
        with open(log_path, encoding="utf-8", errors="replace") as fh:
            tail = fh.read()[-3000:]
        raise SystemExit(f"Blender failed on {blend} (log: {log_path}):\n{tail}")
    return run_dir


def _inside_blender(args_path):
    import addon_utils
    import bpy

    with open(args_path, encoding="utf-8") as fh:
        args = json.load(fh)
    for path in args["python_paths"] + [args["addon_dir"]]:
        if path not in sys.path:
            sys.path.insert(0, path)
    bpy.context.preferences.use_preferences_save = False
    if addon_utils.enable("bxdf_lab", default_set=False, handle_error=None) is None:
        raise SystemExit("the bxdf_lab add-on did not enable")
    from bxdf_lab import compare
    result = bpy.ops.bxdf_lab.compare_renders(directory=args["out"], size=args["size"],
                                              samples=args["samples"])
    print(f"compare_renders: {result}; report {compare.last_result.get('report')}")


if __name__ == "__main__" and "--" in sys.argv and "bpy" in sys.modules:
    _inside_blender(sys.argv[sys.argv.index("--") + 1])
