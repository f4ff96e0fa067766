"""Runs inside Blender: builds one scene, sets it up for one engine, renders it once per seed.

    blender -b --factory-startup --python-exit-code 1 --python compare/driver.py -- JOB.json

JOB.json (written by jobs.py): scene, engine, spp (per render), seeds, resolution, out_dir, threads,
repo_root, python_paths, overrides. Writes <out_dir>/<ENGINE>_seed<k>.exr (POV-Ray: <ENGINE>.png,
linear 16-bit) and <out_dir>/<ENGINE>.meta.json; any error leaves the exit code non-zero."""
import json
import os
import shutil
import sys
import time


def _job_from_argv():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 1:
        raise SystemExit("usage: blender -b ... --python compare/driver.py -- JOB.json")
    with open(argv[0], encoding="utf-8") as fh:
        return json.load(fh)


def enable_addons(job):
    import addon_utils
    import bpy

    enabled = {}
    if job["engine"] == "POVRAY_RENDER":
        enabled["render_povray"] = addon_utils.enable("render_povray", default_set=True) is not None
    addon_dir = os.path.join(job["repo_root"], "blender_addon")
    if os.path.isdir(os.path.join(addon_dir, "bxdf_lab")):
        if addon_dir not in sys.path:
            sys.path.append(addon_dir)
        enabled["bxdf_lab"] = addon_utils.enable("bxdf_lab", default_set=True) is not None
        enabled["bxdf_lab_full"] = hasattr(bpy.types.Material, "bxdf_lab")
    return enabled


def _apply_overrides(spec, overrides):
    """{material name: {param: value}}: replaces parameters of this engine's materials only (a
    deliberately wrong material, to check that the diffs catch it)."""
    if not overrides:
        return spec
    from dataclasses import replace

    def fix(obj):
        changes = overrides.get(obj.material.name)
        if not changes:
            return obj
        params = dict(obj.material.params)
        params.update({k: tuple(v) if isinstance(v, list) else v for k, v in changes.items()})
        return replace(obj, material=replace(obj.material, params=params))
    return replace(spec, objects=tuple(fix(o) for o in spec.objects))


def raise_engine_error(engine, seed):
    """Blender swallows exceptions inside RenderEngine.render and may still write an (empty)
    image: the BXDF_LAB engine records its error in bxdf_lab.engine.last_error."""
    if engine != "BXDF_LAB":
        return
    module = sys.modules.get("bxdf_lab.engine")
    error = getattr(module, "last_error", "") if module else ""
    if error:
        raise RuntimeError(f"BXDF_LAB render failed for seed {seed}: {error}")


def main():
    job = _job_from_argv()
    for path in [job["repo_root"]] + job.get("python_paths", []):
        if path not in sys.path:
            sys.path.insert(0, path)
    import bpy

    from compare import bpy_build, engine_setup, material_setup, scenes

    engine = job["engine"]
    out_dir = job["out_dir"]
    os.makedirs(out_dir, exist_ok=True)
    meta = {"scene": job["scene"], "engine": engine, "blender": bpy.app.version_string,
            "renders": []}
    meta_path = os.path.join(out_dir, f"{engine}.meta.json")

    meta["addons"] = enable_addons(job)
    spec = scenes.get(job["scene"])
    spec = _apply_overrides(spec, job.get("overrides", {}).get(engine, {}))
    if job.get("resolution"):
        from dataclasses import replace
        spec = replace(spec, resolution=tuple(job["resolution"]))

    bpy_build.clear_scene()
    materials = {m.name: bpy.data.materials.new(m.name) for m in spec.materials()}
    objects = bpy_build.build(spec, materials, out_dir)
    engine_setup.common_settings(spec)

    meta["materials"] = {}
    for mat_spec in spec.materials():
        owner = next(objects[o.name] for o in spec.objects if o.material.name == mat_spec.name)
        addon_label = material_setup.setup(materials[mat_spec.name], owner, mat_spec.model,
                                           mat_spec.params, engine)
        meta["materials"][mat_spec.name] = {
            "model": mat_spec.model, "params": mat_spec.params, "addon_label": addon_label,
            "renders_as": material_setup.summarize(materials[mat_spec.name], engine)}

    scene = bpy.context.scene
    if engine == "POVRAY_RENDER":
        basename = f"{job['scene']}_pov"
        meta["settings"] = engine_setup.configure_povray(spec, out_dir, basename, job["threads"])
        start = time.perf_counter()
        bpy.ops.render.render(write_still=False)
        seconds = time.perf_counter() - start
        produced = os.path.join(out_dir, "povray_files", basename + ".png")
        if not os.path.isfile(produced):
            raise RuntimeError(f"POV-Ray produced no image at {produced}")
        image = os.path.join(out_dir, f"{engine}.png")
        shutil.move(produced, image)
        meta["renders"].append({"seed": None, "seconds": seconds, "image": os.path.basename(image)})
    else:
        configure = (engine_setup.configure_cycles if engine == "CYCLES"
                     else engine_setup.configure_bxdf_lab)
        for seed in job["seeds"]:
            meta["settings"] = configure(spec, job["spp"], seed, job["threads"])
            image = os.path.join(out_dir, f"{engine}_seed{seed}.exr")
            scene.render.filepath = image
            start = time.perf_counter()
            bpy.ops.render.render(write_still=True)
            seconds = time.perf_counter() - start
            raise_engine_error(engine, seed)
            if not os.path.isfile(image):
                # Exceptions inside a RenderEngine are swallowed by Blender: no file is the sign.
                raise RuntimeError(f"{engine} wrote no image (render failed) for seed {seed}")
            meta["renders"].append({"seed": seed, "seconds": seconds,
                                    "image": os.path.basename(image)})
        # One record for all seeds: samples are per render; the full image has len(seeds) times
        # as many.
        meta["settings"].pop("seed", None)
        meta["settings"]["seeds"] = job["seeds"]
        meta["settings"]["samples_per_render"] = meta["settings"].pop("samples")
        meta["settings"]["samples_total"] = job["spp"] * len(job["seeds"])
    with open(meta_path, "w", encoding="utf-8") as fh:
        json.dump(meta, fh, indent=1)


if __name__ == "__main__":
    # Run as a script by Blender: the package comes from the repository this file is in.
    _root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    if _root not in sys.path:
        sys.path.insert(0, _root)
    from compare import blender_main
    blender_main.run(main)
