"""The material properties are generated from bxdf.models(): every model, every parameter, with
the registry's defaults, ranges, units and tooltips."""

import math

import bpy
import pytest

from bxdf_lab import properties, schema


def _rna(group, name):
    return group.bl_rna.properties[properties.attr_name(name)]


def _check_property(group, spec):
    rna = _rna(group, spec["name"])
    kind = spec["kind"]
    assert spec["doc"].rstrip(".") in rna.description
    if kind == "float":
        assert rna.type == "FLOAT" and rna.array_length == 0
        assert getattr(group, spec["name"]) == pytest.approx(spec["default"], rel=1e-6)
    if kind == "rgb":
        colour = spec.get("subtype", "color") == "color"
        assert rna.type == "FLOAT" and rna.array_length == 3
        assert rna.subtype == ("COLOR" if colour else "NONE")  # per-channel numbers: number fields
        assert tuple(getattr(group, spec["name"])) == pytest.approx(tuple(spec["default"]), rel=1e-6)
    if kind in ("float", "rgb"):
        for bound, hard, inward in (("min", rna.hard_min, 1), ("max", rna.hard_max, -1)):
            if math.isfinite(spec[bound]):
                if spec.get(f"{bound}_exclusive"):  # the excluded value cannot be typed
                    step = (hard - spec[bound]) * inward
                    assert 0.0 < step <= 1.01e-4 * max(1.0, abs(spec[bound])), (spec["name"], bound)
                else:
                    assert hard == pytest.approx(spec[bound], abs=1e-6), (spec["name"], bound)
        if spec["unit"]:
            assert schema.UNIT_SYMBOLS.get(spec["unit"], spec["unit"]) in rna.name
    if kind == "enum":
        assert rna.type == "ENUM"
        assert list(rna.enum_items.keys()) == list(spec["choices"])
        assert getattr(group, spec["name"]) == spec["default"]
    if kind == "bool":
        assert rna.type == "BOOLEAN" and getattr(group, spec["name"]) == spec["default"]
    if kind == "string":
        assert rna.type == "STRING" and (rna.subtype == "FILE_PATH") == (spec["name"] == "path")


def test_every_model_is_selectable(bxdf, material):
    items = bpy.types.Material.bl_rna.properties["bxdf_lab"].fixed_type.properties["model"].enum_items
    assert list(items.keys()) == list(bxdf.models())
    assert material.bxdf_lab.model in bxdf.models()


def test_every_parameter_has_the_registry_default_range_unit_and_tooltip(bxdf, material):
    for model_name, specs in bxdf.models().items():
        group = getattr(material.bxdf_lab, model_name)
        for spec in specs:
            if spec["kind"] == "list":
                material.bxdf_lab.model = model_name  # fills lists with their default elements
                collection = getattr(group, properties.attr_name(spec["name"]))
                assert len(collection) == len(spec["default"])
                for element in collection:
                    for field in spec["fields"]:
                        _check_property(element, field)
            else:
                _check_property(group, spec)


def _same(a, b):
    """Equal up to float32 storage (Blender keeps single precision)."""
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, float):
        return a == pytest.approx(b, rel=1e-6, abs=1e-7)
    return a == b


def test_a_new_material_describes_the_registry_default_model(bxdf, material):
    from bxdf_lab import api
    for model_name in bxdf.models():
        material.bxdf_lab.model = model_name
        name, params = api.describe(material)
        assert name == model_name
        assert _same(params, bxdf.make(model_name).params), model_name


# The generator on every kind the registry declares (bxdf.models() documents these shapes);
# the real registry may not use every kind yet.
SPECS = [
    {"name": "distribution", "kind": "enum", "default": "ggx", "choices": ["beckmann", "ggx"],
     "doc": "Microfacet distribution", "unit": "", "min": None, "max": None},
    {"name": "alpha_x", "kind": "float", "default": 0.1, "min": 0.0, "max": math.inf,
     "min_exclusive": True, "unit": "", "doc": "Width along x",
     "when": {"param": "distribution", "values": ["beckmann", "ggx"]}},
    {"name": "exponent", "kind": "float", "default": 20.0, "min": 0.0, "max": math.inf,
     "min_exclusive": True, "unit": "", "doc": "Blinn exponent",
     "when": {"param": "distribution", "values": ["blinn"]}},
    {"name": "sigma", "kind": "float", "default": 20.0, "min": 0.0, "max": 90.0, "unit": "degrees",
     "doc": "Facet slope deviation"},
    {"name": "eta", "kind": "rgb", "default": (1.5, 1.5, 1.5), "min": 0.0, "max": math.inf,
     "min_exclusive": True, "unit": "", "doc": "Index of refraction"},
    {"name": "two_sided", "kind": "bool", "default": True, "doc": "Both sides", "unit": "",
     "min": None, "max": None},
    {"name": "path", "kind": "string", "default": "", "doc": "Measured file", "unit": "",
     "min": None, "max": None},
]


def test_generator_handles_every_kind_and_condition():
    params = [schema.param_from_spec(s) for s in SPECS]
    group_cls = properties._make_group("BXDFLAB_PG_test_kinds", params, "test")
    try:
        bpy.types.Material.bxdf_lab_test = bpy.props.PointerProperty(type=group_cls)
        group = bpy.data.materials.new("kinds").bxdf_lab_test
        for spec in SPECS:
            _check_property(group, spec)
        alpha = _rna(group, "alpha_x")
        assert 0.0 < alpha.hard_min <= 1.01e-4 and alpha.soft_min > 0.0  # exclusive: stays inside
        assert "(0, inf)" in alpha.description and "Used when distribution is beckmann or ggx" in alpha.description
        values = {p.name: getattr(group, p.name) for p in params}
        assert params[1].relevant(values) and not params[2].relevant(values)
        group.distribution = "beckmann"
        values["distribution"] = "beckmann"
        assert params[1].relevant(values)
    finally:
        del bpy.types.Material.bxdf_lab_test
        bpy.utils.unregister_class(group_cls)
        properties._classes.remove(group_cls)


def test_enum_values_are_stable_numbers_and_survive_save_and_load(bxdf, material, tmp_path):
    """Enum values are stored as numbers in .blend files; ours hash the identifier, so a registry
    that adds or reorders models does not change what a saved file means."""
    items = bpy.types.Material.bl_rna.properties["bxdf_lab"].fixed_type.properties["model"].enum_items
    assert all(item.value == properties.enum_number(item.identifier) for item in items)
    assert len({item.value for item in items}) == len(items)
    last = list(bxdf.models())[-1]
    material.bxdf_lab.model = last
    material.use_fake_user = True  # an unused material is not saved otherwise
    path = str(tmp_path / "saved.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.open_mainfile(filepath=path)
    assert bpy.data.materials["Test Material"].bxdf_lab.model == last


def test_list_elements_are_added_and_removed(bxdf, material):
    list_models = {m: s for m, specs in bxdf.models().items() for s in specs if s["kind"] == "list"}
    assert list_models, "the registry has no list parameter (Lafortune lobes)"
    from bxdf_lab import api
    for model_name, spec in list_models.items():
        material.bxdf_lab.model = model_name
        n = len(spec["default"])
        with bpy.context.temp_override(material=material):
            assert bpy.ops.bxdf_lab.list_add(param=spec["name"]) == {"FINISHED"}
            assert len(api.describe(material)[1][spec["name"]]) == n + 1
            assert bpy.ops.bxdf_lab.list_remove(param=spec["name"], index=0) == {"FINISHED"}
            assert len(api.describe(material)[1][spec["name"]]) == n
            with pytest.raises(RuntimeError, match="no element"):
                bpy.ops.bxdf_lab.list_remove(param=spec["name"], index=n + 5)
        api.make(material)  # still a valid model
