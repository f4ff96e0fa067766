"""Scenes of worlds and lights as Cycles has them: an HDRI sphere grid (alone and with a sun), an
area-light room with every shape, soft shadows (point and spot radius, sun angle), an HDRI
furnace, and a Lambertian sphere under a z-gradient world (closed form, gradient_world.py).

Every material is exact in BXDF_LAB and Cycles, so a difference beyond the noise is the lights'
or the world's. They are small (resolution, samples) so that `make report` stays quick."""
from __future__ import annotations

from .scene_spec import (AreaLight, Camera, EnvironmentMap, Material, PointLight, Quad, SceneSpec,
                         Sphere, SpotLight, SunLight, ZGradientWorld)

HDRI = "/usr/share/blender/datafiles/studiolights/world/courtyard.exr"  # max 56: few fireflies
GRID_CAMERA = Camera(location=(0.0, -8.0, 0.6), look_at=(0.0, 0.0, 0.0), lens_mm=50.0)

WHITE = Material("lambert_08", "lambertian", {"reflectance": (0.8, 0.8, 0.8)})
FLOOR = Material("floor_05", "lambertian", {"reflectance": (0.5, 0.5, 0.5)})
GRID_MATERIALS = (
    WHITE,
    Material("cycles_on_05", "cycles_oren_nayar", {"color": (0.8, 0.5, 0.3), "roughness": 0.5}),
    Material("velvet_05", "cycles_velvet", {"color": (0.5, 0.6, 0.9), "sigma": 0.5}),
    Material("glossy_ggx_02", "cycles_glossy",
             {"color": (0.9, 0.9, 0.9), "distribution": "ggx", "roughness": 0.2}),
    Material("glossy_beckmann_04", "cycles_glossy",
             {"color": (0.9, 0.7, 0.5), "distribution": "beckmann", "roughness": 0.4}),
    Material("glossy_as_03", "cycles_glossy",
             {"color": (0.7, 0.8, 0.9), "distribution": "ashikhmin_shirley", "roughness": 0.3}),
)


def _sphere_grid():
    """Two rows of three spheres, one model each."""
    return tuple(Sphere(f"sphere_{m.name}", (-1.5 + 1.5 * (i % 3), 0.0, 0.75 - 1.5 * (i // 3)),
                        0.6, m) for i, m in enumerate(GRID_MATERIALS))


def hdri_sphere_grid():
    return SceneSpec(
        name="hdri_sphere_grid",
        description="Six spheres (Lambert, Cycles Oren-Nayar, Velvet, Glossy GGX, Beckmann, "
                    "Ashikhmin-Shirley) lit only by an HDRI (courtyard.exr, turned 60 degrees), "
                    "direct light only",
        camera=GRID_CAMERA, objects=_sphere_grid(), lights=(),
        environment=EnvironmentMap(HDRI, strength=1.0, rotation_z_deg=60.0),
        max_bounces=0, spp=64, resolution=(128, 96), tags=("lights",))


def hdri_sun_sphere_grid():
    return SceneSpec(
        name="hdri_sun_sphere_grid",
        description="The HDRI sphere grid with a sun of angle 3 degrees from the upper left, "
                    "direct light only",
        camera=GRID_CAMERA, objects=_sphere_grid(),
        lights=(SunLight(direction=(-1.0, -1.5, 1.2), irradiance=2.0, angle_deg=3.0),),
        environment=EnvironmentMap(HDRI, strength=0.5, rotation_z_deg=60.0),
        max_bounces=0, spp=64, resolution=(128, 96), tags=("lights",))


def _room_walls():
    # A grey box x, y in [-1.5, 1.5], z in [0, 2], open towards the camera (-y).
    return (
        Quad("floor", ((-1.5, -1.5, 0), (1.5, -1.5, 0), (1.5, 1.5, 0), (-1.5, 1.5, 0)), FLOOR),
        Quad("back_wall", ((-1.5, 1.5, 0), (1.5, 1.5, 0), (1.5, 1.5, 2), (-1.5, 1.5, 2)), FLOOR),
        Quad("left_wall", ((-1.5, -1.5, 0), (-1.5, 1.5, 0), (-1.5, 1.5, 2), (-1.5, -1.5, 2)),
             FLOOR),
    )


def area_light_room():
    down = (0.0, 0.0, -1.0)
    lights = (
        AreaLight((-0.8, 0.6, 1.9), down, "SQUARE", power=40.0, size=0.5),
        AreaLight((0.8, 0.6, 1.9), (0.3, 0.0, -1.0), "RECTANGLE", power=40.0, size=0.8,
                  size_y=0.3, color=(1.0, 0.8, 0.6)),
        AreaLight((-0.8, -0.6, 1.9), down, "DISK", power=40.0, size=0.6, color=(0.6, 0.8, 1.0)),
        AreaLight((0.8, -0.6, 1.9), (-0.3, 0.2, -1.0), "ELLIPSE", power=40.0, size=0.9,
                  size_y=0.4),
    )
    spheres = (Sphere("ball_left", (-0.5, 0.2, 0.4), 0.4, WHITE),
               Sphere("ball_right", (0.6, 0.0, 0.35), 0.35, GRID_MATERIALS[3]))
    return SceneSpec(
        name="area_light_room",
        description="A grey room lit by four one-sided area lights (square, rectangle, disk, "
                    "ellipse; two tilted), a Lambert and a Glossy GGX sphere, one bounce",
        camera=Camera(location=(0.0, -5.0, 1.2), look_at=(0.0, 0.0, 0.8), lens_mm=35.0),
        objects=_room_walls() + spheres, lights=lights, max_bounces=1, spp=64,
        resolution=(96, 96), tags=("lights",))


def soft_shadows():
    floor = Quad("floor", ((-4, -4, 0), (4, -4, 0), (4, 4, 0), (-4, 4, 0)), WHITE)
    spheres = tuple(Sphere(f"ball_{i}", (x, 0.0, 0.45), 0.45, WHITE)
                    for i, x in enumerate((-1.6, 0.0, 1.6)))
    lights = (
        PointLight(location=(-1.2, -0.8, 2.2), intensity=3.0, radius=0.4),
        SpotLight(location=(0.6, -1.2, 2.6), direction=(-0.2, 0.4, -1.0), intensity=6.0,
                  spot_size_deg=60.0, blend=0.3, radius=0.3, color=(1.0, 0.85, 0.7)),
        SunLight(direction=(1.0, -0.6, 1.4), irradiance=1.2, angle_deg=12.0,
                 color=(0.7, 0.8, 1.0)),
    )
    return SceneSpec(
        name="soft_shadows",
        description="Three Lambert spheres on a floor: a point light of radius 0.4, a spot of "
                    "radius 0.3 (60 degrees, blend 0.3) and a sun of angle 12 degrees, direct "
                    "light only",
        camera=Camera(location=(0.0, -6.0, 3.5), look_at=(0.0, 0.0, 0.3), lens_mm=40.0),
        objects=(floor,) + spheres, lights=lights, max_bounces=0, spp=64, resolution=(128, 80),
        tags=("lights",))


def hdri_furnace():
    return SceneSpec(
        name="hdri_furnace",
        description="Furnace under an HDRI: two touching spheres (Lambert 0.8 and Glossy GGX "
                    "0.2) in courtyard.exr, 4 bounces (light passes between them)",
        camera=Camera(location=(0.0, -7.0, 0.0), look_at=(0.0, 0.0, 0.0), lens_mm=50.0),
        objects=(Sphere("sphere_lambert", (-0.8, 0.0, 0.0), 0.8, WHITE),
                 Sphere("sphere_glossy", (0.8, 0.0, 0.0), 0.8, GRID_MATERIALS[3])),
        lights=(), environment=EnvironmentMap(HDRI, strength=1.0, rotation_z_deg=-30.0),
        max_bounces=4, spp=64, resolution=(96, 64), tags=("lights", "gi"))


def gradient_world_sphere():
    return SceneSpec(
        name="gradient_world_sphere",
        description="Lambertian sphere (albedo 0.8) in a world of radiance 0.6 + 0.4 z: the "
                    "closed form is 0.8 (0.6 + 0.4 * 2/3 n_z); one bounce",
        camera=Camera(location=(0.0, -7.0, 0.0), look_at=(0.0, 0.0, 0.0), lens_mm=50.0),
        objects=(Sphere("sphere", (0.0, 0.0, 0.0), 1.0, WHITE),),
        lights=(), environment=ZGradientWorld(a=0.6, b=0.4), max_bounces=1, spp=64,
        resolution=(96, 96), tags=("lights",))


LIGHT_SCENES = (hdri_sphere_grid, hdri_sun_sphere_grid, area_light_room, soft_shadows,
                hdri_furnace, gradient_world_sphere)
