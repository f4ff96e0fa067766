"""The reference scenes. Each is a function returning a SceneSpec; `bpy_build.build(spec)` turns it
into a bpy scene inside Blender and `analytic.render(spec)` computes its closed-form image.

Light strengths are chosen so that a 0.8-albedo surface comes out near 0.5 (POV-Ray's 16-bit PNG
clips at 1); the sun's irradiance is pi * srgb_to_linear(0.9) so that the POV-Ray light colour
E/pi, which render_povray writes as three-digit sRGB, is represented exactly."""
from __future__ import annotations

import math
from dataclasses import replace

from .light_scenes import LIGHT_SCENES
from .node_scenes import DEFAULT_NODE_SCENES, NODE_SCENES
from .scene_spec import Box, Camera, Material, PointLight, Quad, SceneSpec, Sphere, SunLight


def srgb_to_linear(c: float) -> float:
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


SPHERE_CAMERA = Camera(location=(0.0, -7.0, 0.0), look_at=(0.0, 0.0, 0.0), lens_mm=50.0)
# Up, right and in front of the sphere: lit crescent plus a visible highlight for glossy models.
SPHERE_KEY_LIGHT = PointLight(location=(3.0, -4.0, 3.0), intensity=40.0)
SUN_IRRADIANCE = math.pi * srgb_to_linear(0.9)


def _lit_sphere(name, description, material, spp=16):
    return SceneSpec(
        name=name, description=description, camera=SPHERE_CAMERA,
        objects=(Sphere("sphere", (0.0, 0.0, 0.0), 1.0, material),),
        lights=(SPHERE_KEY_LIGHT,), max_bounces=0, spp=spp, resolution=(128, 128),
        tags=("lit_sphere",))


def lit_lambertian():
    return _lit_sphere("lit_lambertian", "Lambertian sphere, one point light, direct light only",
                       Material("lambert_orange", "lambertian", {"reflectance": (0.8, 0.55, 0.3)}))


def lit_cycles_oren_nayar():
    return _lit_sphere("lit_cycles_oren_nayar",
                       "Cycles' improved Oren-Nayar (roughness 0.8), one point light",
                       Material("cycles_on_rough", "cycles_oren_nayar",
                                {"color": (0.8, 0.8, 0.8), "roughness": 0.8}))


def lit_oren_nayar():
    return _lit_sphere("lit_oren_nayar", "Classic Oren-Nayar, sigma 30 degrees, one point light",
                       Material("oren_nayar_30", "oren_nayar",
                                {"reflectance": (0.8, 0.8, 0.8), "sigma": 30.0}))


def lit_cycles_glossy_ggx():
    return _lit_sphere("lit_cycles_glossy_ggx", "Cycles Glossy GGX, roughness 0.4, one point light",
                       Material("glossy_ggx_04", "cycles_glossy",
                                {"color": (0.9, 0.9, 0.9), "distribution": "ggx",
                                 "roughness": 0.4}))


def lit_cycles_glossy_beckmann():
    return _lit_sphere("lit_cycles_glossy_beckmann",
                       "Cycles Glossy Beckmann, roughness 0.3, one point light",
                       Material("glossy_beckmann_03", "cycles_glossy",
                                {"color": (0.9, 0.9, 0.9), "distribution": "beckmann",
                                 "roughness": 0.3}))


def lit_cycles_glossy_ashikhmin_shirley():
    return _lit_sphere("lit_cycles_glossy_ashikhmin_shirley",
                       "Cycles Glossy Ashikhmin-Shirley, roughness 0.4, one point light",
                       Material("glossy_as_04", "cycles_glossy",
                                {"color": (0.9, 0.9, 0.9), "distribution": "ashikhmin_shirley",
                                 "roughness": 0.4}))


def lit_cycles_velvet():
    return _lit_sphere("lit_cycles_velvet", "Cycles Velvet, sigma 0.5, one point light",
                       Material("velvet_05", "cycles_velvet",
                                {"color": (0.8, 0.5, 0.6), "sigma": 0.5}), spp=64)


def cycles_glass_room():
    """Glass, refraction, translucent and velvet spheres in the Cornell room with global
    illumination: every material is one Cycles node, so BXDF_LAB and CYCLES must agree."""
    ior = 1.45
    materials = (
        Material("glass_sharp", "cycles_glass",
                 {"color": (1.0, 1.0, 1.0), "distribution": "sharp", "ior": ior}),
        Material("refraction_ggx", "cycles_refraction",
                 {"color": (0.9, 0.95, 1.0), "distribution": "ggx", "roughness": 0.3, "ior": ior}),
        Material("glass_beckmann", "cycles_glass",
                 {"color": (1.0, 0.95, 0.8), "distribution": "beckmann", "roughness": 0.3,
                  "ior": ior}),
        Material("translucent", "cycles_translucent", {"color": (0.8, 0.6, 0.4)}),
        Material("velvet", "cycles_velvet", {"color": (0.5, 0.6, 0.9), "sigma": 0.4}),
    )
    places = ((-0.55, 0.4), (0.0, 0.4), (0.55, 0.4), (-0.3, -0.35), (0.3, -0.35))
    spheres = tuple(Sphere(f"ball_{m.name}", (x, y, 0.24), 0.24, m)
                    for (x, y), m in zip(places, materials))
    return SceneSpec(
        name="cycles_glass_room",
        description="Cornell-like room with Cycles' Glass (sharp, Beckmann 0.3), Refraction (GGX "
                    "0.3), Translucent and Velvet spheres, ior 1.45, global illumination "
                    "(8 bounces), one point light",
        camera=Camera(location=(0.0, -3.9, 1.0), look_at=(0.0, 0.0, 0.6), lens_mm=45.0),
        objects=_cornell_walls() + spheres,
        lights=(PointLight(location=(0.0, -0.2, 1.6), intensity=1.5),),
        max_bounces=8, spp=256, resolution=(128, 128), povray_radiosity=True, tags=("gi",))


def sun_sphere():
    return SceneSpec(
        name="sun_sphere", description="Lambertian sphere under a sun (directional) light",
        camera=SPHERE_CAMERA,
        objects=(Sphere("sphere", (0.0, 0.0, 0.0), 1.0,
                        Material("lambert_grey", "lambertian", {"reflectance": (0.7, 0.7, 0.7)})),),
        lights=(SunLight(direction=(1.0, -1.0, 1.0), irradiance=SUN_IRRADIANCE),),
        max_bounces=0, spp=16, resolution=(128, 128), tags=("lit_sphere",))


def furnace():
    return SceneSpec(
        name="furnace",
        description="Furnace: Lambertian sphere (albedo 0.8) in a uniform white world, all "
                    "bounces; truth is 0.8 on the sphere and 1 elsewhere",
        camera=SPHERE_CAMERA,
        objects=(Sphere("sphere", (0.0, 0.0, 0.0), 1.0,
                        Material("lambert_08", "lambertian", {"reflectance": (0.8, 0.8, 0.8)})),),
        lights=(), world_color=(1.0, 1.0, 1.0), max_bounces=4, spp=64, resolution=(96, 96),
        povray_radiosity=True, tags=("gi",))


def sweep_glossy_roughness():
    roughness = (0.1, 0.25, 0.4, 0.6, 0.85)
    spheres = tuple(
        Sphere(f"sphere_{i}", (-2.0 + 1.0 * i, 0.0, 0.0), 0.42,
               Material(f"glossy_ggx_r{r:g}", "cycles_glossy",
                        {"color": (0.9, 0.9, 0.9), "distribution": "ggx", "roughness": r}))
        for i, r in enumerate(roughness))
    return SceneSpec(
        name="sweep_glossy_roughness",
        description="Row of Cycles Glossy GGX spheres, roughness " + ", ".join(map(str, roughness)),
        camera=Camera(location=(0.0, -9.0, 0.0), look_at=(0.0, 0.0, 0.0), lens_mm=50.0),
        objects=spheres, lights=(PointLight(location=(1.0, -6.0, 3.0), intensity=60.0),),
        max_bounces=0, spp=16, resolution=(256, 80), tags=("sweep",))


def sweep_oren_nayar_sigma():
    sigmas = (0.0, 10.0, 20.0, 40.0, 60.0)
    spheres = tuple(
        Sphere(f"sphere_{i}", (-2.0 + 1.0 * i, 0.0, 0.0), 0.42,
               Material(f"oren_nayar_s{s:g}", "oren_nayar",
                        {"reflectance": (0.8, 0.8, 0.8), "sigma": s}))
        for i, s in enumerate(sigmas))
    return SceneSpec(
        name="sweep_oren_nayar_sigma",
        description="Row of classic Oren-Nayar spheres, sigma " + ", ".join(map(str, sigmas)),
        camera=Camera(location=(0.0, -9.0, 0.0), look_at=(0.0, 0.0, 0.0), lens_mm=50.0),
        objects=spheres, lights=(PointLight(location=(4.0, -3.0, 2.0), intensity=60.0),),
        max_bounces=0, spp=16, resolution=(256, 80), tags=("sweep",))


def _principled_grid(name, description, rows, max_bounces=0, spp=16):
    """Rows (top to bottom) of five Principled spheres; each row is a list of parameter dicts."""
    spheres = []
    for j, row in enumerate(rows):
        for i, params in enumerate(row):
            label = "_".join(f"{k}{v}" for k, v in sorted(params.items())
                             if not isinstance(v, tuple)).replace(".", "")
            spheres.append(Sphere(f"sphere_{j}_{i}", (-2.0 + 1.0 * i, 0.0, 1.0 * (len(rows) - 1) / 2 - j),
                                  0.42, Material(f"principled_{j}_{i}_{label}"[:60], "cycles_principled",
                                                 {"base_color": (0.8, 0.45, 0.25), **params})))
    return SceneSpec(
        name=name, description=description,
        camera=Camera(location=(0.0, -11.0, 0.0), look_at=(0.0, 0.0, 0.0), lens_mm=50.0),
        objects=tuple(spheres), lights=(PointLight(location=(2.0, -7.0, 4.0), intensity=120.0),),
        max_bounces=max_bounces, spp=spp, resolution=(200, 40 * len(rows) + 40), tags=("sweep",))


def sweep_principled_metallic_roughness():
    roughness = (0.1, 0.25, 0.4, 0.6, 0.85)
    return _principled_grid(
        "sweep_principled_metallic_roughness",
        "Cycles Principled spheres: metallic 0, 0.5, 1 (rows) x roughness 0.1-0.85 (columns)",
        [[{"metallic": m, "roughness": r} for r in roughness] for m in (0.0, 0.5, 1.0)])


def sweep_principled_lobes():
    # Multiscatter is compared in sweep_principled_multiscatter (a Cycles quirk); transmission
    # with bounces in sweep_principled_transmission. Anisotropy uses Cycles' default tangent
    # (radial about the sphere's Z axis), which BXDF_LAB and the analytic image reproduce.
    return _principled_grid(
        "sweep_principled_lobes",
        "Cycles Principled rows: specular and specular tint; sheen and sheen tint; clearcoat and "
        "clearcoat roughness; anisotropic and anisotropic rotation; transmission, IOR and "
        "transmission roughness (direct light)",
        [
            [{"specular": 0.0}, {"specular": 0.5}, {"specular": 1.0},
             {"specular": 1.0, "specular_tint": 0.5}, {"specular": 1.0, "specular_tint": 1.0}],
            [{"sheen": 0.5, "roughness": 0.8}, {"sheen": 1.0, "roughness": 0.8},
             {"sheen": 1.0, "sheen_tint": 0.0, "roughness": 0.8},
             {"sheen": 1.0, "sheen_tint": 1.0, "roughness": 0.8},
             {"sheen": 1.0, "roughness": 0.8, "metallic": 0.5}],
            [{"clearcoat": 0.5}, {"clearcoat": 1.0}, {"clearcoat": 1.0, "clearcoat_roughness": 0.2},
             {"clearcoat": 1.0, "clearcoat_roughness": 0.5},
             {"clearcoat": 1.0, "clearcoat_roughness": 0.5, "metallic": 1.0}],
            [{"anisotropic": 0.5, "roughness": 0.3}, {"anisotropic": 0.9, "roughness": 0.4},
             {"anisotropic": 0.9, "roughness": 0.4, "anisotropic_rotation": 0.125},
             {"anisotropic": 0.9, "roughness": 0.4, "anisotropic_rotation": 0.25},
             {"anisotropic": 0.7, "roughness": 0.5, "metallic": 1.0, "anisotropic_rotation": 0.4}],
            [{"transmission": 0.5, "roughness": 0.1, "ior": 1.3},
             {"transmission": 0.5, "roughness": 0.2, "ior": 1.8},
             {"transmission": 0.5, "roughness": 0.5, "transmission_roughness": 0.5},
             {"transmission": 0.25, "roughness": 0.3}, {"transmission": 0.75, "roughness": 0.3}],
        ])


def sweep_principled_transmission():
    """Transmission: the light reaches the camera through the spheres only by refracting twice,
    once by next-event estimation through the rough refraction closure, so this scene needs
    bounces (and has no analytic image)."""
    return _principled_grid(
        "sweep_principled_transmission",
        "Cycles Principled rows: transmission 1 with IOR 1.1-2.5 (roughness 0.3); transmission "
        "roughness 0-1 (roughness 0.2, IOR 1.45); transmission 0-1 (roughness 0.4); 6 bounces",
        [
            [{"transmission": 1.0, "roughness": 0.3, "ior": ior} for ior in (1.1, 1.3, 1.45, 1.8, 2.5)],
            [{"transmission": 1.0, "roughness": 0.2, "transmission_roughness": t}
             for t in (0.0, 0.25, 0.5, 0.75, 1.0)],
            [{"transmission": t, "roughness": 0.4} for t in (0.0, 0.25, 0.5, 0.75, 1.0)],
        ], max_bounces=6, spp=32)


def sweep_principled_multiscatter():
    """Single-scatter GGX (top) against multiscatter GGX (bottom) in a white world (no lights):
    the light is found by BSDF sampling alone, which for multiscatter GGX is Cycles' sampling
    walk (it disagrees with the eval walk: multiscatter_ggx.h), in BXDF_LAB as in Cycles; the
    top row shows the rest of the scene agreeing."""
    columns = [{"metallic": 1.0, "base_color": (0.95, 0.95, 0.95), "roughness": r}
               for r in (0.3, 0.5, 0.7, 0.9)] + [{"roughness": 0.6}]
    return replace(_principled_grid(
        "sweep_principled_multiscatter",
        "Cycles Principled in a white world: GGX (top row) against Multiscatter GGX (bottom "
        "row); white metal at roughness 0.3-0.9 and a dielectric at roughness 0.6; one bounce",
        [columns, [{**c, "distribution": "multi_ggx"} for c in columns]], max_bounces=1, spp=32),
        lights=(), world_color=(1.0, 1.0, 1.0))


def sweep_principled_multiscatter_direct():
    """The same spheres under a point light, direct light only: Cycles evaluates its walk and
    never samples it, so its image converges to the walk's expectation, and so does BXDF_LAB's
    (its walks salted per sample, multiscatter_ggx.h): an exact pairing."""
    columns = [{"metallic": 1.0, "base_color": (0.95, 0.95, 0.95), "roughness": r}
               for r in (0.3, 0.5, 0.7, 0.9)] + [{"roughness": 0.6}]
    return _principled_grid(
        "sweep_principled_multiscatter_direct",
        "Cycles Principled under a point light: GGX (top row) against Multiscatter GGX (bottom "
        "row); white metal at roughness 0.3-0.9 and a dielectric at roughness 0.6; direct light",
        [columns, [{**c, "distribution": "multi_ggx"} for c in columns]], spp=64)


def principled_clearcoat_world():
    """Clearcoat spheres in a white world (no lights): the light is found by BSDF sampling
    alone, where Cycles' clearcoat weights GGX's visible normals by a GTR1 pdf (biased), as
    BXDF_LAB's Cycles sampler does too. The top row has no clearcoat and shows what the rest of
    the material does."""
    base = {"base_color": (0.05, 0.05, 0.05), "roughness": 0.6}
    rows = [[{**base, "specular": s} for s in (0.0, 0.25, 0.5, 0.75, 1.0)],
            [{**base, "clearcoat": 1.0, "clearcoat_roughness": r} for r in (0.0, 0.1, 0.3, 0.6, 1.0)]]
    return replace(_principled_grid(
        "principled_clearcoat_world",
        "Cycles Principled in a white world, dark base: specular 0-1 (top), clearcoat 1 with "
        "clearcoat roughness 0-1 (bottom); one bounce", rows, max_bounces=1, spp=64),
        lights=(), world_color=(1.0, 1.0, 1.0))


def _cornell_walls():
    white = Material("cornell_white", "lambertian", {"reflectance": (0.73, 0.73, 0.73)})
    red = Material("cornell_red", "lambertian", {"reflectance": (0.63, 0.065, 0.05)})
    green = Material("cornell_green", "lambertian", {"reflectance": (0.14, 0.45, 0.091)})
    # Room x in [-1, 1], y in [-1, 1] (open towards -y, the camera), z in [0, 2].
    return (
        Quad("floor", ((-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)), white),
        Quad("ceiling", ((-1, -1, 2), (-1, 1, 2), (1, 1, 2), (1, -1, 2)), white),
        Quad("back_wall", ((-1, 1, 0), (1, 1, 0), (1, 1, 2), (-1, 1, 2)), white),
        Quad("left_wall", ((-1, -1, 0), (-1, 1, 0), (-1, 1, 2), (-1, -1, 2)), red),
        Quad("right_wall", ((1, -1, 0), (1, -1, 2), (1, 1, 2), (1, 1, 0)), green),
    )


def cornell():
    diffuse = Material("box_diffuse", "lambertian", {"reflectance": (0.73, 0.73, 0.73)})
    glossy = Material("sphere_glossy", "cycles_glossy",
                      {"color": (0.8, 0.8, 0.8), "distribution": "ggx", "roughness": 0.5})
    gold = Material("sphere_gold", "microfacet",
                    {"reflectance": (1.0, 1.0, 1.0), "distribution": "ggx",
                     "alpha_x": 0.05, "alpha_y": 0.05, "shadowing": "smith",
                     "fresnel": "conductor", "eta": (0.370, 0.370, 0.370),
                     "k": (2.820, 2.820, 2.820)})
    glass = Material("sphere_glass", "fresnel_specular",
                     {"reflectance": (1.0, 1.0, 1.0), "transmittance": (1.0, 1.0, 1.0),
                      "eta_i": 1.0, "eta_t": 1.5})
    objects = _cornell_walls() + (
        Box("tall_box", (-0.4, 0.35, 0.6), (0.55, 0.55, 1.2), 20.0, diffuse),
        Sphere("glossy_ball", (0.45, 0.45, 0.3), 0.3, glossy),
        Sphere("gold_ball", (-0.5, -0.45, 0.25), 0.25, gold),
        Sphere("glass_ball", (0.35, -0.35, 0.3), 0.3, glass),
    )
    return SceneSpec(
        name="cornell",
        description="Cornell-like room: diffuse box, glossy, gold and glass spheres, global "
                    "illumination (4 bounces), one point light in the upper middle of the room",
        camera=Camera(location=(0.0, -3.9, 1.0), look_at=(0.0, 0.0, 1.0), lens_mm=45.0),
        objects=objects, lights=(PointLight(location=(0.0, -0.2, 1.45), intensity=1.2),),
        max_bounces=4, spp=128, resolution=(128, 128), povray_radiosity=True, tags=("gi",))


SCENES = {f().name: f for f in (
    lit_lambertian, lit_cycles_oren_nayar, lit_oren_nayar, lit_cycles_glossy_ggx,
    lit_cycles_glossy_beckmann, sun_sphere, furnace, sweep_glossy_roughness,
    sweep_oren_nayar_sigma, cornell, sweep_principled_metallic_roughness,
    sweep_principled_lobes, lit_cycles_glossy_ashikhmin_shirley, lit_cycles_velvet,
    cycles_glass_room, sweep_principled_transmission, sweep_principled_multiscatter,
    sweep_principled_multiscatter_direct, principled_clearcoat_world)}
SCENES.update({f().name: f for f in LIGHT_SCENES})

DEFAULT_SCENES = tuple(SCENES) + tuple(f().name for f in DEFAULT_NODE_SCENES)
SCENES.update({f().name: f for f in NODE_SCENES})


def get(name: str) -> SceneSpec:
    try:
        return SCENES[name]()
    except KeyError:
        raise ValueError(f"unknown scene {name!r}; known scenes: {', '.join(SCENES)}") from None
