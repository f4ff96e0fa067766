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


class BXDFLAB_PT_missing_module(bpy.types.Panel):
    """Shown instead of the add-on's UI when the compiled module `bxdf` does not import."""
    bl_label = "BxDF Lab: module missing"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"

    def draw(self, _context):
        column = self.layout.column(align=True)
        column.alert = True
        for line in dependency.help_lines():
            column.label(text=line)


class BXDFLAB_PT_missing_module_material(BXDFLAB_PT_missing_module):
    bl_context = "material"


def _full_modules():
    from . import properties, render_settings, fit_report, engine, ui, operators
    return [properties, render_settings, fit_report, engine, operators, ui]


def register():
    bxdf = dependency.try_import()
    if bxdf is None:
        # No traceback: a panel in the Render and Material tabs says what to do.
        print("BxDF Lab: " + dependency.help_text())
        for cls in (BXDFLAB_PT_missing_module, BXDFLAB_PT_missing_module_material):
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
