"""Scenes built only from Blender shader nodes (compare/node_recipes.py): BXDF_LAB renders them
through the add-on's node translation, with no BxDF Lab set-up at all."""
from __future__ import annotations

from .scene_spec import NODES, Camera, Material, PointLight, Quad, SceneSpec, Sphere, SunLight


def _nodes(name, recipe):
    return Material(name, NODES, {"recipe": recipe})


SHOWROOM = ("gold", "plastic_clearcoat", "sheen_fabric", "brushed_metal", "glass",
            "mix_diffuse_glossy")


def principled_showroom():
    spheres = tuple(Sphere(f"sphere_{i}", (-2.5 + 1.0 * i, 0.0, 0.0), 0.42, _nodes(recipe, recipe))
                    for i, recipe in enumerate(SHOWROOM))
    return SceneSpec(
        name="principled_showroom",
        description="Blender node materials: Principled gold, clear-coated plastic, sheen fabric, "
                    "brushed anisotropic metal and glass, and a Mix of Diffuse and Glossy; a "
                    "point light and a grey world, 4 bounces",
        camera=Camera(location=(0.0, -9.0, 0.0), look_at=(0.0, 0.0, 0.0), lens_mm=50.0),
        objects=spheres, lights=(PointLight(location=(1.0, -6.0, 3.0), intensity=60.0),),
        world_color=(0.3, 0.3, 0.3), max_bounces=4, spp=64, resolution=(256, 80),
        tags=("nodes",))


def textured_floor():
    floor = Quad("floor", ((-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)),
                 _nodes("textured_floor", "textured_floor"))
    return SceneSpec(
        name="textured_floor",
        description="An image-textured, normal-mapped floor: a Mix of a Diffuse BSDF coloured by "
                    "a generated checker and a Glossy BSDF normal-mapped by generated bevelled "
                    "tiles; a sun and a point light, direct light only",
        camera=Camera(location=(0.0, -4.5, 3.0), look_at=(0.0, 0.0, 0.0), lens_mm=35.0),
        objects=(floor,),
        lights=(SunLight(direction=(-1.0, -0.5, 1.2), irradiance=2.0),
                PointLight(location=(1.0, -1.0, 1.5), intensity=8.0)),
        max_bounces=0, spp=32, resolution=(128, 128), tags=("nodes",))


NODE_SCENES = (principled_showroom, textured_floor)
# principled_showroom renders in BXDF_LAB once the registry has cycles_principled (issue #10).
DEFAULT_NODE_SCENES = (textured_floor,)
