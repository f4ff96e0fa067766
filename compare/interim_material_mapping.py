"""INTERIM: the model -> Cycles node tree / POV-Ray finish mapping and POV-Ray's light calibration,
used only while the bxdf_lab add-on's "Set Up Cycles Material" / "Set Up POV-Ray Material" operators
have not landed on main. Delete this file (and its imports in material_setup.py and driver.py) once
they have: the add-on owns the mapping, and there must not be two copies of it.

Exact where the formulas agree (reference/renderers.md): Lambert everywhere, Cycles' own Oren-Nayar
and Glossy (GGX/Beckmann, separable Smith, F = 1) in Cycles, Lambert in POV-Ray with the light
calibration of engine_setup. Everything else is a best approximation."""
from __future__ import annotations

import math

from .scene_spec import PointLight, SunLight

# A fade distance of about 1 cm keeps POV-Ray's 2/(1 + (d/D)^2) within (D/d)^2 ~ 1e-5 of 2 D^2/d^2
# at scene distances; the exporter writes the colour as `srgb <%.3g>` and D as %.6f.
POV_FADE_DISTANCE = 0.01


def srgb_to_linear(c: float) -> float:
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def linear_to_srgb(c: float) -> float:
    return c * 12.92 if c <= 0.0031308 else 1.055 * c ** (1.0 / 2.4) - 0.055


def _rgb(value):
    if isinstance(value, (int, float)):
        return (float(value),) * 3
    return tuple(float(v) for v in value)


def _f0_conductor(eta, k):
    """Normal-incidence reflectance of a conductor: ((eta-1)^2 + k^2) / ((eta+1)^2 + k^2)."""
    return tuple(((e - 1) ** 2 + kk ** 2) / ((e + 1) ** 2 + kk ** 2)
                 for e, kk in zip(_rgb(eta), _rgb(k)))


def _f0_dielectric(eta_i, eta_t):
    return (((eta_t - eta_i) / (eta_t + eta_i)) ** 2,) * 3


def _fresnel_tint(params):
    fresnel = params.get("fresnel", "none")
    if fresnel == "conductor":
        return _f0_conductor(params.get("eta", 1.0), params.get("k", 0.0))
    if fresnel == "dielectric":
        return _f0_dielectric(params.get("eta_i", 1.0), params.get("eta_t", 1.5))
    return (1.0, 1.0, 1.0)


def _mul(a, b):
    return tuple(x * y for x, y in zip(a, b))


def _alpha(params):
    """A single GGX/Beckmann alpha for a microfacet model (Blinn exponent e ~ 2/alpha^2 - 2)."""
    dist = params.get("distribution", "ggx")
    if dist in ("ggx", "beckmann"):
        alpha_x = params.get("alpha_x", 0.1)
        return math.sqrt(alpha_x * params.get("alpha_y", alpha_x))
    if dist == "blinn":
        return math.sqrt(2.0 / (params.get("exponent", 20.0) + 2.0))
    e = math.sqrt(params.get("exponent_x", 20.0) * params.get("exponent_y", 20.0))
    return math.sqrt(2.0 / (e + 2.0))


# ---- Cycles -----------------------------------------------------------------------------------

def setup_cycles(material, model, params):
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")

    def bsdf(kind, **inputs):
        node = tree.nodes.new(kind)
        for name, value in inputs.items():
            if name == "distribution":
                node.distribution = value
            else:
                node.inputs[name].default_value = value
        tree.links.new(node.outputs["BSDF"], out.inputs["Surface"])
        return node

    if model == "lambertian":
        bsdf("ShaderNodeBsdfDiffuse", Color=(*_rgb(params["reflectance"]), 1), Roughness=0.0)
    elif model == "cycles_oren_nayar":
        bsdf("ShaderNodeBsdfDiffuse", Color=(*_rgb(params["color"]), 1),
             Roughness=params["roughness"])
    elif model == "oren_nayar":
        # Cycles' improved Oren-Nayar takes sigma in [0, 1] directly; classic sigma is degrees.
        bsdf("ShaderNodeBsdfDiffuse", Color=(*_rgb(params["reflectance"]), 1),
             Roughness=min(1.0, math.radians(params["sigma"])))
    elif model == "cycles_glossy":
        bsdf("ShaderNodeBsdfGlossy", Color=(*_rgb(params["color"]), 1),
             Roughness=params["roughness"], distribution=params["distribution"].upper())
    elif model == "microfacet":
        dist = "BECKMANN" if params.get("distribution") == "beckmann" else "GGX"
        color = _mul(_rgb(params.get("reflectance", 1.0)), _fresnel_tint(params))
        bsdf("ShaderNodeBsdfGlossy", Color=(*color, 1), Roughness=math.sqrt(_alpha(params)),
             distribution=dist)
    elif model == "fresnel_specular":
        bsdf("ShaderNodeBsdfGlass", Color=(*_rgb(params["transmittance"]), 1), Roughness=0.0,
             IOR=params["eta_t"] / params["eta_i"], distribution="SHARP")
    else:
        raise NotImplementedError(f"no interim Cycles mapping for model '{model}'")


# ---- POV-Ray ----------------------------------------------------------------------------------

def _pov_base(material, color):
    material.use_nodes = False           # render_povray exports only non-node materials
    material.diffuse_color = (*color, 1.0)
    pov = material.pov
    pov.ambient = 0.0                    # default 1.0 would add the colour everywhere
    pov.emit = 0.0
    pov.diffuse_shader = "LAMBERT"       # brilliance 1
    pov.diffuse_intensity = 1.0          # the 1/pi of Lambert is in the light calibration
    pov.translucency = 0.0
    pov.specular_intensity = 0.0         # default phong 0.1 -> none
    pov.conserve_energy = False
    material.pov_raytrace_mirror.use = False
    return pov


def _pov_highlight(material, color, alpha):
    """POV's Blinn `specular S (n.h)^(1/roughness)`, no normalisation or n.l: exponent
    e = 2/alpha^2 - 2 and S = (e + 2)/8, the peak of D/(4 cos cos) times pi (light calibration)."""
    pov = material.pov
    e = max(2.0 / (alpha * alpha) - 2.0, 1.0)
    pov_roughness = min(max(1.0 / e, 1.0 / 511.0), 0.1 + 1.0 / 511.0)
    hardness = 1.0 + 510.0 * (1.0 - (pov_roughness - 1.0 / 511.0) / 0.1)
    pov.specular_shader = "BLINN"
    # The exporter writes specular = intensity * ior / 4 with intensity <= 1 and ior <= 10, so
    # POV-Ray's highlight cannot exceed 2.5: sharp lobes come out too dim (a finding).
    strength = (e + 2.0) / 8.0 * max(color)
    pov.specular_intensity = min(strength, 1.0)
    pov.specular_ior = min(4.0 * strength / max(pov.specular_intensity, 1e-6), 10.0)
    pov.specular_hardness = int(round(min(max(hardness, 1.0), 511.0)))
    pov.specular_color = color if max(color) > 0 else (1.0, 1.0, 1.0)
    return pov


def setup_povray(material, model, params):
    if model in ("lambertian", "cycles_oren_nayar", "oren_nayar"):
        # POV-Ray has no Oren-Nayar: the rough diffuse models become Lambert of the same colour.
        key = {"lambertian": "reflectance", "cycles_oren_nayar": "color",
               "oren_nayar": "reflectance"}[model]
        _pov_base(material, _rgb(params[key]))
    elif model in ("cycles_glossy", "microfacet"):
        if model == "cycles_glossy":
            color, alpha = _rgb(params["color"]), params["roughness"] ** 2
        else:
            color = _mul(_rgb(params.get("reflectance", 1.0)), _fresnel_tint(params))
            alpha = _alpha(params)
        pov = _pov_base(material, (0.0, 0.0, 0.0))
        pov.diffuse_intensity = 0.0
        _pov_highlight(material, color, alpha)
        if alpha < 0.1:
            # A nearly sharp metal: POV-Ray's mirror reflection shows the room in it.
            mirror = material.pov_raytrace_mirror
            mirror.use = True
            mirror.reflect_factor = 1.0
            pov.mirror_color = color
    elif model == "fresnel_specular":
        pov = _pov_base(material, _rgb(params["transmittance"]))
        material.diffuse_color = (*_rgb(params["transmittance"]), 0.0)   # transmit 1
        pov.diffuse_intensity = 0.0
        pov.use_transparency = True
        pov.transparency_method = "RAYTRACE"
        material.pov_raytrace_transparency.ior = params["eta_t"] / params["eta_i"]
        pov.mirror_use_IOR = True            # reflection weighted by POV's own Fresnel
        pov.conserve_energy = True           # transmission reduced by what is reflected
        mirror = material.pov_raytrace_mirror
        mirror.use = True
        mirror.reflect_factor = 1.0
        pov.mirror_color = (1.0, 1.0, 1.0)
    else:
        raise NotImplementedError(f"no interim POV-Ray mapping for model '{model}'")


def calibrate_povray_lights(spec) -> None:
    """POV-Ray ignores light energy and attenuates a point light by 2 / (1 + (d/D)^2) with
    D = sqrt(distance/2); for D << d that is 2 D^2 / d^2. Its diffuse term has no 1/pi, so a
    Lambertian match needs colour C with C * 2 D^2 = I / pi; a sun (parallel light, no fade) needs
    C = E / pi."""
    import bpy  # noqa: PLC0415 - inside Blender only

    lights = [o for o in bpy.context.scene.objects if o.type == "LIGHT"]
    lights.sort(key=lambda o: int(o.name.rsplit("_", 1)[1]))
    for obj, light in zip(lights, spec.lights):
        data = obj.data
        if isinstance(light, PointLight):
            intensity = [light.intensity * ch for ch in light.color]
            peak = max(range(3), key=lambda k: intensity[k])
            # The colour POV-Ray will read back after the exporter's 3-digit formatting ...
            written = [float(f"{linear_to_srgb(i / (math.pi * 2 * POV_FADE_DISTANCE ** 2)):.3g}")
                       for i in intensity]
            # ... and the fade distance that makes C * 2 D^2 = I / pi hold for it exactly.
            fade = round(math.sqrt(intensity[peak] / (math.pi * 2 * srgb_to_linear(written[peak]))),
                         6)
            data.distance = 2.0 * fade * fade
            data.falloff_type = "INVERSE_SQUARE"
            data.color = written
        elif isinstance(light, SunLight):
            data.color = tuple(linear_to_srgb(light.irradiance * ch / math.pi)
                               for ch in light.color)
