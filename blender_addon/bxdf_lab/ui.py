"""Panels: the material (drawn from the registry schema), a compact one under Cycles, and the
render settings. Stock panels that support BLENDER_RENDER also show for BXDF_LAB (as Cycles does)."""

import bpy

from . import api, fit_report, node_panel, properties
from .engine import BXDFLAB_RenderEngine
from .operators.presets import BXDFLAB_MT_presets

ENGINE = BXDFLAB_RenderEngine.bl_idname


def draw_params(layout, group, params):
    """Every parameter of a model in registry order, hiding those whose `when` does not hold."""
    values = {p.name: getattr(group, properties.attr_name(p.name), None) for p in params
              if p.kind != "list"}
    for p in params:
        if not p.relevant(values):
            continue
        if p.kind == "list":
            draw_list(layout, group, p)
        else:
            layout.prop(group, properties.attr_name(p.name))


def draw_list(layout, group, param):
    box = layout.box()
    row = box.row()
    row.label(text=param.name.replace("_", " ").capitalize())
    row.operator("bxdf_lab.list_add", text="", icon="ADD").param = param.name
    for i, element in enumerate(getattr(group, properties.attr_name(param.name))):
        sub = box.column(align=True)
        header = sub.row()
        header.label(text=f"{i + 1}")
        remove = header.operator("bxdf_lab.list_remove", text="", icon="X")
        remove.param, remove.index = param.name, i
        draw_params(sub, element, param.fields)


def draw_status(layout, material):
    """The registry's verdict on the stored values: an error names the parameter and range."""
    try:
        api.make(material)
    except ValueError as exc:
        col = layout.column()
        col.alert = True
        col.label(text=str(exc), icon="ERROR")


def draw_fit_report(layout, material):
    """The last "Fit to Measured File" of this material and its error, flagged once the
    parameters have been edited (the error then no longer describes them)."""
    summary = fit_report.summary(material)
    if not summary:
        return
    layout.label(text=summary, icon="INFO")
    if not fit_report.is_current(material):
        layout.label(text="Parameters changed since this fit", icon="ERROR")


class BXDFLAB_PT_material(bpy.types.Panel):
    bl_label = "BxDF Lab"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"
    COMPAT_ENGINES = {ENGINE}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES and context.material is not None

    def draw(self, context):
        material = context.material
        settings = material.bxdf_lab
        source = node_panel.draw_source(self.layout, material)
        layout = self.layout.column()
        layout.active = source == "MODEL"  # the model stays editable, greyed while unused
        layout.use_property_split = True
        row = layout.row(align=True)
        row.prop(settings, "model")
        row.menu(BXDFLAB_MT_presets.bl_idname, text="", icon="PRESET")
        model = properties.MODELS[settings.model]
        if model.doc:
            layout.label(text=model.doc)
        draw_params(layout, properties.model_group(settings), model.params)
        draw_status(layout, material)
        col = layout.column(align=True)
        col.operator("bxdf_lab.bake_lobe_texture", icon="IMAGE_DATA")
        col.operator("bxdf_lab.add_lobe_mesh", icon="MESH_UVSPHERE")
        row = col.row(align=True)
        row.operator("bxdf_lab.import_material", text="Import JSON", icon="IMPORT")
        row.operator("bxdf_lab.export_material", text="Export JSON", icon="EXPORT")
        row.operator("bxdf_lab.fit_measured", text="Fit to Measured", icon="GRAPH")
        row = col.row(align=True)
        row.operator("bxdf_lab.set_up_cycles", icon="NODETREE")
        row.operator("bxdf_lab.set_up_povray")
        draw_fit_report(layout, material)
        for target in ("cycles", "pov"):
            label = getattr(settings, f"{target}_label")
            if label:
                layout.label(text=f"{target}: {label} — {getattr(settings, f'{target}_mapping')}")


class BXDFLAB_PT_material_cycles(bpy.types.Panel):
    """Compact: pick the BxDF Lab model and build the Cycles node tree closest to it."""
    bl_label = "BxDF Lab"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"
    bl_options = {"DEFAULT_CLOSED"}
    COMPAT_ENGINES = {"CYCLES"}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES and context.material is not None

    def draw(self, context):
        settings = context.material.bxdf_lab
        layout = self.layout
        layout.use_property_split = True
        layout.prop(settings, "model")
        model = properties.MODELS[settings.model]
        draw_params(layout.column(align=True), properties.model_group(settings), model.params)
        draw_status(layout, context.material)
        layout.operator("bxdf_lab.set_up_cycles", icon="NODETREE")
        if settings.cycles_label:
            layout.label(text=f"{settings.cycles_label}: {settings.cycles_mapping}")


class BXDFLAB_PT_render(bpy.types.Panel):
    bl_label = "BxDF Lab"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {ENGINE}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def draw(self, context):
        settings = context.scene.bxdf_lab_render
        layout = self.layout
        layout.use_property_split = True
        for name in ("samples", "max_bounces", "pixel_filter", "filter_width", "threads", "seed"):
            if name == "filter_width" and settings.pixel_filter == "PIXEL_CENTER":
                continue
            layout.prop(settings, name)
        layout.operator("bxdf_lab.compare_renders", icon="IMAGE_REFERENCE")


# Stock panels shown for BXDF_LAB too: those for the old internal renderer and the material slots.
_STOCK_EXTRA = {"EEVEE_MATERIAL_PT_context_material"}


def _stock_panels():
    for panel in bpy.types.Panel.__subclasses__():
        engines = getattr(panel, "COMPAT_ENGINES", None)
        if engines is not None and ("BLENDER_RENDER" in engines or panel.__name__ in _STOCK_EXTRA):
            yield panel


classes = (BXDFLAB_PT_material, BXDFLAB_PT_material_cycles, BXDFLAB_PT_render)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    for panel in _stock_panels():
        panel.COMPAT_ENGINES.add(ENGINE)


def unregister():
    for panel in _stock_panels():
        panel.COMPAT_ENGINES.discard(ENGINE)
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
