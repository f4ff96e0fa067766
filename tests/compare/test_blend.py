"""`python3 -m compare run --blend FILE.blend` on a saved two-material scene: the three engines
render it at the preview size, and the report gives each material's pairing label and the node
coverage table."""
import glob
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

MAKE_SCENE = r"""
import os, sys, bpy
sys.path.insert(0, sys.argv[-2])
sys.path[:0] = [p for p in os.environ.get("BXDF_PYTHONPATH", "").split(os.pathsep) if p]
import addon_utils
addon_utils.enable("bxdf_lab", default_set=False, handle_error=None)
from bxdf_lab import api
scene = bpy.context.scene
cube = bpy.data.objects["Cube"]
panel = bpy.data.materials.new("Panel Only")
api.assign(panel, "oren_nayar", sigma=20.0)
cube.data.materials[0] = panel
bpy.ops.mesh.primitive_plane_add(size=6, location=(0, 0, -1))
floor = bpy.context.object
nodes = bpy.data.materials.new("Node Tree")
nodes.use_nodes = True
floor.data.materials.append(nodes)
bpy.ops.wm.save_as_mainfile(filepath=sys.argv[-1])
"""


def test_blend_renders_a_saved_scene_with_the_coverage_table(tmp_path):
    blend = str(tmp_path / "two_materials.blend")
    build_python = [p for p in os.environ.get("BXDF_PYTHONPATH", "").split(os.pathsep) if p]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([ROOT] + build_python))
    script = tmp_path / "make_scene.py"
    script.write_text(MAKE_SCENE)
    subprocess.run(["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python", str(script),
                    "--", os.path.join(ROOT, "blender_addon"), blend],
                   check=True, capture_output=True, env=dict(env, BXDF_PYTHONPATH=os.pathsep.join(build_python)),
                   timeout=300)
    out = tmp_path / "out"
    run = subprocess.run([sys.executable, "-m", "compare", "run", "--blend", blend, "--size", "24",
                          "--spp", "4", "--out", str(out)],
                         cwd=ROOT, env=env, capture_output=True, text=True, timeout=900)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    (run_dir,) = glob.glob(str(out / "*"))
    for engine in ("bxdf_lab", "cycles", "povray_render"):
        assert os.path.exists(os.path.join(run_dir, f"{engine}.exr")), engine
    assert os.path.exists(os.path.join(run_dir, "comparison.png"))
    with open(os.path.join(run_dir, "index.html"), encoding="utf-8") as fh:
        page = fh.read()
    assert "Panel Only" in page and "Node Tree" in page and "Node coverage" in page
    assert "ShaderNodeBsdfPrincipled" in page and "both render its node tree" in page
    assert "unsupported" in page and "24 px" in page.replace("\n", " ")
