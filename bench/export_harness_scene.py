"""Writes a harness scene as the add-on hands it to bxdf.render, for profiling outside Blender.

    blender -b --factory-startup --python-exit-code 1 --python bench/export_harness_scene.py -- \
        --scene cornell --out /tmp/cornell.pickle

Builds the scene as bench/side_by_side.py does (materials set up by the add-on for both engines),
renders it once with BXDF_LAB at 1 sample and keeps the scene data and settings the add-on passed
to bxdf.render (its export, node programs and all); generated world images go to a folder beside
the pickle (OUT without its extension, plus "-world"). bench/render_exported.py then renders that
file with /usr/bin/python3 alone, where `perf` and `valgrind --tool=callgrind` see only the
renderer: the harness scene's own instruction count, steady from run to run, unlike its time.
"""
import argparse
import os
import pickle
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="export_harness_scene.py", description=__doc__.splitlines()[0])
    p.add_argument("--scene", default="cornell", help="harness scene name (compare/scenes.py)")
    p.add_argument("--out", required=True, help="pickle file to write")
    return p.parse_args(argv)


def main():
    args = parse_args()
    if HERE not in sys.path:
        sys.path.insert(0, HERE)
    import side_by_side

    # Generated world images (the scene data names them) are kept beside the pickle.
    world_dir = os.path.splitext(os.path.abspath(args.out))[0] + "-world"
    os.makedirs(world_dir, exist_ok=True)
    spec, _ = side_by_side.set_up_scene(args.scene, None, world_dir)  # enables the add-on
    from bxdf_lab import renderer

    captured = {}
    original = renderer.render

    def capture(scene_data, settings, on_progress, partial_images=True):
        captured["scene"], captured["settings"] = scene_data, dict(settings)
        return original(scene_data, settings, on_progress, partial_images)

    renderer.render = capture
    try:
        work = tempfile.mkdtemp(prefix="bxdf-export-")
        side_by_side.render("BXDF_LAB", spec, 1, 1, 2, os.path.join(work, "one.exr"))
        os.rmdir(work)  # render() removes the image it read
    finally:
        renderer.render = original
    if "scene" not in captured:
        sys.exit("export_harness_scene: the BXDF_LAB render did not reach bxdf.render")
    with open(args.out, "wb") as f:
        pickle.dump({"harness_scene": args.scene, "scene": captured["scene"],
                     "settings": captured["settings"]}, f)
    print(f"export_harness_scene: {args.scene} written to {args.out}")


if __name__ == "__main__":
    main()
