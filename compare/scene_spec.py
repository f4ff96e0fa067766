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
    """Radiant intensity `intensity` W/sr (Blender power P = 4*pi*I), radius 0."""
    location: tuple
    intensity: float
    color: tuple = (1.0, 1.0, 1.0)


@dataclass(frozen=True)
class SunLight:
    """Irradiance `irradiance` W/m^2 on a surface facing the sun; `direction` points from the scene
    towards the sun."""
    direction: tuple
    irradiance: float
    color: tuple = (1.0, 1.0, 1.0)


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
        """Spheres lit by point or sun lights, direct light only (or a furnace of one Lambertian
        sphere): the image is a closed-form function of the model's f."""
        if not all(isinstance(o, Sphere) and o.material.model != NODES for o in self.objects):
            return False
        if self.max_bounces == 0:
            return bool(self.lights)
        return is_lambert_furnace(self)


def is_lambert_furnace(spec: SceneSpec) -> bool:
    """One Lambertian sphere in a constant world and no lights: radiance = R * L_world exactly
    (a convex object sees only the world, whatever the number of bounces)."""
    return (not spec.lights and len(spec.objects) == 1 and isinstance(spec.objects[0], Sphere)
            and spec.objects[0].material.model == "lambertian" and spec.max_bounces >= 1)
