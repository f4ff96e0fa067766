"""Refraction BSDF → `cycles_refraction` (the refraction lobe alone)."""

from .registry_params import from_sockets

BL_IDNAMES = ("ShaderNodeBsdfRefraction",)


def closures(scope, node, weight):
    params = from_sockets(scope, "cycles_refraction", exclude={"Normal", "Weight"})
    params["distribution"] = node.distribution.lower()
    scope.add_closure("cycles_refraction", weight, params, normal=scope.normal(), count=1)
