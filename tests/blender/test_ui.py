"""The panels draw every relevant parameter, hide those whose `when` condition fails, and show
the registry's error for a broken value (drawn into a recording layout: headless Blender has no
UI to draw into)."""

import math

import bpy

import pytest

from bxdf_lab import api, properties, schema, ui


class RecordingLayout:
    """Stands in for bpy.types.UILayout: records what would be drawn."""

    def __init__(self, log=None, alert=False):
        self.log = [] if log is None else log
        self.alert = alert  # inherited by child layouts, as in Blender
        self.use_property_split = False

    def prop(self, data, name, **_):
        self.log.append(("prop", name, self.alert))

    def label(self, text="", **_):
        self.log.append(("label", text, self.alert))

    def operator(self, idname, **_):
        self.log.append(("operator", idname))
        return type("Props", (), {})()

    def menu(self, idname, **_):
        self.log.append(("menu", idname))

    def _child(self, *_, **__):
        return RecordingLayout(self.log, self.alert)

    row = column = box = _child


def _draw(panel_cls, context):
    layout = RecordingLayout()
    panel_cls.draw(type("Panel", (), {"layout": layout})(), context)
    return layout.log


def test_material_panel_draws_every_parameter_and_the_operators(bxdf, material):
    context = type("Context", (), {"material": material, "scene": bpy.context.scene})()
    for model_name, specs in bxdf.models().items():
        material.bxdf_lab.model = model_name
        log = _draw(ui.BXDFLAB_PT_material, context)
        drawn = {entry[1] for entry in log if entry[0] == "prop"}
        assert "model" in drawn
        unconditional = {properties.attr_name(s["name"]) for s in specs
                         if s["kind"] != "list" and "when" not in s}
        assert unconditional <= drawn, model_name
        assert ("operator", "bxdf_lab.bake_lobe_texture") in log
        assert ("operator", "bxdf_lab.set_up_cycles") in log
        assert not any(entry[0] == "label" and entry[2] for entry in log)  # no error shown


def test_a_broken_value_is_shown_as_an_error_in_the_panel(material):
    material.bxdf_lab.model = "lambertian"
    material.bxdf_lab.lambertian.reflectance = (0.5, 0.5, float("nan"))
    context = type("Context", (), {"material": material, "scene": bpy.context.scene})()
    for panel in (ui.BXDFLAB_PT_material, ui.BXDFLAB_PT_material_cycles):
        errors = " ".join(e[1] for e in _draw(panel, context) if e[0] == "label" and e[2])
        assert "reflectance" in errors and "Test Material" in errors


def test_parameters_whose_condition_fails_are_hidden():
    specs = [
        {"name": "distribution", "kind": "enum", "default": "ggx", "choices": ["blinn", "ggx"],
         "doc": "d", "unit": ""},
        {"name": "exponent", "kind": "float", "default": 20.0, "min": 0.0, "max": math.inf,
         "doc": "e", "unit": "", "when": {"param": "distribution", "values": ["blinn"]}},
        {"name": "alpha", "kind": "float", "default": 0.1, "min": 0.0, "max": 1.0,
         "doc": "a", "unit": "", "when": {"param": "distribution", "values": ["ggx"]}},
    ]
    params = [schema.param_from_spec(s) for s in specs]
    group_cls = properties._make_group("BXDFLAB_PG_test_when", params, "test")
    try:
        bpy.types.Material.bxdf_lab_test_when = bpy.props.PointerProperty(type=group_cls)
        group = bpy.data.materials.new("when").bxdf_lab_test_when
        layout = RecordingLayout()
        ui.draw_params(layout, group, params)
        assert [e[1] for e in layout.log] == ["distribution", "alpha"]
        group.distribution = "blinn"
        layout = RecordingLayout()
        ui.draw_params(layout, group, params)
        assert [e[1] for e in layout.log] == ["distribution", "exponent"]
    finally:
        del bpy.types.Material.bxdf_lab_test_when
        bpy.utils.unregister_class(group_cls)
        properties._classes.remove(group_cls)


def test_render_panel_draws_the_settings():
    context = type("Context", (), {"scene": bpy.context.scene})()
    drawn = [e[1] for e in _draw(ui.BXDFLAB_PT_render, context) if e[0] == "prop"]
    # Cycles' Noise Threshold and Min Samples around each sample count, and its Light Paths
    # settings at the end: read by both renderers.
    assert drawn == ["use_adaptive_sampling", "adaptive_threshold", "samples", "adaptive_min_samples",
                     "preview_samples",
                     "use_preview_adaptive_sampling", "preview_adaptive_threshold", "viewport_samples",
                     "preview_adaptive_min_samples", "preview_pixel_size",
                     "max_bounces", "pixel_filter", "filter_width", "threads", "seed",
                     "min_light_bounces", "transparent_max_bounces"]


def _rna(group, name):
    return group.bl_rna.properties[properties.attr_name(name)]


def test_colours_are_swatches_and_per_channel_numbers_are_number_fields(material):
    settings = material.bxdf_lab
    assert _rna(settings.microfacet, "reflectance").subtype == "COLOR"
    assert _rna(settings.microfacet, "eta").subtype == "NONE"
    assert _rna(settings.microfacet, "k").subtype == "NONE"
    api.assign(material, "lafortune")
    lobe = settings.lafortune.lobes[0]
    for name in ("cx", "cy", "cz", "exponent"):
        assert _rna(lobe, name).subtype == "NONE", name
    assert _rna(settings.lafortune, "diffuse").subtype == "COLOR"
    # A coefficient of -1.09 is kept and shown as the number it is.
    lobe.cx = (-1.09, -1.09, -1.09)
    assert tuple(lobe.cx) == pytest.approx((-1.09,) * 3)


def test_labels_and_enum_names_read_as_blender_writes_them(material):
    group = material.bxdf_lab.microfacet
    names = {i.identifier: i.name for i in _rna(group, "distribution").enum_items}
    assert names == {"blinn": "Blinn", "ashikhmin_shirley": "Ashikhmin-Shirley",
                     "beckmann": "Beckmann", "ggx": "GGX"}
    assert {i.name for i in _rna(group, "shadowing").enum_items} == {"V-Groove", "Smith"}
    assert schema.enum_label("multi_ggx") == "Multiscatter GGX"
    assert _rna(material.bxdf_lab.oren_nayar, "sigma").name == "Sigma (°)"
    assert _rna(group, "alpha_x").name == "Alpha X"


def test_an_exclusive_bound_cannot_be_typed(material):
    group = material.bxdf_lab.microfacet
    material.bxdf_lab.model = "microfacet"
    group.alpha_x = 0.0  # (0, 10]: the field stops at the nearest value it shows inside
    assert 0.0 < group.alpha_x <= 1.01e-4
    api.make(material)  # valid
    group.eta = (0.0, 0.5, 0.5)
    assert group.eta[0] > 0.0


def test_a_bad_value_highlights_its_field_and_the_message_names_it(material):
    api.assign(material, "microfacet", fresnel="conductor")
    material.bxdf_lab.microfacet.k = (0.5, float("nan"), 0.5)  # only Python can store this
    context = type("Context", (), {"material": material, "scene": bpy.context.scene,
                                   "region": type("Region", (), {"width": 240})()})()
    log = _draw(ui.BXDFLAB_PT_material, context)
    highlighted = [e[1] for e in log if e[0] == "prop" and e[2]]
    assert highlighted == ["k"]
    error_lines = [e[1] for e in log if e[0] == "label" and e[2]]
    assert "'k'" in " ".join(error_lines) or " k " in " ".join(error_lines)
    assert all(len(line) <= 240 / ui.CHAR_WIDTH for line in error_lines)  # wrapped, not cut


def test_the_last_render_report_is_shown_in_both_tabs(material):
    from bxdf_lab import render_report
    report = render_report.Report("render", "Scene", summary="done")
    report.warnings += [f"material '{material.name}': node 'Noise Texture' is not translated",
                        "light 'Lamp': radius rendered as 0"]
    render_report.record(report)
    try:
        context = type("Context", (), {"material": material, "scene": bpy.context.scene})()
        render_tab = " ".join(e[1] for e in _draw(ui.BXDFLAB_PT_render, context) if e[0] == "label")
        material_tab = " ".join(e[1] for e in _draw(ui.BXDFLAB_PT_material, context) if e[0] == "label")
        assert "Noise Texture" in render_tab and "'Lamp'" in render_tab
        assert "Noise Texture" in material_tab
        assert "'Lamp'" not in material_tab  # only what names this material
    finally:
        render_report.clear()


def test_a_new_report_redraws_the_properties_editors():
    # F12 records its report on the render thread; a main-thread timer notices it and tags the
    # Properties editors (which show it) for redraw, once per new report.
    from bxdf_lab import render_report
    assert bpy.app.timers.is_registered(ui.redraw_after_new_report)
    assert ui.redraw_after_new_report() == ui.REPORT_REDRAW_INTERVAL
    seen = render_report.recorded()
    render_report.record(render_report.Report("render", "Scene", summary="done"))
    try:
        assert render_report.recorded() == seen + 1
        assert ui.redraw_after_new_report() == ui.REPORT_REDRAW_INTERVAL
        assert ui._reports_drawn == seen + 1  # caught up: the next call tags nothing
    finally:
        render_report.clear()
