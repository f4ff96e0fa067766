"""Material source: a material renders from its node tree unless its BxDF Lab model was set;
files saved before the switch existed keep rendering from their model."""

import os

import bpy
import pytest

from bxdf_lab import api, export, material_source

DATA = os.path.join(os.path.dirname(__file__), "data")


def test_a_file_saved_before_the_switch_keeps_its_panel_materials():
    # Saved by the add-on as it was before the switch (see data/README.md): "assigned" through
    # api.assign, "param_edited" with only a parameter edited in the panel, "panel_viewed" only
    # displayed by the panel, "never_touched" never seen by BxDF Lab.
    bpy.ops.wm.open_mainfile(filepath=os.path.join(DATA, "materials_before_source.blend"))
    sources = {m.name: material_source.source(m) for m in bpy.data.materials}
    assert sources == {"assigned": "MODEL", "param_edited": "MODEL", "panel_viewed": "NODES",
                       "never_touched": "NODES"}
    assert api.describe(bpy.data.materials["assigned"])[0] == "oren_nayar"


def test_new_materials_render_their_nodes_and_assign_switches_to_the_model(material):
    assert material_source.source(material) == "NODES"
    material.bxdf_lab.lambertian.reflectance[0]  # reading stores nothing
    assert material_source.source(material) == "NODES"
    api.assign(material, "lambertian", reflectance=(0.5, 0.5, 0.5))
    assert material_source.source(material) == "MODEL"
    material_source.set_source(material, "NODES")
    assert material_source.source(material) == "NODES"
    with pytest.raises(ValueError, match="'PANEL' is not one of NODES, MODEL"):
        material_source.set_source(material, "PANEL")


def test_the_operator_switches_the_active_material(material):
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.set_material_source(source="MODEL") == {"FINISHED"}
    assert material_source.source(material) == "MODEL" and material.bxdf_lab.source == "MODEL"


def _scene_with(material):
    mesh = bpy.data.meshes.new("plane")
    mesh.from_pydata([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    obj = bpy.data.objects.new("plane", mesh)
    bpy.context.scene.collection.objects.link(obj)
    return export.export_scene(bpy.context.evaluated_depsgraph_get())


def test_export_follows_the_source(material):
    material.use_nodes = True
    material.node_tree.nodes["Principled BSDF"].inputs["Roughness"].default_value = 0.25
    api.assign(material, "oren_nayar", sigma=10.0)
    (entry,) = _scene_with(material)["materials"]
    assert entry["model"] == "oren_nayar" and "graph" not in entry
    material_source.set_source(material, "NODES")
    (entry,) = _scene_with(material)["materials"]
    (closure,) = entry["graph"]["closures"]
    assert closure["model"] == "cycles_principled" and closure["params"]["roughness"] == 0.25
