"""Glass BSDF → `cycles_glass` (Fresnel-weighted reflection and refraction)."""

from .registry_params import from_sockets

BL_IDNAMES = ("ShaderNodeBsdfGlass",)


def closures(scope, node, weight):
    params = from_sockets(scope, "cycles_glass", exclude={"Normal", "Weight"})
    params["distribution"] = node.distribution.lower()
    lobes = ([("glass", 2, True)] if params["distribution"] == "multi_ggx"
             else [("reflection", 1, True), ("refraction", 1, True)])
    scope.add_closure("cycles_glass", weight, params, normal=scope.normal(), lobes=lobes, count=2)
