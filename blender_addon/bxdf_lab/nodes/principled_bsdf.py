"""Principled BSDF → `cycles_principled` (parameters by their registry names), plus the Emission
closure and the Transparent mix that Cycles adds for its Emission and Alpha inputs
(PrincipledBsdfNode::expand)."""

from . import emission
from . import graph as g
from .registry_params import from_sockets

BL_IDNAMES = ("ShaderNodeBsdfPrincipled",)
MODEL = "cycles_principled"
# Inputs that are not registry parameters: translated below or reported.
SPECIAL = {"Emission", "Emission Strength", "Alpha", "Normal", "Clearcoat Normal", "Tangent",
           "Subsurface Radius", "Subsurface IOR", "Subsurface Anisotropy", "Weight"}
CUTOFF = 1e-5  # CLOSURE_WEIGHT_CUTOFF (Cycles' kernel/types.h)


def closures(scope, node, weight):
    graph = scope.graph
    alpha = scope.input("Alpha", "float")
    if g.is_reference(alpha) or g.to_float(alpha) != 1.0:
        alpha = graph.saturate(alpha)
        scope.add_closure("cycles_transparent", graph.multiply(weight, graph.one_minus(alpha)),
                          {"color": (1.0, 1.0, 1.0)}, lobes=[("transparent", 1, True)], count=1)
        weight = graph.multiply(weight, alpha)
    emission.closures(scope, node, weight)  # as Cycles' expand: Emission, Emission Strength

    params = from_sockets(scope, MODEL, exclude=SPECIAL)
    params["distribution"] = node.distribution.lower()
    subsurface = params.get("subsurface", 0.0)
    if g.is_reference(subsurface) or g.to_float(subsurface) > CUTOFF:
        scope.warn("subsurface scattering is rendered as Cycles renders it after a diffuse "
                   "bounce: a diffuse lobe whose colour is mixed towards Subsurface Color")
    if scope.linked("Clearcoat Normal"):
        scope.warn("Clearcoat Normal is not translated; the clearcoat uses the Normal input")
    if scope.linked("Tangent"):
        scope.warn("the Tangent input is not translated; Cycles' default tangent (around the "
                   "object's Z axis) is used")
    scope.add_closure(MODEL, weight, params, normal=scope.normal(), lobes=lobes(params), count=8)


def _active(value, test):
    """Whether a lobe condition holds: always assumed for a per-hit (referenced) value."""
    return True if g.is_reference(value) else test(value)


def lobes(params):
    """Cycles' allocation order of the Principled lobes (svm/closure.h), with each lobe's slot
    cost (a MicrofacetExtra takes one more slot) and whether constant inputs rule it out."""
    def value(name, default=0.0):
        return params.get(name, default)

    metallic, transmission = value("metallic"), value("transmission")
    if g.is_constant(metallic) and g.is_constant(transmission):
        m = min(max(g.to_float(metallic), 0.0), 1.0)
        t = min(max(g.to_float(transmission), 0.0), 1.0)
        diffuse_weight, final_transmission = (1 - m) * (1 - t), t * (1 - m)
    else:
        diffuse_weight = final_transmission = {"node": -1, "out": "per hit"}
    specular_weight = (1.0 - final_transmission if g.is_constant(final_transmission)
                       else final_transmission)
    base = value("base_color", (0.8, 0.8, 0.8))
    roughness = value("roughness", 0.5)
    over = lambda v: _active(v, lambda x: g.to_float(x) > CUTOFF)
    single_glass = (params.get("distribution") == "ggx" or
                    _active(roughness, lambda r: g.to_float(r) <= 5e-2))
    # Cycles tests the base colour's channel average (of the colour mixed towards Subsurface
    # Color, which a subsurface of 0 leaves as the base colour).
    base_average = _active(base, lambda c: sum(g.to_triple(c)) / 3.0 > CUTOFF)
    out = [("diffuse", 1, over(diffuse_weight) and base_average),
           ("sheen", 1, over(diffuse_weight) and over(value("sheen"))),
           ("specular", 2, over(specular_weight) and (over(value("specular", 0.5)) or
                                                      over(metallic)))]
    if single_glass:
        out += [("transmission reflection", 2, over(final_transmission)),
                ("transmission refraction", 1, over(final_transmission))]
    else:
        out += [("transmission", 2, over(final_transmission))]
    out.append(("clearcoat", 2, over(value("clearcoat"))))
    return out
