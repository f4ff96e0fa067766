"""Anisotropic BSDF → `cycles_glossy` with its anisotropy, the tangent rotated about the normal
by Rotation turns (the closure's `rotation`) and a linked Tangent input as the closure's
`tangent`."""

from . import graph as g
from .glossy_bsdf import slots
from .registry_params import from_sockets

BL_IDNAMES = ("ShaderNodeBsdfAnisotropic",)


def closures(scope, node, weight):
    params = from_sockets(scope, "cycles_glossy", exclude={"Normal", "Tangent", "Rotation", "Weight"})
    params["distribution"] = node.distribution.lower()
    rotation = scope.input("Rotation", "float")
    tangent = scope.input("Tangent", "triple") if scope.linked("Tangent") else None
    n = slots(params["distribution"])
    scope.add_closure("cycles_glossy", weight, params, normal=scope.normal(),
                      lobes=[("glossy", n, True)], count=n,
                      rotation=None if g.is_constant(rotation) and rotation == 0.0 else rotation,
                      tangent=tangent if g.is_reference(tangent) else None)
