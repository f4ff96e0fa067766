"""bxdf.render() with material graphs (docs/material-graph.md): the same graphs as scene files,
errors naming the Python path of the field, per-corner UV maps, missing images in magenta."""

import numpy as np
import pytest

import bxdf
from test_render import DIRECT, scene_dict, sphere_mesh

pytestmark = pytest.mark.skipif(not hasattr(bxdf, "render"), reason="built without the renderer")


def image_graph(texture, closure_param="reflectance", model="lambertian"):
    return {"graph": {
        "textures": [texture],
        "nodes": [{"op": "uv"}, {"op": "image", "texture": 0, "vector": {"node": 0, "out": "vector"}}],
        "closures": [{"model": model, "params": {closure_param: {"node": 1, "out": "color"}}}]}}


def test_constant_texture_renders_like_the_constant_material(tmp_path):
    oiio = pytest.importorskip("OpenImageIO")
    path = str(tmp_path / "grey.exr")
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(4, 4, 3, "float"))
    out.write_image(np.full((4, 4, 3), 0.35, np.float32))
    out.close()
    textured = bxdf.render(scene_dict(image_graph({"path": path, "colorspace": "linear"})), DIRECT)
    plain = bxdf.render(scene_dict({"model": "lambertian", "params": {"reflectance": 0.35}}), DIRECT)
    assert plain[..., :3].max() > 0.01
    np.testing.assert_allclose(textured, plain, rtol=1e-6, atol=1e-7)


def test_missing_image_is_magenta():
    img = bxdf.render(scene_dict(image_graph({"missing": True})), DIRECT)
    lit = img[..., 0] > 0.01
    assert lit.sum() > 20
    np.testing.assert_array_equal(img[lit][:, 1], 0.0)
    # Reflectance (1, 0, 1) under the lamp's (30, 20, 10): red is three times blue.
    np.testing.assert_allclose(img[lit][:, 0], 3.0 * img[lit][:, 2], rtol=1e-5)


def test_bad_graph_names_the_python_path():
    bad = {"graph": {"nodes": [{"op": "uv"}, {"op": "separate", "vector": {"node": 3}}],
                     "closures": [{"model": "lambertian"}]}}
    with pytest.raises(ValueError, match=r"^scene\['materials'\]\[0\]\['graph'\]\['nodes'\]\[1\]\['vector'\]: "
                                         r"node 3 is not earlier than 1"):
        bxdf.render(scene_dict(bad), DIRECT)
    enum_ref = {"graph": {"nodes": [{"op": "uv"}, {"op": "separate", "vector": {"node": 0}}],
                          "closures": [{"model": "cycles_glossy",
                                        "params": {"distribution": {"node": 1, "out": "x"}}}]}}
    with pytest.raises(ValueError, match=r"\['closures'\]\[0\]\['params'\]\['distribution'\]: enum parameters"):
        bxdf.render(scene_dict(enum_ref), DIRECT)
    with pytest.raises(ValueError, match=r"\['closures'\]\[0\]\['params'\]"):
        bxdf.render(scene_dict({"graph": {"closures": [{"model": "cycles_glossy",
                                                        "params": {"roughness": 3.0}}]}}), DIRECT)
    with pytest.raises(ValueError, match=r"is not allowed next to 'graph'"):
        bxdf.render(scene_dict({"graph": {"closures": [{"model": "lambertian"}]}, "model": "lambertian"}),
                    DIRECT)


def test_per_corner_uv_maps_drive_the_lookup():
    mesh = sphere_mesh()
    corners = mesh["triangles"].size
    # Map 0 puts every corner at u = 0.25 (left texel, red), map 1 at u = 0.75 (right, blue).
    left = np.tile([[0.25, 0.5]], (corners, 1)).astype(np.float32)
    right = np.tile([[0.75, 0.5]], (corners, 1)).astype(np.float32)
    mesh["uv_maps"] = [left, right]
    graph = {"graph": {
        "textures": [{"missing": True}],
        "nodes": [{"op": "uv", "map": 1}, {"op": "separate", "vector": {"node": 0}},
                  {"op": "combine", "x": {"node": 1, "out": "x"}, "y": 0.0, "z": 0.0}],
        "closures": [{"model": "lambertian", "params": {"reflectance": {"node": 2, "out": "color"}}}]}}
    img = bxdf.render(scene_dict(graph, mesh), DIRECT)
    lit = img[..., 0] > 1e-3
    assert lit.sum() > 20
    np.testing.assert_array_equal(img[lit][:, 1:3], 0.0)  # reflectance (0.75, 0, 0)
    mesh["uv_maps"] = [left[:-1], right]
    with pytest.raises(ValueError, match=r"\['uv_maps'\]\[0\]: expected shape"):
        bxdf.render(scene_dict(graph, mesh), DIRECT)


@pytest.mark.parametrize("model,param,extra", [
    ("cycles_principled", "base_color", {"roughness": 0.3, "sheen": 0.5, "clearcoat": 0.4}),
    ("cycles_principled", "base_color", {"transmission": 0.6, "distribution": "multi_ggx"}),
    ("cycles_glass", "color", {"roughness": 0.3, "distribution": "ggx"}),
    ("cycles_refraction", "color", {"roughness": 0.2}),
    ("cycles_translucent", "color", {}),
    ("cycles_transparent", "color", {}),
    ("cycles_velvet", "color", {"sigma": 0.4}),
])
def test_per_hit_models_render_like_their_constant_material(model, param, extra):
    # A missing image is magenta: the per-hit (placed) model equals the prebuilt constant one.
    # A grey world and bounces, so that the transmissive and delta models show something.
    settings = dict(DIRECT, samples=2, max_bounces=4)

    def render(material):
        scene = scene_dict(material)
        scene["world"] = {"color": [0.5, 0.5, 0.5]}
        return bxdf.render(scene, settings)

    graph = image_graph({"missing": True}, param, model)
    graph["graph"]["closures"][0]["params"].update(extra)
    textured = render(graph)
    plain = render({"model": model, "params": {param: [1.0, 0.0, 1.0], **extra}})
    assert plain[..., 0].max() > 0.05
    np.testing.assert_allclose(textured, plain, rtol=1e-6, atol=1e-7)
