"""bxdf.render's world and light keys: an equirectangular world (rendered the same whether it is
importance-sampled or found by BSDF sampling alone), and bad world, light and mesh settings refused
with the key's path."""

import numpy as np
import pytest

import bxdf
from test_render import SIZE, scene_dict

HDRI = "/usr/share/blender/datafiles/studiolights/world/studio.exr"
MATERIAL = {"name": "m", "model": "lambertian", "params": {"reflectance": 0.8}}


def hdri_scene(sampling):
    scene = scene_dict(MATERIAL)
    scene["lights"] = []
    scene["world"] = {"color": [0.05, 0.05, 0.05], "sampling": sampling,
                      "texture": {"path": HDRI, "weight": [1.0, 1.0, 1.0],
                                  "matrix": np.array([[0, -1, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0]], float)}}
    return scene


@pytest.mark.skipif(not __import__("os").path.exists(HDRI), reason="Blender's studio lights are not installed")
def test_importance_sampled_world_renders_what_bsdf_sampling_finds():
    settings = {"samples": 256, "max_bounces": 0, "pixel_filter": "pixel_center", "threads": 2}
    sampled = bxdf.render(hdri_scene("auto"), settings)
    plain = bxdf.render(hdri_scene("none"), dict(settings, samples=1024))
    assert np.all(np.isfinite(sampled))
    centre = slice(SIZE // 4, 3 * SIZE // 4)
    a, b = sampled[centre, centre, :3].mean(), plain[centre, centre, :3].mean()
    assert a > 0.01 and a == pytest.approx(b, rel=0.03)


@pytest.mark.parametrize("edit, message", [
    (lambda s: s["world"]["texture"].update(path="/nonexistent.exr"), r"scene\['world'\]\['texture'\]\['path'\]"),
    (lambda s: s["world"]["texture"].update(matrix=np.eye(3)), r"scene\['world'\]\['texture'\]\['matrix'\]: has shape \(3, 3\)"),
    (lambda s: s["world"].update(sampling="sometimes"), r"scene\['world'\]\['sampling'\]: 'sometimes' is unknown"),
    (lambda s: s["world"].update(map_resolution=3), r"scene\['world'\]: .*map_resolution 3"),
    (lambda s: s["meshes"][0].update(terminator_offset=(2.0, 0.0)), r"scene\['meshes'\]\[0\]\['terminator_offset'\]"),
    (lambda s: s["lights"].append({"type": "point", "position": [0, 0, 3], "intensity": [1, 1, 1], "radius": -1}),
     r"scene\['lights'\]\[0\]\['radius'\]: -1.0 is out of range"),
    (lambda s: s["lights"].append({"type": "area", "shape": "disk", "size": (1, 1), "matrix": np.eye(4), "power": 1.0,
                                   "color": [1, 1, 1], "cast_shadow": "yes"}),
     r"scene\['lights'\]\[0\]\['cast_shadow'\]: 'yes' is not a bool"),
])
def test_bad_world_light_and_mesh_settings_name_the_key(edit, message):
    scene = hdri_scene("auto")
    edit(scene)
    with pytest.raises(ValueError, match=message):
        bxdf.render(scene, {"samples": 1})
