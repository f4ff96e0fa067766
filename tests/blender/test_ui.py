"""The panels draw every relevant parameter, hide those whose `when` condition fails, and show
the registry's error for a broken value (drawn into a recording layout: headless Blender has no
UI to draw into)."""

import math

import bpy

from bxdf_lab import properties, schema, ui


class RecordingLayout:
    """Stands in for bpy.types.UILayout: records what would be drawn."""

    def __init__(self, log=None):
        self.log = [] if log is None else log
        self.alert = False
        self.use_property_split = False

    def prop(self, data, name, **_):
        self.log.append(("prop", name))

    def label(self, text="", **_):
        self.log.append(("label", text, self.alert))

    def operator(self, idname, **_):
        self.log.append(("operator", idname))
        return type("Props", (), {})()

    def menu(self, idname, **_):
        self.log.append(("menu", idname))

    def _child(self, *_, **__):
        return RecordingLayout(self.log)

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
        errors = [e for e in _draw(panel, context) if e[0] == "label" and e[2]]
        assert len(errors) == 1 and "reflectance" in errors[0][1]


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
    assert drawn == ["samples", "max_bounces", "pixel_filter", "filter_width", "threads", "seed"]
