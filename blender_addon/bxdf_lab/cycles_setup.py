"""The Cycles node tree closest to a BxDF Lab material, and whether it is exact.

`exact` means Cycles 3.4 evaluates the same formula (reference/renderers.md: Lambert, Cycles' own
Oren–Nayar, GGX/Beckmann with separable Smith and F = 1, sharp glass, Lambertian transmission,
and every `cycles_*` model, which is one Cycles node);
`approximate` means the best mapping we know, and the mapping text says what was matched.
"""

import math

import numpy as np

from . import api, dependency

EXACT = "exact"
APPROXIMATE = "approximate"


class Mapping:
    """What to build: one BSDF node type, its inputs and settings, the label and the reasoning."""

    def __init__(self, node, label, text, inputs=None, settings=None, diffuse=None):
        self.node, self.label, self.text = node, label, text
        self.inputs = inputs or {}
        self.settings = settings or {}
        self.diffuse = diffuse  # RGB of a Lambertian term added under the lobe, or None


def _rgba(rgb):
    return (*[float(c) for c in rgb], 1.0)


def _clamp01(rgb):
    return tuple(min(max(float(c), 0.0), 1.0) for c in rgb)


def roughness_anisotropy(alpha_x, alpha_y):
    """Cycles' (roughness, anisotropy) giving microfacet widths (αx, αy): Cycles sets
    r = roughness², a ≥ 0 → αx = r(1−a), αy = r/(1−a); a < 0 → αx = r/(1+a), αy = r(1+a)."""
    r = math.sqrt(alpha_x * alpha_y)
    a = 1.0 - math.sqrt(alpha_x / alpha_y) if alpha_x <= alpha_y else math.sqrt(alpha_y / alpha_x) - 1.0
    return math.sqrt(r), a


def alpha_from_exponent(n):
    """Walter et al.'s Blinn–Beckmann correspondence α = √(2/(n+2)) (also Cycles'
    Ashikhmin–Shirley: n = 2/α² − 2)."""
    return math.sqrt(2.0 / (float(n) + 2.0))


def classic_oren_nayar(reflectance, sigma_deg):
    """Cycles' improved Oren–Nayar settings closest to the classic one: match the ratio of the
    s/t term to the constant term (classic B/A = Cycles' σ) and the constant term's colour."""
    s2 = math.radians(sigma_deg) ** 2
    a = 1.0 - 0.5 * s2 / (s2 + 0.33)
    b = 0.45 * s2 / (s2 + 0.09)
    sigma_c = min(b / a, 1.0)
    scale = a * (math.pi + (math.pi / 2 - 2.0 / 3.0) * sigma_c) / math.pi
    color = _clamp01(np.asarray(reflectance) * scale)
    return sigma_c, color, a, b


def _albedo_colour(model):
    return _clamp01(np.asarray(model.rho_hh(4096)).reshape(3))


def _fresnel_colour(params):
    """Normal-incidence Fresnel reflectance (the colour a Fresnel-less Cycles lobe can carry)."""
    bxdf = dependency.require()
    kind = params.get("fresnel", "none")
    if kind == "conductor":
        return np.asarray(bxdf.fresnel_conductor(1.0, params["eta"], params["k"]),
                          dtype=float).reshape(3)
    if kind == "dielectric":
        return np.full(3, float(bxdf.fresnel_dielectric(1.0, params["eta_i"], params["eta_t"])))
    return np.ones(3)


def _microfacet(params):
    distribution = params.get("distribution", "ggx")
    notes, exact = [], True
    if distribution in ("ggx", "beckmann"):
        ax, ay = float(params["alpha_x"]), float(params["alpha_y"])
        cycles_distribution = "GGX" if distribution == "ggx" else "BECKMANN"
    else:  # blinn, ashikhmin_shirley: exponent(s) → Beckmann-equivalent widths
        exact = False
        if distribution == "blinn":
            ax = ay = alpha_from_exponent(params["exponent"])
            cycles_distribution = "BECKMANN"
            notes.append(f"Blinn exponent {params['exponent']:g} → Beckmann α = √(2/(n+2)) = {ax:.4g}")
        else:
            ax, ay = alpha_from_exponent(params["exponent_x"]), alpha_from_exponent(params["exponent_y"])
            cycles_distribution = "ASHIKHMIN_SHIRLEY"
            notes.append(f"Ashikhmin–Shirley exponents → α = √(2/(n+2)) = ({ax:.4g}, {ay:.4g}); "
                         "Cycles' node has no Fresnel, diffuse or shadowing term")
    if max(ax, ay) > 1.0:
        exact = False
        notes.append("Cycles clamps α to 1")
        ax, ay = min(ax, 1.0), min(ay, 1.0)
    roughness, anisotropy = roughness_anisotropy(ax, ay)
    if abs(anisotropy) > 0.99:
        exact = False
        notes.append(f"anisotropy {anisotropy:.3f} clamped to ±0.99 by Cycles")
    if params.get("shadowing", "smith") != "smith":
        exact = False
        notes.append("V-groove shadowing → Cycles' separable Smith")
    color = np.asarray(params.get("reflectance", (1, 1, 1)), dtype=float)
    if params.get("fresnel", "none") != "none":
        exact = False
        f0 = _fresnel_colour(params)
        color = color * f0
        notes.append(f"{params['fresnel']} Fresnel → constant colour F(0°) = "
                     f"({f0[0]:.3f}, {f0[1]:.3f}, {f0[2]:.3f}); Cycles' Glossy has F = 1")
    if distribution == "beckmann" and ax != ay:
        notes.append("Cycles 3.4 samples anisotropic Beckmann with (αx, αx): indirect light is biased")
    isotropic = ax == ay
    text = (f"{distribution} αx={ax:.4g} αy={ay:.4g} → roughness = (αx·αy)^¼ = {roughness:.4g}"
            + ("" if isotropic else f", anisotropy = {anisotropy:.4g}"))
    inputs = {"Color": _rgba(_clamp01(color)), "Roughness": roughness}
    if not isotropic or cycles_distribution == "ASHIKHMIN_SHIRLEY":
        inputs["Anisotropy"] = anisotropy
        node = "ShaderNodeBsdfAnisotropic"
    else:
        node = "ShaderNodeBsdfGlossy"
    diffuse = tuple(params.get("diffuse", (0.0, 0.0, 0.0)))
    if max(diffuse) > 0.0:
        notes.append("Lambertian term diffuse/π: Diffuse BSDF added to the lobe (Add Shader)")
    return Mapping(node, EXACT if exact else APPROXIMATE, "; ".join([text] + notes), inputs,
                   {"distribution": cycles_distribution}, diffuse if max(diffuse) > 0.0 else None)


def principled_socket(param):
    """The Principled BSDF socket of a cycles_principled parameter (snake_case of its name)."""
    return "IOR" if param == "ior" else param.replace("_", " ").title()


def _principled(params):
    """cycles_principled → Cycles' own Principled BSDF, every parameter on its socket."""
    inputs = {}
    for key, value in params.items():
        if key == "distribution":
            continue
        inputs[principled_socket(key)] = _rgba(value) if isinstance(value, (tuple, list)) else float(value)
    subsurface = float(params["subsurface"])
    text = (f"Principled BSDF, {params['distribution']}, every input on its socket; Cycles' own "
            "closures")
    if subsurface > 0.0:
        text += (f"; subsurface {subsurface:g}: BxDF Lab mixes the subsurface colour into the "
                 "diffuse (Cycles' rule after a diffuse bounce), Cycles scatters below the surface "
                 "on camera paths")
    return Mapping("ShaderNodeBsdfPrincipled", APPROXIMATE if subsurface > 0.0 else EXACT, text,
                   inputs, {"distribution": params["distribution"].upper()})


# Models that are a Cycles node exactly: node type and {socket: registry parameter}.
_CYCLES_NODES = {
    "cycles_glass": ("ShaderNodeBsdfGlass", {"Color": "color", "Roughness": "roughness",
                                             "IOR": "ior"}),
    "cycles_refraction": ("ShaderNodeBsdfRefraction", {"Color": "color", "Roughness": "roughness",
                                                       "IOR": "ior"}),
    "cycles_translucent": ("ShaderNodeBsdfTranslucent", {"Color": "color"}),
    "cycles_transparent": ("ShaderNodeBsdfTransparent", {"Color": "color"}),
    "cycles_velvet": ("ShaderNodeBsdfVelvet", {"Color": "color", "Sigma": "sigma"}),
}


def mapping_for(name, params, model):
    """The Mapping for model `name` with validated `params` (`model` is the bxdf object)."""
    if name == "lambertian":
        return Mapping("ShaderNodeBsdfDiffuse", EXACT, "Lambert: Diffuse BSDF, roughness 0",
                       {"Color": _rgba(params["reflectance"]), "Roughness": 0.0})
    if name == "lambertian_transmission":
        return Mapping("ShaderNodeBsdfTranslucent", EXACT, "Lambertian transmission: Translucent BSDF",
                       {"Color": _rgba(params["transmittance"])})
    if name == "cycles_oren_nayar":
        return Mapping("ShaderNodeBsdfDiffuse", EXACT,
                       f"Cycles' Oren–Nayar: Diffuse BSDF, roughness {params['roughness']:g}",
                       {"Color": _rgba(params["color"]), "Roughness": float(params["roughness"])})
    if name == "oren_nayar":
        sigma_c, color, a, b = classic_oren_nayar(params["reflectance"], params["sigma"])
        return Mapping("ShaderNodeBsdfDiffuse", APPROXIMATE,
                       f"classic Oren–Nayar σ={params['sigma']:g}° (A={a:.4g}, B={b:.4g}) → Cycles' "
                       f"improved Oren–Nayar roughness B/A = {sigma_c:.4g}, colour scaled to match A; "
                       "differs where cos(φi−φo) < 0", {"Color": _rgba(color), "Roughness": sigma_c})
    if name == "microfacet":
        return _microfacet(params)
    if name == "cycles_glossy":
        anisotropy = float(params["anisotropy"])
        inputs = {"Color": _rgba(params["color"]), "Roughness": float(params["roughness"])}
        node = "ShaderNodeBsdfGlossy"
        if anisotropy != 0.0 and params["distribution"] != "sharp":  # a mirror has no anisotropy
            inputs["Anisotropy"] = anisotropy
            node = "ShaderNodeBsdfAnisotropic"
        return Mapping(node, EXACT,
                       f"Cycles' own {params['distribution']}: roughness {params['roughness']:g}, "
                       f"anisotropy {anisotropy:g}", inputs,
                       {"distribution": params["distribution"].upper()})
    if name == "cycles_refraction" and params["distribution"] == "multi_ggx":
        return Mapping("ShaderNodeBsdfRefraction", APPROXIMATE,
                       f"multiscatter refraction (the multiscatter Glass walk's transmitted part, "
                       f"Fresnel included) → Refraction BSDF, GGX, roughness "
                       f"{float(params['roughness']):g}, IOR {float(params['ior']):g}: Blender 3.4's "
                       "Refraction node has no multiscatter GGX; it scatters once and has no "
                       "Fresnel loss", {"Color": _rgba(params["color"]),
                                        "Roughness": float(params["roughness"]),
                                        "IOR": float(params["ior"])}, {"distribution": "GGX"})
    if name in _CYCLES_NODES:
        node, sockets = _CYCLES_NODES[name]
        inputs = {socket: (_rgba(params[key]) if socket == "Color" else float(params[key]))
                  for socket, key in sockets.items()}
        settings = ({"distribution": params["distribution"].upper()}
                    if "distribution" in params else {})
        return Mapping(node, EXACT, f"Cycles' own {node[len('ShaderNodeBsdf'):]} BSDF: "
                       + ", ".join(f"{k} {v}" for k, v in sorted(params.items())), inputs, settings)
    if name == "specular_reflection":
        fresnel = _fresnel_colour(params)
        exact = params.get("fresnel", "none") == "none"
        return Mapping("ShaderNodeBsdfGlossy", EXACT if exact else APPROXIMATE,
                       "mirror: Glossy BSDF, sharp" + ("" if exact else
                                                       f"; {params['fresnel']} Fresnel → F(0°) colour"),
                       {"Color": _rgba(_clamp01(np.asarray(params["reflectance"]) * fresnel)),
                        "Roughness": 0.0}, {"distribution": "SHARP"})
    if name == "fresnel_specular":
        ior = float(params["eta_t"]) / float(params["eta_i"])
        same = tuple(params["reflectance"]) == tuple(params["transmittance"])
        return Mapping("ShaderNodeBsdfGlass", EXACT if same else APPROXIMATE,
                       f"glass: Glass BSDF, sharp, IOR = ηt/ηi = {ior:.4g}" +
                       ("" if same else "; one colour for reflection and refraction (transmittance)"),
                       {"Color": _rgba(params["transmittance"]), "Roughness": 0.0, "IOR": ior},
                       {"distribution": "SHARP"})
    if name in ("specular_transmission", "microfacet_transmission"):
        ior = float(params["eta_t"]) / float(params["eta_i"])
        alpha = math.sqrt(float(params.get("alpha_x", 0.0)) * float(params.get("alpha_y", 0.0)))
        return Mapping("ShaderNodeBsdfRefraction", APPROXIMATE,
                       f"Refraction BSDF IOR {ior:.4g}, roughness √α = {math.sqrt(alpha):.4g}; "
                       "Cycles' Refraction BSDF has no Fresnel factor",
                       {"Color": _rgba(params["transmittance"]), "Roughness": math.sqrt(alpha),
                        "IOR": ior},
                       {"distribution": str(params.get("distribution", "sharp")).upper()
                        if alpha > 0 else "SHARP"})
    if name == "cycles_principled":
        return _principled(params)
    # Anything else (Lafortune fits, measured data, future models): Principled with the model's
    # hemispherical albedo as base colour.
    albedo = _albedo_colour(model)
    return Mapping("ShaderNodeBsdfPrincipled", APPROXIMATE,
                   f"{name}: no Cycles closure; Principled BSDF, base colour = hemispherical albedo "
                   f"({albedo[0]:.3f}, {albedo[1]:.3f}, {albedo[2]:.3f}), specular 0",
                   {"Base Color": _rgba(albedo), "Specular": 0.0, "Roughness": 1.0})


def set_up(material):
    """Replaces `material`'s node tree with the closest Cycles BSDF; stores and returns
    (label, mapping text). ValueError if the material's parameters are invalid."""
    model = api.make(material)
    name, params = api.describe(material)
    mapping = mapping_for(name, dict(model.params), model)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    output.location = (300, 0)
    bsdf = nodes.new(mapping.node)
    bsdf.label = f"BxDF Lab {name} ({mapping.label})"
    for key, value in mapping.settings.items():
        setattr(bsdf, key, value)
    for key, value in mapping.inputs.items():
        bsdf.inputs[key].default_value = value
    surface = bsdf.outputs[0]
    if mapping.diffuse is not None:  # closures add in Cycles: Lambert + lobe is still exact
        diffuse = nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = _rgba(mapping.diffuse)
        diffuse.inputs["Roughness"].default_value = 0.0
        diffuse.location = (-200, -200)
        add = nodes.new("ShaderNodeAddShader")
        add.location = (150, 0)
        material.node_tree.links.new(diffuse.outputs[0], add.inputs[0])
        material.node_tree.links.new(bsdf.outputs[0], add.inputs[1])
        surface = add.outputs[0]
    material.node_tree.links.new(surface, output.inputs["Surface"])
    material.bxdf_lab.cycles_label = mapping.label
    material.bxdf_lab.cycles_mapping = mapping.text
    return mapping.label, mapping.text
