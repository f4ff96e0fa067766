"""BxDF Lab: reflection models from the BxDF Lab library as a Blender render engine.

Material tab: pick a model and its parameters (generated from the model registry), bake lobe
textures, add a 3D lobe plot, set up the closest Cycles or POV-Ray material. Render tab: the
BXDF_LAB engine's settings. Scripting: `bxdf_lab.api.assign(material, "oren_nayar", sigma=20.0)`.
"""

bl_info = {
    "name": "BxDF Lab",
    "author": "BxDF Lab authors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Render (engine BxDF Lab) and Properties > Material",
    "description": "Textbook reflection models: material panel, lobe baking, render engine, "
                   "Cycles/POV-Ray comparison",
    "warning": "",
    "doc_url": "",
    "category": "Render",
}

import bpy

from . import dependency

# Modules registered when `bxdf` imports, in order (later ones use earlier ones' classes).
_modules = []
_fallback_classes = []


class MissingModulePanel:
    """Shown instead of the add-on's UI when the compiled module `bxdf` does not import: first in
    its tab, each line wrapped to the panel's width. A mix-in, not a Panel: Blender cannot call
    a registered Panel subclass of another registered Panel (bpy_class_call: unable to get
    Python class for RNA struct)."""
    bl_label = "BxDF Lab: module missing"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_order = -1000  # above the stock panels

    def draw(self, context):
        import textwrap
        column = self.layout.column(align=True)
        column.alert = True
        chars = max(20, int(getattr(context.region, "width", 300) / 7.0) - 4)
        for line in dependency.help_lines():
            for i, part in enumerate(textwrap.wrap(line, chars)):
                column.label(text=part, icon="ERROR" if i == 0 else "BLANK1")


class BXDFLAB_PT_missing_module(MissingModulePanel, bpy.types.Panel):
    bl_context = "render"


class BXDFLAB_PT_missing_module_material(MissingModulePanel, bpy.types.Panel):
    bl_context = "material"


class BXDFLAB_RenderEngine_missing_module(bpy.types.RenderEngine):
    """Keeps "BxDF Lab" in the engine list (and scenes set to it) while the module is missing;
    a render says why it cannot run."""
    bl_idname = "BXDF_LAB"
    bl_label = "BxDF Lab (module missing)"

    def render(self, _depsgraph):
        self.report({"ERROR"}, dependency.help_text())


def _full_modules():
    from . import properties, render_settings, fit_report, engine, ui, operators
    return [properties, render_settings, fit_report, engine, operators, ui]


def register():
    bxdf = dependency.try_import()
    if bxdf is None:
        # No traceback: a panel in the Render and Material tabs says what to do.
        print("BxDF Lab: " + dependency.help_text())
        for cls in (BXDFLAB_PT_missing_module, BXDFLAB_PT_missing_module_material,
                    BXDFLAB_RenderEngine_missing_module):
            bpy.utils.register_class(cls)
            _fallback_classes.append(cls)
        return
    _modules[:] = _full_modules()
    for module in _modules:
        module.register()


def unregister():
    for module in reversed(_modules):
        module.unregister()
    _modules.clear()
    for cls in reversed(_fallback_classes):
        bpy.utils.unregister_class(cls)
    _fallback_classes.clear()
