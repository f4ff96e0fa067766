"""Plain-data description of a reference scene.

The same description is built into bpy by `bpy_build` (inside Blender) and ray traced
analytically by `analytic` (outside Blender), so the camera, lights and spheres cannot drift
apart. No bpy here."""
from __future__ import annotations

import math
from dataclasses import dataclass, field


# The `model` of a material built only from Blender shader nodes; its params name the recipe
# (compare/node_recipes.py): {"recipe": name}.
NODES = "blender_nodes"


@dataclass(frozen=True)
class Material:
    name: str
    model: str            # a bxdf model name (DESIGN.md), or NODES
    params: dict          # its parameters, as bxdf.make(model, **params) takes them


@dataclass(frozen=True)
class Sphere:
    name: str
    center: tuple
    radius: float
    material: Material


@dataclass(frozen=True)
class Quad:
    """A planar quad with corners in counter-clockwise order seen from the side its normal faces."""
    name: str
    corners: tuple
    material: Material


@dataclass(frozen=True)
class Box:
    name: str
    center: tuple
    size: tuple
    rotation_z_deg: float
    material: Material


@dataclass(frozen=True)
class PointLight:
    """Radiant intensity `intensity` W/sr (Blender power P = 4*pi*I); a `radius` above 0 makes it
    Cycles' sphere light (soft shadows)."""
    location: tuple
    intensity: float
    color: tuple = (1.0, 1.0, 1.0)
    radius: float = 0.0


@dataclass(frozen=True)
class SpotLight:
    """A point light (as PointLight) limited to a cone along `direction`: full angle
    `spot_size_deg`, Blender's `blend`."""
    location: tuple
    direction: tuple
    intensity: float
    spot_size_deg: float
    blend: float = 0.0
    radius: float = 0.0
    color: tuple = (1.0, 1.0, 1.0)


@dataclass(frozen=True)
class SunLight:
    """Irradiance `irradiance` W/m^2 on a surface facing the sun; `direction` points from the scene
    towards the sun; `angle_deg` is the sun's angular diameter (soft shadows)."""
    direction: tuple
    irradiance: float
    color: tuple = (1.0, 1.0, 1.0)
    angle_deg: float = 0.0


@dataclass(frozen=True)
class AreaLight:
    """Blender's one-sided area light of power `power` W centred at `center`, emitting along
    `direction`; `shape` is SQUARE, RECTANGLE, DISK or ELLIPSE, `size` x `size_y` its extent (the
    square and disk use `size` only)."""
    center: tuple
    direction: tuple
    shape: str
    power: float
    size: float
    size_y: float = 0.0
    color: tuple = (1.0, 1.0, 1.0)


# The world's importance map: Cycles' Manual sampling at this resolution (0: Automatic, whose map
# for a 1024 x 512 image takes Cycles 15 s per render on two cores). Both renderers follow it.
MAP_RESOLUTION = 256


@dataclass(frozen=True)
class EnvironmentMap:
    """An equirectangular image file as the world (Cycles' Environment Texture through Texture
    Coordinate > Mapping), times `strength`, turned by `rotation_z_deg` about +Z."""
    path: str
    strength: float = 1.0
    rotation_z_deg: float = 0.0
    map_resolution: int = MAP_RESOLUTION


@dataclass(frozen=True)
class ZGradientWorld:
    """A world of radiance a + b*z for the direction's z, written as an equirectangular image by
    the scene builder (rows of constant elevation). A Lambertian sphere under it has the
    closed-form irradiance E(n) = pi (a + 2/3 b n_z); a >= |b| keeps it non-negative."""
    a: float
    b: float
    width: int = 512
    height: int = 256
    map_resolution: int = MAP_RESOLUTION


@dataclass(frozen=True)
class Camera:
    location: tuple
    look_at: tuple
    lens_mm: float = 50.0
    sensor_width_mm: float = 36.0

    def horizontal_fov(self) -> float:
        return 2.0 * math.atan(self.sensor_width_mm / 2.0 / self.lens_mm)


@dataclass(frozen=True)
class SceneSpec:
    name: str
    description: str
    camera: Camera
    objects: tuple
    lights: tuple
    world_color: tuple = (0.0, 0.0, 0.0)
    environment: object = None        # EnvironmentMap or ZGradientWorld, replaces world_color
    max_bounces: int = 0              # 0 = direct light only
    spp: int = 64                     # default samples per pixel for the stochastic engines
    resolution: tuple = (128, 128)
    povray_radiosity: bool = False    # POV-Ray's own global illumination (approximate by nature)
    tags: tuple = field(default_factory=tuple)

    def materials(self) -> list:
        seen = {}
        for obj in self.objects:
            seen.setdefault(obj.material.name, obj.material)
        return list(seen.values())

    def has_analytic_truth(self) -> bool:
        """Spheres lit by hard point or sun lights, direct light only (or one Lambertian sphere
        in a constant or z-gradient world): the image is a closed-form function of the model's
        f."""
        if not all(isinstance(o, Sphere) and o.material.model != NODES for o in self.objects):
            return False
        if is_lambert_furnace(self):
            return True
        if self.environment is not None or self.max_bounces != 0:
            return False
        return bool(self.lights) and all(is_hard_light(light) for light in self.lights)


def is_hard_light(light) -> bool:
    """A delta light: a point light of radius 0 or a sun of angle 0."""
    return ((isinstance(light, PointLight) and light.radius == 0.0)
            or (isinstance(light, SunLight) and light.angle_deg == 0.0))


def soft_lighting(spec: SceneSpec) -> list:
    """What of the scene's lighting is more than hard point and sun lights and a colour world
    (POV-Ray's export renders none of it as Cycles does), one description each."""
    found = []
    for light in spec.lights:
        if isinstance(light, PointLight) and light.radius > 0.0:
            found.append(f"point light of radius {light.radius:g}")
        elif isinstance(light, SpotLight):
            found.append(f"spot light (radius {light.radius:g}, blend {light.blend:g})")
        elif isinstance(light, SunLight) and light.angle_deg > 0.0:
            found.append(f"sun of angle {light.angle_deg:g} degrees")
        elif isinstance(light, AreaLight):
            found.append(f"{light.shape.lower()} area light")
    if isinstance(spec.environment, EnvironmentMap):
        found.append(f"environment map {spec.environment.path}")
    elif isinstance(spec.environment, ZGradientWorld):
        found.append("z-gradient world")
    return found


def is_lambert_furnace(spec: SceneSpec) -> bool:
    """One Lambertian sphere in a constant or z-gradient world and no lights: a convex object
    sees only the world, whatever the number of bounces, so its radiance is R * L_world (constant)
    or R (a + 2/3 b n_z) (gradient)."""
    return (not spec.lights and len(spec.objects) == 1 and isinstance(spec.objects[0], Sphere)
            and spec.objects[0].material.model == "lambertian" and spec.max_bounces >= 1
            and (spec.environment is None or isinstance(spec.environment, ZGradientWorld)))
