"""POV-Ray 3.7 (Blender's render_povray add-on) settings closest to a BxDF Lab material.

POV's finish model (reference/renderers.md): per light, diffuse = D·pigment·(n·l) with no 1/π,
Blinn specular = S·(n·h)^(1/roughness) with no n·l, normalisation or Fresnel; ambient defaults to
0.1 and radiosity is on. render_povray exports a material from `diffuse_color` and
`material.pov.*` only when `use_nodes` is False, and writes every light as `color srgb <color>`
ignoring its energy, with fade_distance = √(distance/2) and fade_power 2 for inverse-square falloff.

Lights are calibrated so that all three engines see the same light: POV's attenuation
2/(1 + (d/D)²) ≈ 2D²/d² for a small fade distance D, so a Lambertian (f = R/π, POV diffuse 1)
matches when colour C satisfies C·2D² = I/π, with I = P·colour/(4π) the Blender point light's
intensity. We set the light's colour to C (sRGB-encoded, as render_povray writes it) and its
energy so that P·colour, what Cycles and BxDF Lab use, is unchanged, and pick D so that C
survives the add-on's 3-digit formatting exactly. A sun gives irradiance P·colour, so C = P·colour/π.
"""

import math

import numpy as np

from . import api
from .cycles_setup import APPROXIMATE, EXACT, alpha_from_exponent, classic_oren_nayar

FADE_DISTANCE = 0.01  # m: POV's 2/(1 + (d/D)²) is inverse-square within (D/d)² ≈ 1e-5 at d = 3 m


def srgb_encode(c):
    c = max(float(c), 0.0)
    return 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055


def srgb_decode(s):
    return s / 12.92 if s <= 0.04045 else ((s + 0.055) / 1.055) ** 2.4


def _as_written(c):
    """The linear value POV reads back from render_povray's "%.3g" sRGB formatting."""
    return srgb_decode(float(f"{srgb_encode(c):.3g}"))


def calibrate_light(light):
    """Sets `light` (Blender data) so POV-Ray's render of it matches Cycles' and BxDF Lab's.
    Returns a one-line description, or None for light types POV cannot match (area lights)."""
    # What Cycles and BxDF Lab use (energy·colour); kept unchanged below.
    emitted = float(light.energy) * np.array(light.color, dtype=float)
    peak = float(emitted.max())
    if peak <= 0.0:
        return None
    if light.type in ("POINT", "SPOT"):
        target = emitted / (4.0 * math.pi) / (math.pi * 2.0 * FADE_DISTANCE ** 2)
    elif light.type == "SUN":
        target = emitted / math.pi
    else:
        return None
    channel = int(np.argmax(target))
    # render_povray writes `color srgb <light.color>` with "%.3g": POV decodes what is written.
    encoded = [float(f"{srgb_encode(c):.3g}") for c in target]
    read_back = srgb_decode(encoded[channel])
    if light.type in ("POINT", "SPOT"):
        # Choose D so that the colour POV actually reads gives C·2D² = I/π for the peak channel.
        d = math.sqrt(emitted[channel] / (4.0 * math.pi) / (math.pi * 2.0 * read_back))
        d = round(d, 6)  # render_povray writes fade_distance with "%.6f"
        light.use_custom_distance = False
        light.falloff_type = "INVERSE_SQUARE"
        light.distance = 2.0 * d * d
        text = f"{light.type.lower()}: POV colour {read_back:.4g}, fade distance {d:g}"
    else:
        text = f"sun: POV colour {read_back:.4g} = irradiance/π"
    # Cycles and BxDF Lab use energy·colour linearly: keep it for the peak channel (all channels
    # for a grey light; a coloured light's hue shifts slightly since sRGB encoding is nonlinear).
    light.color = encoded
    light.energy = float(emitted[channel] / encoded[channel])
    if len(set(encoded)) > 1:
        text += " (coloured light: approximate)"
    return text


def _finish_for(name, params, model):
    """(pigment RGB, diffuse, specular dict or None, mirror RGB or None, label, text)."""
    if name == "lambertian":
        return params["reflectance"], 1.0, None, None, EXACT, "Lambert: diffuse 1, brilliance 1"
    if name == "oren_nayar":
        _, _, a, _ = classic_oren_nayar(params["reflectance"], params["sigma"])
        return (tuple(a * c for c in params["reflectance"]), 1.0, None, None, APPROXIMATE,
                f"Oren–Nayar → Lambert with its constant term A = {a:.4g} (POV has no Oren–Nayar)")
    if name == "specular_reflection":
        return ((0, 0, 0), 0.0, None, params["reflectance"], APPROXIMATE,
                "mirror → POV reflection with the reflectance colour (no Fresnel)")
    if name == "cycles_glossy" and params["distribution"] == "sharp":
        return ((0, 0, 0), 0.0, None, params["color"], APPROXIMATE,
                "Cycles' sharp glossy → POV reflection with the colour")
    if name in ("microfacet", "cycles_glossy"):
        distribution = params["distribution"]
        if name == "cycles_glossy":  # every distribution: Cycles' α = roughness² (isotropic part)
            alpha = float(params["roughness"]) ** 2
            exponent = 2.0 / max(alpha * alpha, 1e-12) - 2.0
        elif distribution == "blinn":
            exponent = float(params["exponent"])
        elif distribution == "ashikhmin_shirley":
            exponent = math.sqrt(float(params["exponent_x"]) * float(params["exponent_y"]))
        else:
            alpha = math.sqrt(float(params["alpha_x"]) * float(params["alpha_y"]))
            exponent = 2.0 / max(alpha * alpha, 1e-12) - 2.0
        reflectance = np.asarray(params["color" if name == "cycles_glossy" else "reflectance"],
                                 dtype=float)
        # Blinn lobe at normal view: f·cosθi·E ≈ R(n+2)/(8π)·(n·h)^n·I/d² and POV gives
        # S·(n·h)^e·C·2D²/d² = S·(n·h)^e·I/(π d²): S = R(n+2)/8, e = n.
        strength = float(reflectance.max()) * (exponent + 2.0) / 8.0
        # The pigment carries microfacet's optional Lambertian term; the highlight is grey.
        diffuse = tuple(params.get("diffuse", (0.0, 0.0, 0.0)))
        return (diffuse, 1.0 if max(diffuse) > 0.0 else 0.0,
                {"exponent": exponent, "strength": strength}, None, APPROXIMATE,
                f"{distribution} → POV Blinn highlight exponent {exponent:.4g} (α = "
                f"{alpha_from_exponent(exponent):.4g}), strength R(n+2)/8 = {strength:.4g} "
                "clamped to POV's range; no Fresnel, shadowing or 1/cosθo")
    if name == "cycles_oren_nayar":
        # Its constant term is colour·A, A = 1/(π + (π/2 − 2/3)σ); POV's diffuse stands for R/π.
        scale = math.pi / (math.pi + (math.pi / 2 - 2.0 / 3.0) * float(params["roughness"]))
        return (tuple(scale * c for c in params["color"]), 1.0, None, None, APPROXIMATE,
                f"Cycles' Oren–Nayar → Lambert with its constant term (colour × {scale:.4g}); "
                "POV has no Oren–Nayar")
    if name == "cycles_principled":
        return _principled_finish(params)
    if name in _CYCLES_NODE_FINISHES:
        return _CYCLES_NODE_FINISHES[name](params, model)
    albedo = tuple(float(c) for c in np.asarray(model.rho_hh(4096)).reshape(3))
    return (albedo, 1.0, None, None, APPROXIMATE,
            f"{name} → Lambert with the hemispherical albedo ({albedo[0]:.3f}, {albedo[1]:.3f}, "
            f"{albedo[2]:.3f})")


def _principled_finish(params):
    """Principled → POV: the diffuse closure as Lambert (weight (1 − metallic)(1 − transmission),
    base mixed with the subsurface colour), the specular as a Blinn highlight of GGX α = r²
    whose strength is F0's, and metallic as a mirror tinted by the base colour."""
    subsurface = float(params["subsurface"])
    base = (1.0 - subsurface) * np.asarray(params["base_color"], dtype=float) + \
        subsurface * np.asarray(params["subsurface_color"], dtype=float)
    metallic = float(params["metallic"])
    transmission = float(params["transmission"])
    diffuse_weight = (1.0 - metallic) * (1.0 - transmission)
    alpha = max(float(params["roughness"]) ** 2, 1e-6)
    exponent = 2.0 / (alpha * alpha) - 2.0
    f0 = 0.08 * float(params["specular"]) * (1.0 - metallic) + metallic * float(base.max())
    strength = f0 * (exponent + 2.0) / 8.0
    mirror = tuple(metallic * base) if metallic > 0.0 and params["roughness"] < 0.1 else None
    # With transmission the pigment is the base colour, which POV's filter passes in proportion
    # t(1 − metallic) and whose diffuse POV scales by 1 − t(1 − metallic): D undoes that scale.
    filtered = transmission * (1.0 - metallic)
    if filtered > 0.0:
        pigment, diffuse = tuple(base), diffuse_weight / (1.0 - filtered) if filtered < 1.0 else 0.0
        transmission_text = (f", filter transparency {filtered:.3g} of the base colour at ior "
                             f"{float(params['ior']):g}; POV has no sheen, clearcoat, rough "
                             "transmission or Fresnel")
    else:
        pigment, diffuse = tuple(base * diffuse_weight), 1.0 if diffuse_weight > 0.0 else 0.0
        transmission_text = "; POV has no sheen, clearcoat, transmission or Fresnel"
    return (pigment, diffuse, {"exponent": exponent, "strength": strength}, mirror, APPROXIMATE,
            f"Principled → Lambert × (1 − metallic)(1 − transmission) = {diffuse_weight:.3g}, "
            f"Blinn highlight exponent {exponent:.4g} with F0 {f0:.3g}"
            + ("" if mirror is None else ", a metallic mirror") + transmission_text)


def _glass_finish(params, model):
    color = tuple(params["color"])
    return (color, 0.0, None, color, APPROXIMATE,
            f"Cycles' Glass → POV glass: filter transparency of the colour, interior ior "
            f"{float(params['ior']):g}, Fresnel mirror (reflection {{fresnel}}) of the colour, "
            "conserve_energy; POV refracts and reflects sharply (roughness "
            f"{float(params['roughness']):g} ignored)")


def _refraction_finish(params, model):
    color = tuple(params["color"])
    return (color, 0.0, None, None, APPROXIMATE,
            f"Cycles' Refraction → POV filter transparency of the colour with interior ior "
            f"{float(params['ior']):g} and no reflection (the node has no Fresnel); POV refracts "
            f"sharply (roughness {float(params['roughness']):g} ignored)")


def _translucent_finish(params, model):
    return (tuple(params["color"]), 0.0, None, None, APPROXIMATE,
            "Cycles' Translucent (colour/π to the far side) → POV back-side diffuse "
            "(diffuse 0, 1: POV's diffuse stands for R/π); POV lights the back only where a "
            "light is behind the surface and unshadowed, so closed objects stay darker")


def _transparent_finish(params, model):
    return (tuple(params["color"]), 0.0, None, None, APPROXIMATE,
            "Cycles' Transparent → POV filter transparency of the colour with ior 1 (a straight "
            "pass-through); a surface seen and lit through it comes out × colour in POV, "
            "× colour² in Cycles (its transparent shadows filter the light too)")


def _velvet_finish(params, model):
    albedo = tuple(float(c) for c in np.asarray(model.rho_hh(4096)).reshape(3))
    return (albedo, 1.0, None, None, APPROXIMATE,
            f"Cycles' Velvet → Lambert with its hemispherical albedo ({albedo[0]:.3f}, "
            f"{albedo[1]:.3f}, {albedo[2]:.3f}): POV has no grazing-angle sheen lobe (its "
            "Oren–Nayar brilliance only flattens the falloff from 0.9 up)")


_CYCLES_NODE_FINISHES = {
    "cycles_glass": _glass_finish,
    "cycles_refraction": _refraction_finish,
    "cycles_translucent": _translucent_finish,
    "cycles_transparent": _transparent_finish,
    "cycles_velvet": _velvet_finish,
}


def _transparency_for(name, params):
    """POV transparency of a material: (filter amount, ior, back-side diffuse, Fresnel mirror)
    or None. POV scales the pigment's diffuse by 1 − filter and passes filter × pigment."""
    if name == "cycles_glass":
        return 1.0, float(params["ior"]), 0.0, True
    if name == "cycles_refraction":
        return 1.0, float(params["ior"]), 0.0, False
    if name == "cycles_transparent":
        return 1.0, 1.0, 0.0, False
    if name == "cycles_translucent":
        return 0.0, 1.0, 1.0, False
    if name == "cycles_principled":
        amount = float(params["transmission"]) * (1.0 - float(params["metallic"]))
        return (amount, float(params["ior"]), 0.0, False) if amount > 0.0 else None
    return None


def hardness_for_exponent(exponent):
    """render_povray writes roughness = 0.1·(1 − (h − 1)/510) + 1/511 for hardness h; POV's
    Blinn exponent is 1/roughness, so POV can show exponents ≈ 9.8 … 511 only."""
    roughness = 1.0 / max(exponent, 1e-6)
    h = 1.0 + 510.0 * (1.0 - (roughness - 1.0 / 511.0) / 0.1)
    return int(round(min(max(h, 1.0), 511.0)))


def _set_transparency(material, transparency):
    pov = material.pov
    pov.translucency = 0.0
    pov.mirror_use_IOR = False
    pov.use_transparency = transparency is not None and transparency[0] > 0.0
    if transparency is None:
        return
    amount, ior, back_diffuse, fresnel_mirror = transparency
    pov.translucency = back_diffuse
    if amount > 0.0:
        # render_povray writes filter = f·(1 − alpha) and transmit = (1 − alpha) − filter.
        pov.transparency_method = "RAYTRACE"
        pov.alpha = 1.0 - amount
        material.pov_raytrace_transparency.filter = 1.0
        material.pov_raytrace_transparency.ior = ior
    pov.mirror_use_IOR = fresnel_mirror
    pov.conserve_energy = fresnel_mirror


def set_up(material, scene=None):
    """Sets `material` (use_nodes off, material.pov.*) and, given `scene`, its lights and
    radiosity for a fair POV-Ray render. Stores and returns (label, mapping text)."""
    model = api.make(material)
    name, _ = api.describe(material)
    pigment, diffuse, specular, mirror, label, text = _finish_for(name, dict(model.params), model)
    pov = material.pov
    material.use_nodes = False
    material.diffuse_color = (*[min(max(float(c), 0.0), 1.0) for c in pigment], 1.0)
    pov.ambient = 0.0
    pov.emit = 0.0
    pov.diffuse_shader = "LAMBERT"
    pov.diffuse_intensity = diffuse
    pov.translucency = 0.0
    pov.conserve_energy = False
    pov.specular_color = (1.0, 1.0, 1.0)  # grey highlight: no "metallic" tint
    if specular:
        pov.specular_shader = "BLINN"
        pov.specular_hardness = hardness_for_exponent(specular["exponent"])
        # render_povray writes specular = intensity·ior/4; intensity ≤ 1 and ior ≤ 10.
        pov.specular_ior = 4.0 if specular["strength"] <= 1.0 else min(4.0 * specular["strength"], 10.0)
        pov.specular_intensity = min(specular["strength"] * 4.0 / pov.specular_ior, 1.0)
    else:
        pov.specular_shader = "BLINN"
        pov.specular_intensity = 0.0
    material.pov_raytrace_mirror.use = mirror is not None
    if mirror is not None:
        material.pov_raytrace_mirror.reflect_factor = 1.0
        material.pov_raytrace_mirror.fresnel_factor = 1.0  # render_povray's "exponent"
        pov.mirror_color = tuple(float(c) for c in mirror)
    _set_transparency(material, _transparency_for(name, dict(model.params)))
    notes = [text]
    if scene is not None:
        scene.pov.radio_enable = False
        for obj in scene.objects:
            if obj.type == "LIGHT":
                done = calibrate_light(obj.data)
                notes.append(f"light '{obj.name}': " + (done or "not calibrated (area light)"))
    material.bxdf_lab.pov_label = label
    material.bxdf_lab.pov_mapping = "; ".join(notes)
    return label, material.bxdf_lab.pov_mapping
