"""Which engine pairings are `exact` (the same formula on both sides: the diff must be noise) and
which `approximate` (a best mapping: the diff is the finding). Facts from reference/renderers.md:

- Lambert is exact everywhere (POV-Ray through the light calibration of engine_setup).
- Cycles' own Oren-Nayar (`cycles_oren_nayar`), Glossy (`cycles_glossy`: GGX/Beckmann, separable
  Smith, F = 1; Ashikhmin-Shirley; multiscatter GGX in expectation), Glass, Refraction,
  Translucent, Transparent and Velvet (`cycles_*`) are exact between Cycles, BXDF_LAB and the
  analytic image (both from the core's f).
- Every model is exact between BXDF_LAB and ANALYTIC (both evaluate the core's f).
- A Blender node material (scene_spec.NODES) is exact between BXDF_LAB and Cycles: the add-on
  translates the node tree Cycles renders (the driver records the translation's coverage as the
  add-on's label, which the report checks against this).
- Everything else is approximate; so is any POV-Ray global illumination (radiosity is not a path
  tracer), any POV-Ray render of soft lights (sphere, spot radius, sun angle, area lights) or an
  environment-map world (render_povray exports neither as Cycles has them), and any scene without
  analytic truth where a model is approximate in one engine.
- A measured Cycles quirk (cycles_quirks) makes a CYCLES pairing approximate; the report names
  it and the summary gives its size (Σa/Σb).
- Where the analytic image is not the model's converged image (analytic_limits: multiscatter
  GGX, whose f is a 16-walk estimate evaluated once per pixel there) an ANALYTIC pairing is
  approximate."""
from __future__ import annotations

from itertools import combinations

from . import ALL_ENGINES
from .scene_spec import NODES, SceneSpec, soft_lighting

CORE = {"BXDF_LAB", "ANALYTIC"}
EXACT_IN = {
    "lambertian": {"BXDF_LAB", "ANALYTIC", "CYCLES", "POVRAY_RENDER"},
    "cycles_oren_nayar": CORE | {"CYCLES"},
    "cycles_glossy": CORE | {"CYCLES"},
    NODES: {"BXDF_LAB", "CYCLES"},
    "cycles_principled": CORE | {"CYCLES"},  # the sweeps use no subsurface (approximate then)
    "cycles_glass": CORE | {"CYCLES"},
    "cycles_refraction": CORE | {"CYCLES"},
    "cycles_translucent": CORE | {"CYCLES"},
    "cycles_transparent": CORE | {"CYCLES"},
    "cycles_velvet": CORE | {"CYCLES"},
}


def exact_engines(model: str) -> set:
    return EXACT_IN.get(model, CORE)


def cycles_quirks(spec: SceneSpec, material) -> list:
    """Cycles behaviours (measured, README) that keep its image of `material` in `spec` from
    the model's converged image: a pairing with CYCLES is then approximate, with these reasons."""
    params = material.params
    quirks = []
    # Multiscatter GGX: Cycles' eval walk and sampling walk disagree (white reflection at α 0.64:
    # 0.922 by eval, 1.000 by the walk); BXDF_LAB evaluates with the one and samples with the
    # other as Cycles does, and weighs them by the same pdf (mf_ggx_pdf) for reflection. For
    # the glass its MIS pdf is the normalised blend, not Cycles' mf_glass_pdf, so where a light
    # is found both ways the two walks are mixed in other proportions.
    if is_multiscatter_glass(material) and soft_lighting(spec):
        quirks.append(f"{material.name}: Cycles weighs its multiscatter glass's eval and "
                      "sampling walks (which disagree) by mf_glass_pdf in MIS, BXDF_LAB by a "
                      "normalised pdf, which light found by both light and BSDF sampling shows")
    # Rough refraction: Cycles draws it from its facets alone and so do we, but Cycles' MIS pdf
    # (its eval's) is not zero on the pairs no facet reaches, where light sampling alone finds
    # light; BXDF_LAB's is its cover density there, so each keeps another part of that light.
    if has_rough_refraction(material) and (soft_lighting(spec) or any(spec.world_color)):
        quirks.append(f"{material.name}: Cycles weighs the light sampling finds on the rough "
                      "refraction's pairs that no facet reaches by its eval's pdf, which its "
                      "sampler never realises; BXDF_LAB by its cover density")
    # Clearcoat: Cycles draws GGX's visible normals and weights them by a GTR1 pdf, which
    # biases what BSDF sampling finds; BXDF_LAB draws and weights its samples the same way, but
    # its MIS pdf is the mixture's density, so where a light is found both ways the two
    # estimates are mixed in other proportions.
    if (material.model == "cycles_principled" and params.get("clearcoat", 0.0) > 0.0
            and params.get("clearcoat_roughness", 0.03) ** 4 > 1e-7 and soft_lighting(spec)):
        quirks.append(f"{material.name}: Cycles weighs its clearcoat's BSDF samples (GGX "
                      "visible normals weighted by a GTR1 pdf) against light sampling by that "
                      "pdf in MIS, BXDF_LAB by the mixture's density, which light found by both "
                      "light and BSDF sampling shows")
    return quirks


def is_multiscatter(material) -> bool:
    return (material.model in ("cycles_glossy", "cycles_glass", "cycles_refraction",
                               "cycles_principled")
            and material.params.get("distribution") == "multi_ggx")


def has_rough_refraction(material) -> bool:
    """A rough (not singular) GGX or Beckmann refraction closure, as the models build it:
    Glass and Refraction with roughness² > ~3e-4, the Principled's glass when it is not one
    multiscatter closure (cycles_glass.h, cycles_principled.h)."""
    params = material.params
    distribution = params.get("distribution", "ggx")
    if material.model in ("cycles_glass", "cycles_refraction"):
        roughness = params.get("roughness", 0.0)
        return distribution in ("ggx", "beckmann") and roughness ** 4 > 1e-7
    if material.model == "cycles_principled":
        transmission = params.get("transmission", 0.0) * (1.0 - params.get("metallic", 0.0))
        if transmission <= 1e-5:
            return False
        roughness = params.get("roughness", 0.5)
        if distribution == "multi_ggx":
            # One multiscatter glass closure above 0.05, below it the refraction at roughness.
            return roughness <= 5e-2 and roughness ** 4 > 1e-7
        refraction = 1.0 - (1.0 - roughness) * (1.0 - params.get("transmission_roughness", 0.0))
        return refraction ** 4 > 1e-7
    return False


def is_multiscatter_glass(material) -> bool:
    return is_multiscatter(material) and (
        material.model in ("cycles_glass", "cycles_refraction")
        or (material.model == "cycles_principled" and material.params.get("transmission", 0.0) > 0.0
            and material.params.get("metallic", 0.0) < 1.0))


def analytic_limits(material) -> list:
    """Why the analytic image of `material` is not its converged image (then a pairing with
    ANALYTIC is approximate)."""
    if is_multiscatter(material):
        # BXDF_LAB salts the walks per sample (multiscatter_ggx.h), so its pixels converge to
        # the walk's expectation, as Cycles' do; the analytic image evaluates f once per pixel.
        return [f"{material.name}: the analytic image evaluates multiscatter GGX's f, a 16-walk "
                "estimate, once per pixel: its error (relative RMS 0.24 of f for reflection at "
                "α 0.7, 0.12 for glass at α 0.6) is fixed per pixel, not noise"]
    return []


def label(spec: SceneSpec, a: str, b: str) -> str:
    if "POVRAY_RENDER" in (a, b) and (spec.povray_radiosity or soft_lighting(spec)):
        return "approximate"
    for material in spec.materials():
        engines = exact_engines(material.model)
        if a not in engines or b not in engines:
            return "approximate"
        if "CYCLES" in (a, b) and cycles_quirks(spec, material):
            return "approximate"
        if "ANALYTIC" in (a, b) and analytic_limits(material):
            return "approximate"
    return "exact"


def approximations(spec: SceneSpec, a: str, b: str) -> list:
    """Why a pairing is approximate, one line per reason."""
    reasons = []
    if spec.povray_radiosity and "POVRAY_RENDER" in (a, b):
        reasons.append("POV-Ray's global illumination is radiosity (irradiance caching), "
                       "not path tracing")
    if "POVRAY_RENDER" in (a, b):
        reasons.extend(f"POV-Ray's export has no {kind} as Cycles renders it"
                       for kind in soft_lighting(spec))
    for material in spec.materials():
        engines = exact_engines(material.model)
        for engine in (a, b):
            if engine not in engines:
                reasons.append(f"{material.name}: {engine} has no '{material.model}'; "
                               "it renders the closest mapping")
        if "CYCLES" in (a, b):
            reasons.extend(cycles_quirks(spec, material))
        if "ANALYTIC" in (a, b):
            reasons.extend(analytic_limits(material))
    return reasons


def pairs(engines) -> list:
    """Every pair, ANALYTIC first when present (the reference is the second element `b`)."""
    order = [e for e in ("ANALYTIC", "CYCLES", "BXDF_LAB", "POVRAY_RENDER") if e in engines]
    assert set(order) == set(engines) and set(order) <= set(ALL_ENGINES), engines
    return [(y, x) for x, y in combinations(order, 2)]
