"""The add-on registers and unregisters cleanly, and without `bxdf` says what to do."""

import sys

import addon_utils
import bpy
import pytest

from bxdf_lab import dependency


def _registered(name):
    return hasattr(bpy.types, name)


def test_enable_registers_engine_properties_and_panels():
    assert "BXDF_LAB" in {e.bl_idname for e in bpy.types.RenderEngine.__subclasses__()}
    assert hasattr(bpy.types.Material, "bxdf_lab")
    assert hasattr(bpy.types.Scene, "bxdf_lab_render")
    for cls in ("BXDFLAB_PT_material", "BXDFLAB_PT_material_cycles", "BXDFLAB_PT_render"):
        assert _registered(cls), cls
    operators = set(dir(bpy.ops.bxdf_lab))
    assert {"bake_lobe_texture", "add_lobe_mesh", "set_up_cycles", "set_up_povray",
            "compare_renders", "apply_preset", "import_material", "export_material"} <= operators
    assert "BXDF_LAB" in bpy.types.RENDER_PT_format.COMPAT_ENGINES


def test_disable_removes_everything_and_enable_restores_it():
    addon_utils.disable("bxdf_lab", default_set=True)
    try:
        assert not hasattr(bpy.types.Material, "bxdf_lab")
        assert not hasattr(bpy.types.Scene, "bxdf_lab_render")
        assert not _registered("BXDFLAB_PT_material")
        assert not _registered("BXDFLAB_PG_material")
        assert not any(name.startswith("BXDFLAB_") for name in dir(bpy.types))
        assert not set(dir(bpy.ops.bxdf_lab))
        assert "BXDF_LAB" not in bpy.types.RENDER_PT_format.COMPAT_ENGINES
    finally:
        assert addon_utils.enable("bxdf_lab", default_set=True, handle_error=None) is not None
    material = bpy.data.materials.new("after re-enable")
    assert material.bxdf_lab.model in bpy.types.Material.bl_rna.properties["bxdf_lab"].fixed_type \
        .properties["model"].enum_items.keys()


def test_without_the_module_a_panel_explains_which_python_and_command():
    addon_utils.disable("bxdf_lab", default_set=True)
    saved_module, saved_import = sys.modules.get("bxdf"), dependency.bxdf
    sys.modules["bxdf"] = None  # makes `import bxdf` raise ImportError
    dependency.bxdf = None
    try:
        assert addon_utils.enable("bxdf_lab", default_set=True, handle_error=None) is not None
        for tab in ("", "_material"):  # at the top of the Render and the Material tab
            panel = getattr(bpy.types, "BXDFLAB_PT_missing_module" + tab)
            assert panel.bl_order < 0
            # Not a subclass of another registered panel (Blender could not call its draw).
            assert not any(issubclass(panel, other) for other in bpy.types.Panel.__subclasses__()
                           if other is not panel and other.__name__.startswith("BXDFLAB_"))
        assert not hasattr(bpy.types.Material, "bxdf_lab")
        # The engine stays in the list and says why it cannot render.
        engines = {e.bl_idname: e for e in bpy.types.RenderEngine.__subclasses__()}
        assert "missing" in engines["BXDF_LAB"].bl_label
        scene = bpy.context.scene
        scene.camera = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
        scene.collection.objects.link(scene.camera)
        scene.render.engine = "BXDF_LAB"
        scene.render.resolution_x = scene.render.resolution_y = 8
        with pytest.raises(RuntimeError, match="make install-addon"):
            bpy.ops.render.render()
        text = dependency.help_text()
        assert "/usr/bin/python3" in text and "3.11" in text and "make install-addon" in text
        assert "Error: import of bxdf halted" in text  # the import's own message is shown
        addon_utils.disable("bxdf_lab", default_set=True)
        assert not _registered("BXDFLAB_PT_missing_module")
    finally:
        sys.modules["bxdf"] = saved_module
        dependency.bxdf = saved_import
        assert addon_utils.enable("bxdf_lab", default_set=True, handle_error=None) is not None
    assert hasattr(bpy.types.Material, "bxdf_lab")
