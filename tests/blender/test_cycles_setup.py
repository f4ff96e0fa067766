""""Set Up Cycles Material": the node tree closest to the model, labelled exact or approximate; an
exact set-up renders in Cycles to what the bxdf model predicts."""

import math

import bpy
import numpy as np
import pytest

from bxdf_lab import api

SUN_THETA = 40.0  # degrees from the normal
SUN_IRRADIANCE = math.pi


def _set_up(material):
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.set_up_cycles() == {"FINISHED"}


def _render_plane(material, path):
    """A large plane lit by a sun at SUN_THETA, seen straight down by an orthographic camera:
    every pixel is f(ωo = n, ωi)·E·cos θi (direct light only, no noise from a delta light)."""
    scene = bpy.context.scene
    mesh = bpy.data.meshes.new("plane")
    mesh.from_pydata([(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    scene.collection.objects.link(bpy.data.objects.new("plane", mesh))
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy, sun.angle = SUN_IRRADIANCE, 0.0
    sun_obj = bpy.data.objects.new("sun", sun)
    sun_obj.rotation_euler = (math.radians(SUN_THETA), 0, 0)
    scene.collection.objects.link(sun_obj)
    cam = bpy.data.cameras.new("cam")
    cam.type, cam.ortho_scale = "ORTHO", 2.0
    cam_obj = bpy.data.objects.new("cam", cam)
    cam_obj.location = (0, 0, 5)
    scene.collection.objects.link(cam_obj)
    scene.camera = cam_obj
    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x = r.resolution_y = 8
    r.resolution_percentage = 100
    r.filepath = path
    r.image_settings.file_format, r.image_settings.color_depth = "OPEN_EXR", "32"
    c = scene.cycles
    c.samples, c.max_bounces, c.use_denoising, c.use_adaptive_sampling = 4, 0, False, False
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(path)
    pixels = np.empty(8 * 8 * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    return pixels.reshape(-1, 4)[:, :3]


def _predicted(bxdf_model):
    t = math.radians(SUN_THETA)
    wi = np.array([0.0, -math.sin(t), math.cos(t)])  # towards the sun
    return np.asarray(bxdf_model.f([0.0, 0.0, 1.0], wi))[0] * SUN_IRRADIANCE * math.cos(t)


def test_lambertian_becomes_an_exact_diffuse_bsdf(material):
    api.assign(material, "lambertian", reflectance=(0.2, 0.4, 0.6))
    _set_up(material)
    assert material.bxdf_lab.cycles_label == "exact"
    assert "Diffuse" in material.bxdf_lab.cycles_mapping
    bsdf = material.node_tree.nodes["Diffuse BSDF"]
    assert tuple(bsdf.inputs["Color"].default_value) == pytest.approx((0.2, 0.4, 0.6, 1.0))
    assert bsdf.inputs["Roughness"].default_value == 0.0
    output = material.node_tree.nodes["Material Output"]
    assert output.inputs["Surface"].links[0].from_node == bsdf


@pytest.mark.parametrize("model_name, params", [
    ("lambertian", {"reflectance": (0.7, 0.5, 0.3)}),
    ("cycles_oren_nayar", {"color": (0.7, 0.5, 0.3), "roughness": 0.6}),
    ("cycles_glossy", {"color": (0.7, 0.5, 0.3), "roughness": 0.6, "distribution": "ggx"}),
    ("cycles_glossy", {"color": (0.7, 0.5, 0.3), "roughness": 0.6, "distribution": "beckmann"}),
    ("cycles_principled", {"base_color": (0.7, 0.5, 0.3), "metallic": 0.3, "specular": 0.6,
                           "specular_tint": 0.5, "roughness": 0.4, "sheen": 0.6, "sheen_tint": 0.3,
                           "clearcoat": 0.7, "clearcoat_roughness": 0.3}),
    ("cycles_principled", {"base_color": (0.2, 0.6, 0.8), "roughness": 0.7, "transmission": 0.4,
                           "ior": 1.6, "specular": 0.3}),
    ("cycles_glossy", {"color": (0.7, 0.5, 0.3), "roughness": 0.6,
                       "distribution": "ashikhmin_shirley"}),
    ("cycles_glossy", {"color": (0.7, 0.5, 0.3), "roughness": 0.9,
                       "distribution": "ashikhmin_shirley"}),
    ("microfacet", {"reflectance": (0.7, 0.5, 0.3), "distribution": "ggx", "alpha_x": 0.4,
                    "alpha_y": 0.4, "shadowing": "smith", "fresnel": "none"}),
    ("microfacet", {"reflectance": (0.7, 0.5, 0.3), "distribution": "beckmann", "alpha_x": 0.2,
                    "alpha_y": 0.2, "shadowing": "smith", "fresnel": "none",
                    "diffuse": (0.1, 0.2, 0.3)}),
])
def test_exact_set_up_renders_in_cycles_as_the_model_predicts(model_name, params, material, bxdf,
                                                              tmp_path):
    model = api.assign(material, model_name, **params)
    _set_up(material)
    assert material.bxdf_lab.cycles_label == "exact"
    pixels = _render_plane(material, str(tmp_path / "cycles.exr"))
    expected = _predicted(model)
    assert expected.min() > 0.05
    np.testing.assert_allclose(pixels, np.broadcast_to(expected, pixels.shape), rtol=2e-3)


def test_every_registry_model_gets_a_cycles_material(bxdf, material):
    for model_name in bxdf.models():
        api.assign(material, model_name)
        _set_up(material)
        assert material.bxdf_lab.cycles_label in ("exact", "approximate"), model_name
        assert material.bxdf_lab.cycles_mapping
        links = material.node_tree.nodes["Material Output"].inputs["Surface"].links
        assert len(links) == 1 and links[0].from_node.type.startswith("BSDF"), model_name


def test_set_up_of_a_broken_material_is_an_error(material):
    material.bxdf_lab.lambertian.reflectance = (float("nan"), 0.5, 0.5)
    with bpy.context.temp_override(material=material):
        with pytest.raises(RuntimeError, match="reflectance"):
            bpy.ops.bxdf_lab.set_up_cycles()


def test_classic_oren_nayar_maps_to_cycles_roughness_b_over_a(material):
    api.assign(material, "oren_nayar", reflectance=(0.5, 0.5, 0.5), sigma=20.0)
    _set_up(material)
    assert material.bxdf_lab.cycles_label == "approximate"
    s2 = math.radians(20.0) ** 2
    a, b = 1 - 0.5 * s2 / (s2 + 0.33), 0.45 * s2 / (s2 + 0.09)
    bsdf = material.node_tree.nodes["Diffuse BSDF"]
    assert bsdf.inputs["Roughness"].default_value == pytest.approx(b / a, rel=1e-6)
    # the constant terms agree: colour·A_cycles = R·A/π
    a_cycles = 1 / (math.pi + (math.pi / 2 - 2 / 3) * (b / a))
    assert bsdf.inputs["Color"].default_value[0] * a_cycles == pytest.approx(0.5 * a / math.pi, rel=1e-5)


def test_anisotropic_microfacet_maps_to_cycles_anisotropy(material):
    api.assign(material, "microfacet", distribution="ggx", alpha_x=0.1, alpha_y=0.4,
               shadowing="smith", fresnel="none")
    _set_up(material)
    bsdf = material.node_tree.nodes["Anisotropic BSDF"]
    roughness = bsdf.inputs["Roughness"].default_value
    anisotropy = bsdf.inputs["Anisotropy"].default_value
    # Cycles: r = roughness², a ≥ 0 → αx = r(1 − a), αy = r/(1 − a)
    r = roughness ** 2
    assert (r * (1 - anisotropy), r / (1 - anisotropy)) == pytest.approx((0.1, 0.4), rel=1e-5)
    assert material.bxdf_lab.cycles_label == "exact"


def test_principled_maps_every_parameter_to_its_socket(bxdf, material):
    params = {"base_color": (0.7, 0.5, 0.3), "subsurface": 0.0, "metallic": 0.4, "specular": 0.6,
              "specular_tint": 0.2, "roughness": 0.35, "anisotropic": 0.5,
              "anisotropic_rotation": 0.25, "sheen": 0.3, "sheen_tint": 0.6, "clearcoat": 0.8,
              "clearcoat_roughness": 0.2, "ior": 1.33, "transmission": 0.1,
              "transmission_roughness": 0.4, "distribution": "multi_ggx"}
    model = api.assign(material, "cycles_principled", **params)
    _set_up(material)
    assert material.bxdf_lab.cycles_label == "exact"
    bsdf = material.node_tree.nodes["Principled BSDF"]
    assert bsdf.distribution == "MULTI_GGX"
    declared = [p["name"] for p in bxdf.models()["cycles_principled"]]
    for name in declared:
        if name == "distribution":
            continue
        socket = bsdf.inputs["IOR" if name == "ior" else name.replace("_", " ").title()]
        value = dict(model.params)[name]
        if name in params:
            assert value == pytest.approx(params[name]), name
        if isinstance(value, (tuple, list)):
            assert tuple(socket.default_value)[:3] == pytest.approx(tuple(value)), name
        else:
            assert socket.default_value == pytest.approx(value), name
    # Subsurface: BxDF Lab has no subsurface scattering, so the pairing is approximate.
    api.assign(material, "cycles_principled", subsurface=0.5)
    _set_up(material)
    assert material.bxdf_lab.cycles_label == "approximate"
    assert "subsurface" in material.bxdf_lab.cycles_mapping


@pytest.mark.parametrize("model_name, params, node_type, sockets", [
    ("cycles_glass", {"color": (0.9, 0.8, 0.7), "distribution": "ggx", "roughness": 0.3,
                      "ior": 1.5}, "BSDF_GLASS", {"Roughness": 0.3, "IOR": 1.5}),
    ("cycles_glass", {"distribution": "multi_ggx", "roughness": 0.6, "ior": 1.33}, "BSDF_GLASS",
     {"Roughness": 0.6, "IOR": 1.33}),
    ("cycles_refraction", {"distribution": "sharp", "ior": 2.4}, "BSDF_REFRACTION",
     {"IOR": 2.4}),
    ("cycles_translucent", {"color": (0.9, 0.8, 0.7)}, "BSDF_TRANSLUCENT", {}),
    ("cycles_transparent", {"color": (0.9, 0.8, 0.7)}, "BSDF_TRANSPARENT", {}),
    ("cycles_velvet", {"color": (0.9, 0.8, 0.7), "sigma": 0.25}, "BSDF_VELVET", {"Sigma": 0.25}),
    ("cycles_glossy", {"distribution": "sharp", "anisotropy": 0.5}, "BSDF_GLOSSY", {}),
    ("cycles_glossy", {"distribution": "multi_ggx", "anisotropy": 0.5}, "BSDF_ANISOTROPIC",
     {"Anisotropy": 0.5}),
])
def test_cycles_node_models_map_onto_their_node_exactly(model_name, params, node_type, sockets,
                                                        material):
    api.assign(material, model_name, **params)
    _set_up(material)
    assert material.bxdf_lab.cycles_label == "exact"
    node = material.node_tree.nodes["Material Output"].inputs["Surface"].links[0].from_node
    assert node.type == node_type
    if "distribution" in params:
        assert node.distribution == params["distribution"].upper()
    for socket, value in sockets.items():
        assert node.inputs[socket].default_value == pytest.approx(value)
    if "color" in params:
        assert tuple(node.inputs["Color"].default_value) == pytest.approx((*params["color"], 1.0))


def test_multiscatter_refraction_maps_onto_the_refraction_node_approximately(material):
    """Blender 3.4's Refraction node has no Multiscatter GGX: the closest is its GGX form."""
    api.assign(material, "cycles_refraction", color=(0.9, 0.8, 0.7), distribution="multi_ggx",
               roughness=0.5, ior=1.33)
    _set_up(material)
    assert material.bxdf_lab.cycles_label == "approximate"
    assert "no multiscatter" in material.bxdf_lab.cycles_mapping
    node = material.node_tree.nodes["Material Output"].inputs["Surface"].links[0].from_node
    assert (node.type, node.distribution) == ("BSDF_REFRACTION", "GGX")
    assert node.inputs["Roughness"].default_value == pytest.approx(0.5)
    assert node.inputs["IOR"].default_value == pytest.approx(1.33)
