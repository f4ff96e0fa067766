"""Panels: the material (drawn from the registry schema), a compact one under Cycles, and the
render settings. Stock panels that support BLENDER_RENDER also show for BXDF_LAB (as Cycles does)."""

import re
import textwrap

import bpy

from . import api, fit_report, node_panel, properties, render_report, renderer
from .engine import BXDFLAB_RenderEngine
from .operators.presets import BXDFLAB_MT_presets

ENGINE = BXDFLAB_RenderEngine.bl_idname


# Average width of a character of the UI font at scale 1, in pixels: how much text fits a line.
CHAR_WIDTH = 7.0
LABEL_INSET = 80.0  # px at UI scale 1 (a 222 px region leaves ~140 px of text in a box)


def wrapped_labels(layout, text, width, icon="NONE"):
    """`text` as labels that fit `width` pixels (Blender cuts a long label with "…")."""
    scale = bpy.context.preferences.view.ui_scale if bpy.context.preferences else 1.0
    # The label's own width: the region less the panel's and a box's margins and the icon.
    chars = max(12, int((width - LABEL_INSET * scale) / (CHAR_WIDTH * scale)))
    column = layout.column(align=True)
    for i, line in enumerate(textwrap.wrap(text, chars) or [""]):
        column.label(text=line, icon=icon if i == 0 else "BLANK1")
    return column


def region_width(context):
    region = getattr(context, "region", None)
    return region.width if region is not None else 300


def draw_params(layout, group, params, bad=()):
    """Every parameter of a model in registry order, hiding those whose `when` does not hold;
    those named in `bad` are drawn highlighted (red)."""
    values = {p.name: getattr(group, properties.attr_name(p.name), None) for p in params
              if p.kind != "list"}
    for p in params:
        if not p.relevant(values):
            continue
        if p.kind == "list":
            draw_list(layout, group, p, bad)
        else:
            row = layout.row()
            row.alert = p.name in bad
            row.prop(group, properties.attr_name(p.name))


def draw_list(layout, group, param, bad=()):
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
        draw_params(sub, element, param.fields, bad)


def model_error(material):
    """(message, names of the parameters it is about) of the registry's verdict on the stored
    values, or ("", set()) when they are valid."""
    try:
        api.make(material)
    except ValueError as exc:
        message = str(exc)
        model = properties.MODELS[material.bxdf_lab.model]
        names = {p.name for p in model.params} | {f.name for p in model.params for f in p.fields}
        quoted = set(re.findall(r"'([A-Za-z_][A-Za-z0-9_]*)'", message))
        words = set(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", message))
        return message, (names & quoted) or (names & words)
    return "", set()


def draw_status(layout, message, width):
    """The registry's error, whole (it names the parameter, the value and the range)."""
    if message:
        col = layout.column()
        col.alert = True
        wrapped_labels(col, message, width, icon="ERROR")


def draw_last_renders(layout, width, material=None):
    """The last F12 and viewport renders' summaries, errors and warnings (those that name
    `material` when one is given)."""
    for kind, title in (("render", "Last render"), ("viewport", "Viewport")):
        report = render_report.last(kind)
        if report is None:
            continue
        messages = report.naming(material.name) if material is not None else report.messages()
        if material is not None and not messages:
            continue
        box = layout.box()
        # The summary (size, samples, times) is as long as a warning: wrapped, not cut.
        wrapped_labels(box, f"{title} ({report.scene}): {report.summary}" if report.summary
                       else f"{title} ({report.scene})", width, icon="RENDER_RESULT")
        for level, text in messages:
            col = box.column()
            col.alert = level == "ERROR"
            wrapped_labels(col, text, width, icon="ERROR" if level == "ERROR" else "INFO")


# An F12 render records its report on the render thread, where tagging areas for redraw is not
# safe, so the Render tab kept showing the previous render until the mouse passed over it. A
# main-thread timer redraws the Properties editors (the Render and Material tabs show the
# reports) when a new report has been recorded.
REPORT_REDRAW_INTERVAL = 0.5
_reports_drawn = 0


def redraw_after_new_report():
    """bpy.app.timers callback: tags every Properties editor for redraw after a new report."""
    global _reports_drawn
    recorded = render_report.recorded()
    if recorded != _reports_drawn:
        _reports_drawn = recorded
        for window in bpy.context.window_manager.windows:
            for area in window.screen.areas:
                if area.type == "PROPERTIES":
                    area.tag_redraw()
    return REPORT_REDRAW_INTERVAL


def draw_fit_report(layout, material):
    """The last "Fit to Measured File" of this material and its error, flagged once the
    parameters have been edited (the error then no longer describes them)."""
    summary = fit_report.summary(material)
    if not summary:
        return
    layout.label(text=summary, icon="INFO")
    if not fit_report.is_current(material):
        layout.label(text="Parameters changed since this fit", icon="ERROR")


class MaterialPanel:
    """A panel of the Material tab, shown for the engines in COMPAT_ENGINES (a mix-in: Blender
    cannot call a registered Panel subclass of another registered Panel)."""
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"
    COMPAT_ENGINES = {ENGINE}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES and context.material is not None


class BXDFLAB_PT_material_preview(MaterialPanel, bpy.types.Panel):
    """The material preview, rendered by the BXDF_LAB engine on Blender's preview scene (open by
    default: it is the quickest look at a model)."""
    bl_label = "Preview"

    def draw(self, context):
        self.layout.template_preview(context.material)


class BXDFLAB_PT_material(MaterialPanel, bpy.types.Panel):
    bl_label = "BxDF Lab"

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
        width = region_width(context)
        if model.doc:
            wrapped_labels(layout, model.doc, width)
        error, bad = model_error(material)
        draw_params(layout, properties.model_group(settings), model.params, bad)
        draw_status(layout, error, width)
        col = layout.column(align=True)
        col.operator("bxdf_lab.bake_lobe_texture", icon="IMAGE_DATA")
        col.operator("bxdf_lab.add_lobe_mesh", icon="MESH_UVSPHERE")
        row = col.row(align=True)
        row.operator("bxdf_lab.import_material", text="Import", icon="IMPORT")
        row.operator("bxdf_lab.export_material", text="Export", icon="EXPORT")
        col.operator("bxdf_lab.fit_measured", text="Fit to Measured File", icon="GRAPH")
        row = col.row(align=True)
        row.label(text="Set Up")
        row.operator("bxdf_lab.set_up_cycles", text="Cycles", icon="NODETREE")
        row.operator("bxdf_lab.set_up_povray", text="POV-Ray")
        draw_fit_report(layout, material)
        for target, name in (("cycles", "Cycles"), ("pov", "POV-Ray")):
            label = getattr(settings, f"{target}_label")
            if label:
                wrapped_labels(layout, f"{name}: {label} — {getattr(settings, f'{target}_mapping')}",
                               width, icon="NODETREE")
        draw_last_renders(layout, width, material)


class BXDFLAB_PT_material_cycles(MaterialPanel, bpy.types.Panel):
    """Compact: pick the BxDF Lab model and build the Cycles node tree closest to it."""
    bl_label = "BxDF Lab"
    bl_options = {"DEFAULT_CLOSED"}
    COMPAT_ENGINES = {"CYCLES"}

    def draw(self, context):
        settings = context.material.bxdf_lab
        layout = self.layout
        layout.use_property_split = True
        layout.prop(settings, "model")
        model = properties.MODELS[settings.model]
        width = region_width(context)
        error, bad = model_error(context.material)
        draw_params(layout.column(align=True), properties.model_group(settings), model.params, bad)
        draw_status(layout, error, width)
        layout.operator("bxdf_lab.set_up_cycles", icon="NODETREE")
        if settings.cycles_label:
            wrapped_labels(layout, f"{settings.cycles_label}: {settings.cycles_mapping}", width)


RENDER_SETTINGS = ("samples", "preview_samples", "viewport_samples", "max_bounces", "pixel_filter",
                   "filter_width", "threads", "seed")


# The sample counts that Cycles' adaptive sampling settings of a purpose go with
# (renderer.CYCLES_ADAPTIVE_SAMPLING), drawn around them as Cycles' Sampling panel draws them.
ADAPTIVE_SAMPLES = {"samples": "final", "viewport_samples": "viewport"}


def draw_noise_threshold(layout, cycles, purpose):
    use, threshold, _ = renderer.CYCLES_ADAPTIVE_SAMPLING[purpose]
    row = layout.column(align=True, heading="Noise Threshold").row(align=True)
    row.prop(cycles, use, text="")
    sub = row.row()
    sub.active = getattr(cycles, use)
    sub.prop(cycles, threshold, text="")


def draw_min_samples(layout, cycles, purpose):
    use, _, minimum = renderer.CYCLES_ADAPTIVE_SAMPLING[purpose]
    row = layout.row()
    row.active = getattr(cycles, use)
    row.prop(cycles, minimum, text="Min Samples")


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
        cycles = getattr(context.scene, "cycles", None)
        for name in RENDER_SETTINGS:
            if name == "filter_width" and settings.pixel_filter == "PIXEL_CENTER":
                continue
            purpose = ADAPTIVE_SAMPLES.get(name)
            if purpose and cycles is not None:  # Cycles' Noise Threshold, which both renderers read
                draw_noise_threshold(layout, cycles, purpose)
            layout.prop(settings, name)
            if purpose and cycles is not None:
                draw_min_samples(layout, cycles, purpose)
            if name == "viewport_samples":  # Blender's own setting, which Cycles' viewport reads too
                layout.prop(context.scene.render, "preview_pixel_size", text="Viewport Pixel Size")
        if cycles is not None:  # the Light Paths settings both renderers read
            layout.prop(cycles, "min_light_bounces")
            layout.prop(cycles, "transparent_max_bounces")
        row = layout.row(align=True)
        row.operator("bxdf_lab.compare_renders", icon="IMAGE_REFERENCE")
        row.operator("bxdf_lab.open_compare_report", text="", icon="URL")
        draw_last_renders(layout, region_width(context))


# Stock panels shown for BXDF_LAB too: those for the old internal renderer and the material slots.
_STOCK_EXTRA = {"EEVEE_MATERIAL_PT_context_material"}


def _stock_panels():
    for panel in bpy.types.Panel.__subclasses__():
        engines = getattr(panel, "COMPAT_ENGINES", None)
        if engines is not None and ("BLENDER_RENDER" in engines or panel.__name__ in _STOCK_EXTRA):
            yield panel


classes = (BXDFLAB_PT_material_preview, BXDFLAB_PT_material, BXDFLAB_PT_material_cycles,
           BXDFLAB_PT_render)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    for panel in _stock_panels():
        panel.COMPAT_ENGINES.add(ENGINE)
    bpy.app.timers.register(redraw_after_new_report, first_interval=REPORT_REDRAW_INTERVAL,
                            persistent=True)


def unregister():
    if bpy.app.timers.is_registered(redraw_after_new_report):
        bpy.app.timers.unregister(redraw_after_new_report)
    for panel in _stock_panels():
        panel.COMPAT_ENGINES.discard(ENGINE)
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
