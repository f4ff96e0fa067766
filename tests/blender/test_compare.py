""""Compare Renders" on a two-material scene: each engine renders at the preview size into the
chosen folder, the labelled figure becomes a Blender image, the HTML report gives each material's
pairing label and why, and the scene's settings and add-ons are as they were."""

import math
import os

import addon_utils
import bpy
import numpy as np

from bxdf_lab import api, compare


def _plane(name, material, x):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(x - 5, -5, 0), (x + 5, -5, 0), (x + 5, 5, 0), (x - 5, 5, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    bpy.context.scene.collection.objects.link(bpy.data.objects.new(name, mesh))


def _two_material_scene():
    scene = bpy.context.scene
    paired = bpy.data.materials.new("Paired")
    api.assign(paired, "lambertian", reflectance=(0.6, 0.4, 0.2))
    with bpy.context.temp_override(material=paired):
        assert bpy.ops.bxdf_lab.set_up_cycles() == {"FINISHED"}
        assert bpy.ops.bxdf_lab.set_up_povray() == {"FINISHED"}
    own_nodes = bpy.data.materials.new("Own Nodes")
    own_nodes.use_nodes = True  # a Principled BSDF of its own, never set up from the model
    api.assign(own_nodes, "oren_nayar", sigma=20.0)  # BxDF Lab renders this model, not the tree
    node_tree = bpy.data.materials.new("Node Tree")
    node_tree.use_nodes = True  # a default Principled BSDF, which both engines render
    _plane("left", paired, -5)
    _plane("right", own_nodes, 5)
    _plane("out of view", node_tree, 100)
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy, sun.angle = math.pi, 0.0
    scene.collection.objects.link(bpy.data.objects.new("sun", sun))
    cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
    cam.location = (0, 0, 12)
    scene.collection.objects.link(cam)
    scene.camera = cam
    scene.render.resolution_x, scene.render.resolution_y = 640, 320
    scene.render.resolution_percentage = 100
    return scene, paired, own_nodes


def test_compare_renders_a_two_material_scene_into_a_labelled_result(tmp_path, bxdf):
    scene, paired, own_nodes = _two_material_scene()
    povray_was_enabled = addon_utils.check("render_povray")[1]
    before = (scene.render.engine, scene.render.filepath, scene.render.resolution_percentage,
              scene.cycles.samples, scene.bxdf_lab_render.samples, paired.use_nodes)
    folder = str(tmp_path / "chosen")

    assert bpy.ops.bxdf_lab.compare_renders(directory=folder, size=32, samples=4) == {"FINISHED"}

    result = compare.last_result
    assert [(e, ok) for e, ok, _ in result["results"]] == [(e, True) for e in compare.ENGINES], result
    for engine_id in compare.ENGINES:  # at the preview size: 640×320 scaled to 32×16
        image = compare.load_exr(os.path.join(folder, f"{engine_id.lower()}.exr"))
        assert image.shape == (16, 32, 4), engine_id
    figure = bpy.data.images[compare.RESULT_IMAGE]
    assert figure.size[0] > 0 and os.path.exists(result["figure"])
    # The paired Lambertian half: BxDF Lab and Cycles agree (exact, radiance = R); the whole
    # image's energy agrees only as far as the unpaired half does.
    numbers = result["numbers"][("BXDF_LAB", "CYCLES")]
    assert numbers["rmse"] >= 0.0 and math.isfinite(numbers["energy_ratio"])
    bxdf_image = compare.load_exr(os.path.join(folder, "bxdf_lab.exr"))
    cycles_image = compare.load_exr(os.path.join(folder, "cycles.exr"))
    np.testing.assert_allclose(bxdf_image[:, 2:14, :3], cycles_image[:, 2:14, :3], rtol=0.02, atol=2e-3)
    np.testing.assert_allclose(bxdf_image[:, 2:14, :3].mean(axis=(0, 1)), (0.6, 0.4, 0.2), rtol=0.02)

    # Each pairing follows what the engines render: Cycles the node tree, BxDF Lab the model set
    # by the panel or the node tree.
    labels = {p["material"]: p for p in result["pairings"]}
    assert labels["Paired"]["CYCLES"][0] == "exact"
    assert labels["Own Nodes"]["CYCLES"][0] == "unsupported"
    assert "BxDF Lab renders the panel's model (oren_nayar)" in labels["Own Nodes"]["CYCLES"][1]
    assert labels["Own Nodes"]["POVRAY_RENDER"][0] == "unsupported"
    assert labels["Node Tree"]["CYCLES"] == ("exact", "both render its node tree")
    with open(result["report"], encoding="utf-8") as f:
        page = f.read()
    for text in ("Paired", "Own Nodes", "Node Tree", "exact", "unsupported", "both render its node tree",
                 "comparison.png", "Node coverage", "Principled BSDF", "ShaderNodeBsdfPrincipled"):
        assert text in page, text
    coverage = {p["material"]: p["coverage"] for p in result["pairings"]}
    assert {n["status"] for n in coverage["Node Tree"]} == {"exact"}
    assert {n["status"] for n in coverage["Paired"]} == {"exact"}
    # A tree BxDF Lab does not render is one entry naming its nodes, not a row per node.
    assert len(coverage["Own Nodes"]) == 1 and coverage["Own Nodes"][0]["status"] == "unsupported"
    assert "Principled BSDF" in coverage["Own Nodes"][0]["node"]
    assert "not rendered by BxDF Lab" in coverage["Own Nodes"][0]["why"]

    after = (scene.render.engine, scene.render.filepath, scene.render.resolution_percentage,
             scene.cycles.samples, scene.bxdf_lab_render.samples, paired.use_nodes)
    assert after == before
    assert addon_utils.check("render_povray")[1] == povray_was_enabled  # enabled for the run only


def test_compare_renders_needs_a_folder():
    _two_material_scene()
    import pytest
    with pytest.raises(RuntimeError, match="choose an output folder"):
        bpy.ops.bxdf_lab.compare_renders(directory="")
